// Optimized twins of generate_luma_template / generate_chroma_template
// (grain_template_generation.hpp, the scalar reference of AV1 spec 7.18.3.3): the same
// templates, bit for bit, with the Gaussian fill drawing eight random numbers per LFSR
// update and the auto-regressive filter's rows-above taps in vector lanes
// (simd/grain_ar_filter.hpp).
// Tested equal to the reference on random parameters for every dispatch target
// (tests/unit/simd_av1_template_equivalence_test.cpp).
#pragma once
#include "av1/grain_template_generation.hpp"

namespace filmgrain::av1 {

void generate_luma_template_optimized(const Av1FilmGrainParams& p, int bit_depth, GrainTemplate& out);
void generate_chroma_template_optimized(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                                        int subsampling_y, const GrainTemplate& luma, GrainTemplate& out);
// Cb and Cr together (the same templates as two generate_chroma_template_optimized calls),
// their AR filters interleaved; a plane without grain gets its all-zero template.
void generate_chroma_templates_optimized(const Av1FilmGrainParams& p, int bit_depth, int subsampling_x,
                                         int subsampling_y, const GrainTemplate& luma, GrainTemplate& cb,
                                         GrainTemplate& cr);

}  // namespace filmgrain::av1

// Grain templates of AV1 spec 7.18.3.3: a block of Gaussian noise per plane,
// shaped by a causal auto-regressive filter. Blocks of the picture later copy
// random windows out of these templates (block_synthesis).
#pragma once
#include <cstdint>
#include <vector>

#include "filmgrain/av1_params.hpp"

namespace filmgrain::av1 {

// Luma template: 73 rows x 82 columns. The 32x32 blocks (34x34 with overlap)
// take windows starting at 9 + 2*offset with offset 0..15, and the AR filter
// needs a 3-sample causal border, hence 82 = 9 + 2*15 + 34 + margin.
inline constexpr int kLumaTemplateWidth = 82;
inline constexpr int kLumaTemplateHeight = 73;
// Subsampled chroma dimensions (4:2:0 / 4:2:2 halve the corresponding axis).
inline constexpr int kSubsampledTemplateWidth = 44;
inline constexpr int kSubsampledTemplateHeight = 38;
// Border the AR filter leaves untouched on the top, left and right.
inline constexpr int kArPadding = 3;

// Grain is kept in a signed range one bit wider than 8-bit video at the frame's bit depth:
// [-128 << (bd-8), (128 << (bd-8)) - 1].
struct GrainRange {
    int min, max;
};
inline GrainRange grain_range(int bit_depth) {
    const int ctr = 128 << (bit_depth - 8);
    return {-ctr, ctr - 1};
}

struct GrainTemplate {
    int width = 0;
    int height = 0;
    std::vector<int16_t> samples;  // row-major, width*height

    int at(int y, int x) const { return samples[static_cast<std::size_t>(y) * width + x]; }
    int16_t& ref(int y, int x) { return samples[static_cast<std::size_t>(y) * width + x]; }
};

// LumaGrain (7.18.3.3). All zero when num_y_points == 0 (the spec then draws no
// random numbers, and no luma grain is ever used).
GrainTemplate generate_luma_template(const Av1FilmGrainParams& p, int bit_depth);
// The same into `out`, reusing its storage.
void generate_luma_template(const Av1FilmGrainParams& p, int bit_depth, GrainTemplate& out);

// CbGrain (plane 1) or CrGrain (plane 2). Sized by the subsampling; includes the
// co-located luma term of the AR filter when num_y_points > 0. Zero when the
// plane has no scaling points and chroma_scaling_from_luma is 0.
GrainTemplate generate_chroma_template(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                                       int subsampling_y, const GrainTemplate& luma);
void generate_chroma_template(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                              int subsampling_y, const GrainTemplate& luma, GrainTemplate& out);

}  // namespace filmgrain::av1

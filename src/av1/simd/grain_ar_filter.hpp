// Optimized twin of the auto-regressive filter of AV1 spec 7.18.3.3 (the loops at the end
// of generate_luma_template / generate_chroma_template in grain_template_generation.cpp),
// Highway with runtime dispatch. Bit-equal to that scalar reference on every target
// (tests/unit/simd_av1_template_equivalence_test.cpp).
#pragma once
#include <cstdint>

namespace filmgrain::av1::simd {

struct ArFilterJob {
    int16_t* grain = nullptr;  // the white-noise template, filtered in place
    int width = 0, height = 0;
    // Coefficients minus 128 in the spec's scan order: lag*(2*lag+1) for the rows above,
    // lag for the left neighbours, then (chroma only) the luma coefficient.
    const int* coeffs = nullptr;
    int lag = 0;    // ar_coeff_lag, 0..3
    int shift = 6;  // ar_coeff_shift_minus_6 + 6
    // Luma template for chroma's co-located luma term; null for luma, and for chroma
    // when num_y_points == 0 (the spec then leaves the term out).
    const int16_t* luma = nullptr;
    int luma_width = 0;
    int subsampling_x = 0, subsampling_y = 0;
    int grain_min = 0, grain_max = 0;
};

// Filters rows [3, height) and columns [3, width - 3) of job.grain, as the reference does.
void ar_filter_template(const ArFilterJob& job);
// Both templates, which must have the same size and lag (Cb and Cr of one frame): the same
// results as two ar_filter_template calls, with the two serial chains interleaved.
void ar_filter_template_pair(const ArFilterJob& first, const ArFilterJob& second);

}  // namespace filmgrain::av1::simd

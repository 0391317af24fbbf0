// Noise application of AV1 spec 7.18.3.5: the scaled noise is added to each
// sample and the result clipped, with chroma scaling driven by a mix of the
// co-located luma and the chroma sample itself.
#pragma once
#include <algorithm>
#include <cstdint>

#include "av1/scaling_lookup.hpp"

namespace filmgrain::av1 {

struct ClipLimits {
    int min_value = 0;
    int max_luma = 255;
    int max_chroma = 255;
};

// Restricted range is 16..235 for luma and 16..240 for chroma (at 8 bits,
// shifted up for higher depths). With MC_IDENTITY (matrix_coefficients == 0)
// the "chroma" planes carry R/B colour channels, which share luma's range, so
// the chroma limit is 235 as well.
ClipLimits clip_limits(bool clip_to_restricted_range, int bit_depth, int matrix_coefficients);

// How a chroma sample picks its scaling index (the `merged` value of the spec).
struct ChromaScalingIndex {
    bool from_luma = false;  // chroma_scaling_from_luma: use the luma average
    int mult = 0;            // cb_mult - 128
    int luma_mult = 0;       // cb_luma_mult - 128
    int offset = 0;          // cb_offset - 256
};

inline int round2_signed(int x, int n) { return (x + (1 << (n - 1))) >> n; }

// One luma row: out = clip(src + Round2(scale(src) * noise, scaling_shift)).
template <typename Pixel>
void blend_luma_row(const Pixel* src, Pixel* dst, const int16_t* noise, int width, const ScalingLookup& scaling,
                    int scaling_shift, int min_value, int max_value) {
    for (int x = 0; x < width; ++x) {
        const int orig = src[x];
        const int n = round2_signed(scaling(orig) * noise[x], scaling_shift);
        dst[x] = static_cast<Pixel>(std::clamp(orig + n, min_value, max_value));
    }
}

// The luma co-sited with chroma column x when chroma is subsampled horizontally: the pair's
// average, its right sample clamped to the picture (odd widths repeat the last column).
template <typename Pixel>
int co_sited_luma(const Pixel* luma, int luma_width, int x) {
    return (luma[2 * x] + luma[std::min(2 * x + 1, luma_width - 1)] + 1) >> 1;
}

// The scaling index (`merged`) of chroma sample x with value `orig`. `luma` is the clean
// (pre-grain) luma row co-sited with the chroma row (averaged in pairs by co_sited_luma with
// horizontal subsampling).
template <typename Pixel>
int chroma_scaling_index(const Pixel* luma, int luma_width, int x, int subsampling_x, int orig,
                         const ChromaScalingIndex& index, int bit_depth) {
    const int average_luma = subsampling_x ? co_sited_luma(luma, luma_width, x) : luma[x];
    if (index.from_luma) return average_luma;
    const int combined = average_luma * index.luma_mult + orig * index.mult;
    return std::clamp((combined >> 6) + index.offset * (1 << (bit_depth - 8)), 0, (1 << bit_depth) - 1);
}

// co_sited_luma for chroma columns 0..width-1: both chroma planes index their scaling by it,
// so the optimized synthesis makes it once per row above 8 bits and hands it to both as
// unsubsampled luma.
template <typename Pixel>
void co_sited_luma_row(const Pixel* luma, int luma_width, int width, Pixel* out) {
    for (int x = 0; x < width; ++x)
        out[x] = static_cast<Pixel>(co_sited_luma(luma, luma_width, x));
}

// One chroma row (see chroma_scaling_index for `luma`).
template <typename Pixel>
void blend_chroma_row(const Pixel* src, Pixel* dst, const Pixel* luma, int luma_width, const int16_t* noise,
                      int width, int subsampling_x, const ChromaScalingIndex& index, const ScalingLookup& scaling,
                      int scaling_shift, int bit_depth, int min_value, int max_value) {
    for (int x = 0; x < width; ++x) {
        const int orig = src[x];
        const int merged = chroma_scaling_index(luma, luma_width, x, subsampling_x, orig, index, bit_depth);
        const int n = round2_signed(scaling(merged) * noise[x], scaling_shift);
        dst[x] = static_cast<Pixel>(std::clamp(orig + n, min_value, max_value));
    }
}

}  // namespace filmgrain::av1

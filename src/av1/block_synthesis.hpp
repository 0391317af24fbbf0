// Noise image construction of AV1 spec 7.18.3.5: the picture is covered with
// 32x32 luma blocks (16x16 / 16x32 / 32x32 chroma by subsampling), each copying a
// randomly offset window of the grain template. Adjacent blocks overlap by two
// luma samples (one subsampled chroma sample) and, with overlap_flag, the
// overlap is cross-faded: first horizontally inside a 32-row stripe, then
// vertically between stripes.
#pragma once
#include <cstdint>
#include <vector>

#include "av1/grain_template_generation.hpp"

namespace filmgrain::av1 {

inline constexpr int kBlockSize = 32;  // luma samples per block side and per stripe

// Number of 32-luma-sample blocks across the picture and of stripes down it.
inline int num_blocks_across(int luma_width) { return (luma_width + kBlockSize - 1) / kBlockSize; }
inline int num_stripes(int luma_height) { return (luma_height + kBlockSize - 1) / kBlockSize; }

// The overlap cross-fade of 7.18.3.5: the k-th shared column (horizontally) or row
// (vertically) mixes the earlier block's noise with weight old_weight and the later one's
// with new_weight, Round2 by 5, clipped to the grain range because the weights sum to more
// than 32 (the spec boosts the overlap to make up for the variance two averaged independent
// noise fields lose). Two columns or rows are shared at full resolution, one when
// subsampled; (0, 32) past that keeps the later value.
struct OverlapWeights {
    int old_weight, new_weight;
};
constexpr OverlapWeights overlap_weights(int k, int subsampled) {
    if (subsampled) return k == 0 ? OverlapWeights{23, 22} : OverlapWeights{0, 32};
    return k == 0 ? OverlapWeights{27, 17} : OverlapWeights{17, 27};
}
inline int cross_fade(int old_value, int new_value, OverlapWeights w, GrainRange range) {
    const int v = (old_value * w.old_weight + new_value * w.new_weight + 16) >> 5;
    return v < range.min ? range.min : v > range.max ? range.max : v;
}

// One 8-bit random number per block of a stripe, from the stripe's own seed.
// The high nibble is the horizontal template offset, the low nibble the vertical.
// All planes share them.
std::vector<uint8_t> stripe_block_offsets(int grain_seed, int stripe, int blocks_across);
void fill_stripe_block_offsets(int grain_seed, int stripe, int blocks_across, uint8_t* out);

// The spec's noiseStripe for one plane: (34 >> suby) rows, every block written
// with its two extra overlap columns (one when subsampled) and, with
// overlap_flag, blended with the block to its left.
struct NoiseStripe {
    int width = 0;
    int height = 0;
    std::vector<int16_t> samples;
    int at(int y, int x) const { return samples[static_cast<std::size_t>(y) * width + x]; }
};

NoiseStripe build_noise_stripe(const GrainTemplate& tmpl, const std::vector<uint8_t>& offsets, int subsampling_x,
                               int subsampling_y, bool overlap, int bit_depth);

// Final noise of one plane for the rows of stripe `stripe` (32 >> suby rows,
// fewer at the bottom of the picture) and `plane_width` columns: the stripe's
// noiseStripe with, when overlap_flag is set, its first rows (2 luma / 1
// subsampled) blended with the bottom overlap rows of the previous stripe.
struct StripeNoise {
    int width = 0;
    int rows = 0;
    std::vector<int16_t> samples;
    const int16_t* row(int y) const { return samples.data() + static_cast<std::size_t>(y) * width; }
};

StripeNoise build_stripe_noise(const GrainTemplate& tmpl, int grain_seed, int stripe, int luma_width,
                               int plane_width, int plane_height, int subsampling_x, int subsampling_y, bool overlap,
                               int bit_depth);
// The same from the blocks' random bytes of this stripe and of the one above (read only
// with overlap_flag and stripe > 0), as stripe_block_offsets() draws them: `filmgrain verify`
// hands in bytes a mistaken decoder would have used.
StripeNoise build_stripe_noise(const GrainTemplate& tmpl, const std::vector<uint8_t>& offsets,
                               const std::vector<uint8_t>& previous_offsets, int stripe, int plane_width,
                               int plane_height, int subsampling_x, int subsampling_y, bool overlap, int bit_depth);

}  // namespace filmgrain::av1

#include "av1/stripe_block_origins.hpp"

#include <algorithm>

#include "av1/block_synthesis.hpp"
#include "av1/random_number.hpp"

namespace filmgrain::av1 {

int noise_stripe_width(int luma_width, int subsampling_x) {
    const int block_w = kBlockSize >> subsampling_x;
    const int copy_w = (kBlockSize + 2) >> subsampling_x;
    return num_blocks_across(luma_width) * block_w + (copy_w - block_w);
}

void stripe_block_origins(const GrainTemplate& tmpl, int grain_seed, int stripe, int luma_width, int subsampling_x,
                          int subsampling_y, int32_t* origins) {
    RandomNumberGenerator rng(stripe_seed(grain_seed, stripe));
    for (int b = 0; b < num_blocks_across(luma_width); ++b) {
        const int rand = rng.get(8);
        const int offset_x = rand >> 4, offset_y = rand & 15;
        const int tx = subsampling_x ? 6 + offset_x : 9 + offset_x * 2;
        const int ty = subsampling_y ? 6 + offset_y : 9 + offset_y * 2;
        origins[b] = ty * tmpl.width + tx;
    }
}

void overlap_seams(const int16_t* const* block_rows, int count, int subsampling_x, int bit_depth, uint32_t* seams) {
    const int block_w = kBlockSize >> subsampling_x;
    const int gmin = -(128 << (bit_depth - 8)), gmax = (128 << (bit_depth - 8)) - 1;
    auto pack = [](int a, int b) { return uint32_t(uint16_t(a)) | uint32_t(uint16_t(b)) << 16; };
    if (count > 0) seams[0] = pack(block_rows[0][0], block_rows[0][1]);
    for (int b = 1; b < count; ++b) {
        const int16_t* left = block_rows[b - 1] + block_w;
        const int16_t* cur = block_rows[b];
        // Weights as build_noise_stripe (block_synthesis): 27/17 and 17/27 over two columns, 23/22 over one
        // when subsampled.
        const int s0 = subsampling_x ? std::clamp((left[0] * 23 + cur[0] * 22 + 16) >> 5, gmin, gmax)
                                     : std::clamp((left[0] * 27 + cur[0] * 17 + 16) >> 5, gmin, gmax);
        const int s1 = subsampling_x ? cur[1] : std::clamp((left[1] * 17 + cur[1] * 27 + 16) >> 5, gmin, gmax);
        seams[b] = pack(s0, s1);
    }
}

}  // namespace filmgrain::av1

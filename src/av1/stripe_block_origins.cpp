#include "av1/stripe_block_origins.hpp"

#include <algorithm>

#include "av1/block_synthesis.hpp"

namespace filmgrain::av1 {

int noise_stripe_width(int luma_width, int subsampling_x) {
    const int block_w = kBlockSize >> subsampling_x;
    const int copy_w = (kBlockSize + 2) >> subsampling_x;
    return num_blocks_across(luma_width) * block_w + (copy_w - block_w);
}

void stripe_block_origins(const GrainTemplate& tmpl, const uint8_t* offsets, int blocks, int subsampling_x,
                          int subsampling_y, int32_t* origins) {
    for (int b = 0; b < blocks; ++b) {
        const int offset_x = offsets[b] >> 4, offset_y = offsets[b] & 15;
        const int tx = subsampling_x ? 6 + offset_x : 9 + offset_x * 2;
        const int ty = subsampling_y ? 6 + offset_y : 9 + offset_y * 2;
        origins[b] = ty * tmpl.width + tx;
    }
}

simd::BlockNoiseRow kernel_faded_row(int subsampling_x, int bit_depth) {
    simd::BlockNoiseRow row;
    row.block_width = kBlockSize >> subsampling_x;
    row.fade = true;
    for (int k = 0; k < 2; ++k) {
        const OverlapWeights w = overlap_weights(k, subsampling_x);
        row.fade_old[k] = int16_t(w.old_weight), row.fade_new[k] = int16_t(w.new_weight);
    }
    const GrainRange range = grain_range(bit_depth);
    row.gmin = int16_t(range.min), row.gmax = int16_t(range.max);
    return row;
}

void overlap_seams(const int16_t* const* block_rows, int count, int subsampling_x, int bit_depth, uint32_t* seams) {
    const int block_w = kBlockSize >> subsampling_x;
    const GrainRange range = grain_range(bit_depth);
    auto pack = [](int a, int b) { return uint32_t(uint16_t(a)) | uint32_t(uint16_t(b)) << 16; };
    if (count > 0) seams[0] = pack(block_rows[0][0], block_rows[0][1]);
    for (int b = 1; b < count; ++b) {
        const int16_t* left = block_rows[b - 1] + block_w;
        const int16_t* cur = block_rows[b];
        const int s0 = cross_fade(left[0], cur[0], overlap_weights(0, subsampling_x), range);
        const int s1 = subsampling_x ? cur[1] : cross_fade(left[1], cur[1], overlap_weights(1, 0), range);
        seams[b] = pack(s0, s1);
    }
}

}  // namespace filmgrain::av1

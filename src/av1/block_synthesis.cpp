// AV1 spec 7.18.3.5 (add noise synthesis process), noise stripe and noise image parts.
#include "av1/block_synthesis.hpp"

#include <algorithm>

#include "av1/random_number.hpp"

namespace filmgrain::av1 {

std::vector<uint8_t> stripe_block_offsets(int grain_seed, int stripe, int blocks_across) {
    std::vector<uint8_t> out(static_cast<std::size_t>(blocks_across));
    fill_stripe_block_offsets(grain_seed, stripe, blocks_across, out.data());
    return out;
}

void fill_stripe_block_offsets(int grain_seed, int stripe, int blocks_across, uint8_t* out) {
    RandomNumberGenerator rng(stripe_seed(grain_seed, stripe));
    for (int b = 0; b < blocks_across; ++b) out[b] = static_cast<uint8_t>(rng.get(8));
}

NoiseStripe build_noise_stripe(const GrainTemplate& tmpl, const std::vector<uint8_t>& offsets, int subsampling_x,
                               int subsampling_y, bool overlap, int bit_depth) {
    const int block_w = kBlockSize >> subsampling_x;
    const int copy_w = (kBlockSize + 2) >> subsampling_x;  // block plus overlap columns
    const int copy_h = (kBlockSize + 2) >> subsampling_y;
    const int blocks = static_cast<int>(offsets.size());
    NoiseStripe s;
    s.width = blocks * block_w + (copy_w - block_w);
    s.height = copy_h;
    s.samples.assign(static_cast<std::size_t>(s.width) * s.height, 0);
    const GrainRange range = grain_range(bit_depth);

    for (int b = 0; b < blocks; ++b) {
        const int rand = offsets[static_cast<std::size_t>(b)];
        const int offset_x = rand >> 4, offset_y = rand & 15;
        // Windows start past the AR padding (3) plus a further margin; full
        // resolution planes move in steps of 2 so that luma and subsampled
        // chroma windows stay co-sited.
        const int tx = subsampling_x ? 6 + offset_x : 9 + offset_x * 2;
        const int ty = subsampling_y ? 6 + offset_y : 9 + offset_y * 2;
        const int x0 = b * block_w;
        for (int i = 0; i < copy_h; ++i) {
            int16_t* row = s.samples.data() + static_cast<std::size_t>(i) * s.width;
            for (int j = 0; j < copy_w; ++j) {
                int g = tmpl.at(ty + i, tx + j);
                if (overlap && b > 0) {
                    // Columns already written by the left block's overlap.
                    if (j < (2 >> subsampling_x))
                        g = cross_fade(row[x0 + j], g, overlap_weights(j, subsampling_x), range);
                }
                row[x0 + j] = static_cast<int16_t>(g);
            }
        }
    }
    return s;
}

StripeNoise build_stripe_noise(const GrainTemplate& tmpl, int grain_seed, int stripe, int luma_width,
                               int plane_width, int plane_height, int subsampling_x, int subsampling_y, bool overlap,
                               int bit_depth) {
    const int blocks = num_blocks_across(luma_width);
    // The previous stripe's noise is regenerated rather than kept, so that each stripe
    // depends only on (params, stripe index).
    const bool shares_rows = overlap && stripe > 0;
    return build_stripe_noise(tmpl, stripe_block_offsets(grain_seed, stripe, blocks),
                              shares_rows ? stripe_block_offsets(grain_seed, stripe - 1, blocks) : std::vector<uint8_t>{},
                              stripe, plane_width, plane_height, subsampling_x, subsampling_y, overlap, bit_depth);
}

StripeNoise build_stripe_noise(const GrainTemplate& tmpl, const std::vector<uint8_t>& offsets,
                               const std::vector<uint8_t>& previous_offsets, int stripe, int plane_width,
                               int plane_height, int subsampling_x, int subsampling_y, bool overlap, int bit_depth) {
    const int stripe_h = kBlockSize >> subsampling_y;
    StripeNoise out;
    out.width = plane_width;
    out.rows = std::max(0, std::min(stripe_h, plane_height - stripe * stripe_h));
    out.samples.assign(static_cast<std::size_t>(out.width) * out.rows, 0);
    if (out.rows == 0) return out;

    const NoiseStripe cur = build_noise_stripe(tmpl, offsets, subsampling_x, subsampling_y, overlap, bit_depth);
    for (int y = 0; y < out.rows; ++y)
        std::copy_n(cur.samples.data() + static_cast<std::size_t>(y) * cur.width, plane_width,
                    out.samples.data() + static_cast<std::size_t>(y) * out.width);

    if (overlap && stripe > 0) {
        const NoiseStripe prev =
            build_noise_stripe(tmpl, previous_offsets, subsampling_x, subsampling_y, overlap, bit_depth);
        const GrainRange range = grain_range(bit_depth);
        const int overlap_rows = std::min(out.rows, 2 >> subsampling_y);
        for (int i = 0; i < overlap_rows; ++i) {
            int16_t* row = out.samples.data() + static_cast<std::size_t>(i) * out.width;
            for (int x = 0; x < plane_width; ++x) {
                row[x] = static_cast<int16_t>(
                    cross_fade(prev.at(i + stripe_h, x), row[x], overlap_weights(i, subsampling_y), range));
            }
        }
    }
    return out;
}

}  // namespace filmgrain::av1

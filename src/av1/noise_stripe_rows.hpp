// The noise stripe of AV1 spec 7.18.3.5 built row range by row range into caller-owned
// memory: the same values as build_noise_stripe (block_synthesis), without allocation and
// with whole template rows copied at once. The optimized stripe path uses it; a stripe's
// vertical overlap then needs only the two (one) bottom rows of the previous stripe,
// which are rebuilt here instead of the whole previous stripe.
#pragma once
#include <cstddef>
#include <cstdint>

#include "av1/grain_template_generation.hpp"

namespace filmgrain::av1 {

// Width of the noise stripe of a plane: every block plus its overlap columns.
int noise_stripe_width(int luma_width, int subsampling_x);

// Rows [row0, row1) of stripe `stripe`'s noise stripe (0 <= row0 <= row1 <= (34 >> suby))
// into out[(i - row0) * out_stride + x] for x < noise_stripe_width().
void build_noise_stripe_rows(const GrainTemplate& tmpl, int grain_seed, int stripe, int luma_width, int subsampling_x,
                             int subsampling_y, bool overlap, int bit_depth, int row0, int row1, int16_t* out,
                             std::ptrdiff_t out_stride);

}  // namespace filmgrain::av1

namespace filmgrain::av1 {

// Where each block of stripe `stripe` reads the template (7.18.3.5 offsetX/offsetY): the
// index in tmpl.samples of the block's first sample, for the num_blocks_across(luma_width)
// blocks.
void stripe_block_origins(const GrainTemplate& tmpl, int grain_seed, int stripe, int luma_width, int subsampling_x,
                          int subsampling_y, int32_t* origins);

// The first two noise samples of each of `count` blocks in one row after the horizontal
// overlap with the block on the left (columns block_width and block_width + 1 of that
// block's template row), packed low half first; block 0 keeps its own. block_rows[b] is the
// template row block b reads.
void overlap_seams(const int16_t* const* block_rows, int count, int subsampling_x, int bit_depth, uint32_t* seams);

}  // namespace filmgrain::av1

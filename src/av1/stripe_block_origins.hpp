// Where the optimized AV1 path reads each row's noise (7.18.3.5): the template origin of
// every 32x32 block of a stripe, and the samples the horizontal overlap changes. The rows
// themselves are not copied into a noise stripe: the blends read them from the template.
#pragma once
#include <cstddef>
#include <cstdint>

#include "av1/grain_template_generation.hpp"
#include "av1/simd/av1_kernels.hpp"

namespace filmgrain::av1 {

// Width of the noise stripe of a plane: every block plus its overlap columns.
int noise_stripe_width(int luma_width, int subsampling_x);

// Where each of a stripe's `blocks` blocks reads the template (7.18.3.5 offsetX/offsetY)
// from its random byte in `offsets` (stripe_block_offsets, shared by the planes): the index
// in tmpl.samples of the block's first sample.
void stripe_block_origins(const GrainTemplate& tmpl, const uint8_t* offsets, int blocks, int subsampling_x,
                          int subsampling_y, int32_t* origins);

// The constants of a plane's noise rows for the kernels: the block width, the weights of
// the horizontal overlap of a block's first two columns (7.18.3.5) and the grain range, with
// the overlap faded in the kernels (fade set; only up to 10 bits, see BlockNoiseRow). The
// caller points `blocks` at the row.
simd::BlockNoiseRow kernel_faded_row(int subsampling_x, int bit_depth);

// The first two noise samples of each of `count` blocks in one row after the horizontal
// overlap with the block on the left (columns block_width and block_width + 1 of that
// block's template row), packed low half first; block 0 keeps its own. block_rows[b] is the
// template row block b reads.
void overlap_seams(const int16_t* const* block_rows, int count, int subsampling_x, int bit_depth, uint32_t* seams);

}  // namespace filmgrain::av1

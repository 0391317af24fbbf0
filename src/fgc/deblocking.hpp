// Horizontal deblocking of a grain stripe (TR 23002-9 7.3.3, RDD 5 4.4): a [1 2 1]/4
// filter on the two samples either side of every vertical block edge inside the plane.
//
// The vertical deblocking (horizontal block edges, RDD 5 4.2.4) is done once per template
// instead: predeblock_template_rows.
#pragma once
#include <cstdint>

#include "fgc/grain_template.hpp"

namespace filmgrain::fgc {

// grain: `rows` rows of `stride` int32 values; edges at multiples of block_size that are
// strictly inside [0, width). Both filtered samples use the unfiltered neighbours.
// right_has_grain (ffmpeg flavour, else null: every edge): FFmpeg's h274.c deblocks an edge
// as it synthesizes the block to its right, and a block that matches no intensity interval
// returns before that, so only edges whose right block has grain are filtered (an edge after
// a grainless block is, against its zeros). right_has_grain[k]: the block starting at column
// k * block_size got grain.
void deblock_stripe_vertical_edges(int32_t* grain, int stride, int rows, int width, int block_size,
                                   const uint8_t* right_has_grain = nullptr);

// Vertical deblocking inside the template: rows k*block and k*block + block - 1 are
// scaled by kDeblockFactor[v - 2] / 128, so that blocks cut from the template meet
// softened at their horizontal edges (RDD 5 4.2.4).
void predeblock_template_rows(GrainTemplate& t, int cutoff_v, int block_size);

}  // namespace filmgrain::fgc

// Horizontal deblocking of a grain stripe (TR 23002-9 7.3.3, RDD 5 4.4): a [1 2 1]/4
// filter on the two samples either side of every vertical block edge inside the plane.
#pragma once
#include <cstdint>

namespace filmgrain::fgc {

// grain: `rows` rows of `stride` int32 values; edges at multiples of block_size that are
// strictly inside [0, width). Both filtered samples use the unfiltered neighbours.
void deblock_stripe_vertical_edges(int32_t* grain, int stride, int rows, int width, int block_size);

// FFmpeg's h274.c (ffmpeg flavour): it deblocks an edge as it synthesizes the block to its
// right, and a block that matches no intensity interval returns before that, so only edges
// whose right block has grain are filtered (an edge after a grainless block is, against its
// zeros). right_has_grain[k]: the block starting at column k * block_size got grain.
void deblock_stripe_edges_before_grain(int32_t* grain, int stride, int rows, int width, int block_size,
                                       const uint8_t* right_has_grain);

}  // namespace filmgrain::fgc

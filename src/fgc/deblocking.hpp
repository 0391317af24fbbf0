// Horizontal deblocking of a grain stripe (TR 23002-9 7.3.3, RDD 5 4.4): a [1 2 1]/4
// filter on the two samples either side of every vertical block edge inside the plane.
#pragma once
#include <cstdint>

namespace filmgrain::fgc {

// grain: `rows` rows of `stride` int32 values; edges at multiples of block_size that are
// strictly inside [0, width). Both filtered samples use the unfiltered neighbours.
void deblock_stripe_vertical_edges(int32_t* grain, int stride, int rows, int width, int block_size);

}  // namespace filmgrain::fgc

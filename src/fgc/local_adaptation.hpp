// Local adaptation (TR 23002-9 7.3.2): the average of the decoded samples of each block
// selects the intensity interval, hence the scale factor and the template.
#pragma once
#include <algorithm>
#include <cstdint>

#include "filmgrain/frame.hpp"

namespace filmgrain::fgc {

// The sum of the samples of a size x size block that lie inside the plane, and their count.
template <typename Pixel>
uint32_t block_sum_inside(const PlaneView& plane, int x0, int y0, int size, uint32_t* count) {
    const int w = std::min(size, plane.width - x0), h = std::min(size, plane.height - y0);
    uint32_t sum = 0;
    for (int y = 0; y < h; y++) {
        const Pixel* row = plane.row<const Pixel>(y0 + y) + x0;
        for (int x = 0; x < w; x++) sum += row[x];
    }
    *count = uint32_t(w * h);
    return sum;
}

// RDD 5 (HM-2020): mean over the samples of the block that lie inside the plane (partial
// blocks at the right and bottom edges average fewer samples), then >> (bd - 8). FFmpeg does
// not (block_average_zero_outside).
template <typename Pixel>
int block_average_inside(const PlaneView& plane, int x0, int y0, int size, int bit_depth) {
    uint32_t count = 0;
    const uint32_t sum = block_sum_inside<Pixel>(plane, x0, y0, size, &count);
    return int(std::min<uint32_t>((sum / count) >> (bit_depth - 8), 255));
}

// FFmpeg's h274.c (ffmpeg flavour) sums a whole 8x8 block of the picture it is given, the
// coded picture before the conformance-window crop, and shifts by 6 (8-bit only: FFmpeg
// applies H.274 grain to yuv420p alone; deeper samples are shifted by bd - 8 here). A block
// that reaches past the coded picture reads FFmpeg's frame padding: zero in a buffer fresh
// from its zero-initialising pool, which is what is taken here; a recycled buffer can hold
// stale grain there, which no other decoder can reproduce.
template <typename Pixel>
int block_average_zero_outside(const PlaneView& plane, int x0, int y0, int size, int bit_depth) {
    const int log2_area = size == 8 ? 6 : size == 16 ? 8 : 10;
    uint32_t count = 0;
    const uint32_t sum = block_sum_inside<Pixel>(plane, x0, y0, size, &count);
    return int(std::min<uint32_t>(sum >> (log2_area + bit_depth - 8), 255));
}

// VTM/HM master: sum over a whole block of the picture padded by edge replication (HM
// synthesizes on the coded picture, whose padding replicates the edge), shifted by
// log2(size*size) + bd - 8.
template <typename Pixel>
int block_average_replicated(const PlaneView& plane, int x0, int y0, int size, int bit_depth) {
    const int log2_area = size == 8 ? 6 : size == 16 ? 8 : 10;
    uint64_t sum = 0;
    const bool inside = x0 + size <= plane.width && y0 + size <= plane.height;
    for (int y = 0; y < size; y++) {
        const Pixel* row = plane.row<const Pixel>(std::min(y0 + y, plane.height - 1));
        if (inside) {
            for (int x = 0; x < size; x++) sum += row[x0 + x];
        } else {
            for (int x = 0; x < size; x++) sum += row[std::min(x0 + x, plane.width - 1)];
        }
    }
    return int(std::min<uint64_t>(sum >> (log2_area + bit_depth - 8), 255));
}

// Single-line blocks (TR 23002-9 7.3.2.3): the average of an n x 1 segment of row y, for
// line-based hardware that keeps no line buffer. The two variants follow the block
// averages above: samples inside the plane only, or the segment of the edge-replicated
// picture shifted by log2(n) + bd - 8.
template <typename Pixel>
int segment_average_inside(const PlaneView& plane, int x0, int y, int n, int bit_depth) {
    const int w = std::min(n, plane.width - x0);
    const Pixel* row = plane.row<const Pixel>(y) + x0;
    uint32_t sum = 0;
    for (int x = 0; x < w; x++) sum += row[x];
    return int(std::min<uint32_t>((sum / uint32_t(w)) >> (bit_depth - 8), 255));
}

template <typename Pixel>
int segment_average_replicated(const PlaneView& plane, int x0, int y, int n, int bit_depth) {
    const int log2_n = n == 8 ? 3 : n == 16 ? 4 : 5;
    const Pixel* row = plane.row<const Pixel>(std::min(y, plane.height - 1));
    uint32_t sum = 0;
    for (int x = 0; x < n; x++) sum += row[std::min(x0 + x, plane.width - 1)];
    return int(std::min<uint32_t>(sum >> (log2_n + bit_depth - 8), 255));
}

}  // namespace filmgrain::fgc

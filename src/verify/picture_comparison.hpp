// What a decoder's picture has that the reference's does not: per plane the differing samples,
// the largest difference, the first differing sample in raster order and the differing
// samples per block of the model's grid (AV1: the 32x32 luma blocks of AV1 7.18.3.5, their
// chroma co-sited blocks; FGC: the 16x16 randomization blocks of TR 23002-9 7.3.2 or the
// 8x8 adaptation blocks), so that a team reads where the decoder departs, not only that it does.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "filmgrain/frame.hpp"

namespace filmgrain::verify {

struct FirstDifference {
    int x = -1, y = -1;  // plane coordinates; -1: none
    int expected = 0, decoded = 0;
};

struct PlaneComparison {
    int64_t samples = 0;
    int64_t differing = 0;
    int max_abs_difference = 0;
    FirstDifference first;
    // Differing samples per block, row-major, blocks_x * blocks_y (block_width x block_height
    // plane samples: the luma block size shifted by the plane's subsampling).
    int block_width = 0, block_height = 0, blocks_x = 0, blocks_y = 0;
    std::vector<int32_t> differing_per_block;

    bool exact() const { return differing == 0; }
    double differing_percent() const { return samples ? 100.0 * double(differing) / double(samples) : 0.0; }
};

struct PictureComparison {
    std::vector<PlaneComparison> planes;
    bool exact() const;
    int64_t differing() const;
    // Sum of squared differences over every plane: how far a hypothesis lands.
    double squared_error = 0;
};

// Compares `decoded` with `expected` (same format and size; throws Error(kInvalidArgument)
// naming what differs). luma_block: the block side in luma samples for the per-block counts.
PictureComparison compare_pictures(const FrameView& expected, const FrameView& decoded, int luma_block);

// Only the count and squared error (no per-block grid): the cost of judging a hypothesis.
struct Distance {
    int64_t differing = 0;
    double squared_error = 0;
    bool exact() const { return differing == 0; }
};
Distance picture_distance(const FrameView& a, const FrameView& b);

// The MD5 of a picture's samples as raw YUV files and per-frame conformance lists hash them:
// every plane in order, rows without padding, 16-bit samples little-endian.
std::string picture_md5(const FrameView& picture);

}  // namespace filmgrain::verify

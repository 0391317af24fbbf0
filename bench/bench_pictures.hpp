// Test pictures for the benchmarks in bench/, 4:2:0.
#pragma once
#include <cstdint>
#include <random>

#include "core/frame_buffer.hpp"

namespace filmgrain::bench {

// blocky: a ramp with noise and a random level per 8x8 block, so that neighbouring blocks
// land in different intensity intervals, as in pictures with detail (a smooth ramp alone
// would let whole rows of blocks share one interval's template; for AV1 it is the worst
// case of the scaling look-up). Otherwise the ramp with its noise only (up to 16 8-bit codes).
inline FrameBuffer test_picture(int w, int h, int bd, bool blocky = true) {
    FrameBuffer b(w, h, PixelFormat{ChromaFormat::k420, bd});
    std::mt19937 rng(1);
    FrameView v = b.view();
    for (int p = 0; p < v.plane_count(); p++)
        for (int y = 0; y < v.planes[p].height; y++)
            for (int x = 0; x < v.planes[p].width; x++) {
                const uint32_t block_level =
                    blocky ? ((uint32_t(x / 8) * 2654435761u) ^ (uint32_t(y / 8) * 40503u)) >> 25 : 0;
                const int value = ((x + y) * 255 / (v.planes[p].width + v.planes[p].height) + int(block_level) +
                                   int(rng() % 16)) & 255;
                if (bd > 8)
                    v.planes[p].row<uint16_t>(y)[x] = uint16_t(value << (bd - 8));
                else
                    v.planes[p].row<uint8_t>(y)[x] = uint8_t(value);
            }
    return b;
}

}  // namespace filmgrain::bench

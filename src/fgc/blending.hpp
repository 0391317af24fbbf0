// Additive blending (TR 23002-9 7.3.4, blending_mode_id 0): the 8-bit-scale grain is
// shifted to the picture's bit depth and added, with clipping to [0, 2^bd - 1].
#pragma once
#include <algorithm>
#include <cstdint>

namespace filmgrain::fgc {

template <typename Pixel>
void blend_row_additive(const Pixel* src, Pixel* dst, const int32_t* grain, int width, int bit_depth) {
    const int32_t max_value = (1 << bit_depth) - 1;
    const int shift = bit_depth - 8;
    for (int x = 0; x < width; x++) {
        int32_t g = grain[x] * (1 << shift);
        dst[x] = Pixel(std::clamp<int32_t>(int32_t(src[x]) + g, 0, max_value));
    }
}

}  // namespace filmgrain::fgc

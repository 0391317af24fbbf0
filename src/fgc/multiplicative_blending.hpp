// Multiplicative blending (blending_mode_id = 1, VSEI film grain characteristics semantics):
//
//   Igrain = Clip3(0, (1 << bitDepth) - 1, Idecoded + Round(Idecoded * G / (1 << bitDepth)))
//
// i.e. the grain G is relative to the full-scale signal: it is scaled by the sample's own
// intensity, full strength at the top of the range and none at black, so its standard
// deviation grows in proportion to the signal. G at the picture's bit depth is the 8-bit
// scale grain g8 shifted up by bitDepth - 8, as in additive blending (blending.hpp), so
//
//   Idecoded * G / 2^bitDepth = Idecoded * g8 / 256,
//
// which is what is computed: (Idecoded * g8 + 128) >> 8, rounding half up. The product fits
// in 32 bits for every bit depth up to 16 (|g8| < 2^15). Where the semantics divide by
// (1 << bitDepth) - 1 instead, the results differ by less than one code value per 2^bitDepth.
#pragma once
#include <algorithm>
#include <cstdint>

namespace filmgrain::fgc {

template <typename Pixel>
void blend_row_multiplicative(const Pixel* src, Pixel* dst, const int32_t* grain, int width, int bit_depth) {
    const int32_t max_value = (1 << bit_depth) - 1;
    for (int x = 0; x < width; x++) {
        const int32_t i = src[x];
        const int32_t g = int32_t((int64_t(i) * grain[x] + 128) >> 8);
        dst[x] = Pixel(std::clamp<int32_t>(i + g, 0, max_value));
    }
}

}  // namespace filmgrain::fgc

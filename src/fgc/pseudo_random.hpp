// The 32-bit LFSR of RDD 5 / TR 23002-9 7.3.1: x^31 + x^3 + 1, shifting left, with the
// feedback bit taken as XNOR of bits 30 and 2 (HM's prng(), FFmpeg's prng_shift()).
#pragma once
#include <cstdint>

namespace filmgrain::fgc {

inline uint32_t lfsr_next(uint32_t x) {
    uint32_t feedback = 1u ^ ((x >> 2) & 1u) ^ ((x >> 30) & 1u);
    return (x << 1) | feedback;
}

}  // namespace filmgrain::fgc

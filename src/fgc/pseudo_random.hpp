// The 32-bit LFSR of RDD 5 / TR 23002-9 7.3.1: x^31 + x^3 + 1, shifting left, with the
// feedback bit taken as XNOR of bits 30 and 2 (HM's prng(), FFmpeg's prng_shift()).
#pragma once
#include <cstdint>

namespace filmgrain::fgc {

inline uint32_t lfsr_next(uint32_t x) {
    uint32_t feedback = 1u ^ ((x >> 2) & 1u) ^ ((x >> 30) & 1u);
    return (x << 1) | feedback;
}

// Two and three steps at once. The feedback of step j reads bits 2 - j and 30 - j of the
// starting state (the bits shifted in by the earlier steps sit below bit j), so all the
// feedback bits come from one XOR of the state with itself shifted right by 28, landing in
// the order they are shifted in: x3 = lfsr_next(lfsr_next(lfsr_next(x))).
inline uint32_t lfsr_next2(uint32_t x) { return (x << 2) | (~((x >> 1) ^ (x >> 29)) & 3u); }
inline uint32_t lfsr_next3(uint32_t x) { return (x << 3) | (~(x ^ (x >> 28)) & 7u); }

}  // namespace filmgrain::fgc

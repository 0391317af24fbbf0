// The film grain pseudo-random generator of AV1 spec 7.18.3.2 and the seeds the
// spec derives from grain_seed for each use (7.18.3.3 templates, 7.18.3.5 stripes).
#pragma once
#include <cstdint>

namespace filmgrain::av1 {

// A 16-bit Fibonacci LFSR with taps at bits 0, 1, 3 and 12 (the spec's
// RandomRegister). get(bits) shifts once and returns the top `bits` bits, so
// consecutive draws overlap in all but one bit: only the exact sequence matters
// for bit-exactness, not statistical quality.
class RandomNumberGenerator {
public:
    explicit RandomNumberGenerator(uint16_t seed) : state_(seed) {}

    // get_random_number(bits), bits in 1..16.
    int get(int bits) {
        const unsigned r = state_;
        const unsigned bit = (r ^ (r >> 1) ^ (r >> 3) ^ (r >> 12)) & 1u;
        state_ = static_cast<uint16_t>((r >> 1) | (bit << 15));
        return static_cast<int>((state_ >> (16 - bits)) & ((1u << bits) - 1u));
    }
    uint16_t state() const { return state_; }

private:
    uint16_t state_;
};

// 7.18.3.3: the luma template is seeded with grain_seed itself; Cb and Cr use
// grain_seed XORed with fixed constants so the three templates are uncorrelated.
inline uint16_t luma_template_seed(int grain_seed) { return static_cast<uint16_t>(grain_seed); }
inline uint16_t cb_template_seed(int grain_seed) { return static_cast<uint16_t>(grain_seed ^ 0xb524); }
inline uint16_t cr_template_seed(int grain_seed) { return static_cast<uint16_t>(grain_seed ^ 0x49d8); }

// 7.18.3.5: every 32-luma-row stripe restarts the generator from a seed mixed
// with the stripe number. This is what lets stripes be synthesised
// independently (and in parallel): stripe n never depends on stripe n-1's state.
inline uint16_t stripe_seed(int grain_seed, int stripe) {
    unsigned s = static_cast<uint16_t>(grain_seed);
    s ^= ((static_cast<unsigned>(stripe) * 37u + 178u) & 255u) << 8;
    s ^= (static_cast<unsigned>(stripe) * 173u + 105u) & 255u;
    return static_cast<uint16_t>(s);
}

}  // namespace filmgrain::av1

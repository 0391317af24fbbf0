// Counter-based random numbers keyed by integer coordinates. Every grain cell and every
// white-noise sample draws from a stream that depends only on its own coordinates and the
// seed, never on visiting order: that is what makes output identical for any thread count,
// tiling or region of interest.
#pragma once
#include <cmath>
#include <cstdint>

namespace filmgrain::physical {

// SplitMix64's output function (a bijective 64-bit finalizer).
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

inline uint64_t hash_coordinates(int64_t x, int64_t y, uint64_t seed) {
    return mix64(mix64(seed ^ 0x6a09e667f3bcc909ull) ^ mix64(uint64_t(x) * 0x9e3779b97f4a7c15ull + 0x3c6ef372fe94f82bull) ^
                 (uint64_t(y) * 0xd1b54a32d192ed03ull));
}

class CellRandom {
public:
    explicit CellRandom(uint64_t key) : state_(key) {}
    uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ull); }
    // Uniform in (0, 1): never 0, so logarithms stay finite.
    double uniform() { return (double(next() >> 11) + 0.5) * 0x1.0p-53; }
    double normal() {
        const double a = uniform(), b = uniform();
        return std::sqrt(-2.0 * std::log(a)) * std::cos(6.283185307179586 * b);
    }

private:
    uint64_t state_;
};

}  // namespace filmgrain::physical

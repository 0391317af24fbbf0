// Jump-ahead of the VFGS LFSR (vfgs_random.hpp). The reference runs one register through
// the whole picture, block stripe after block stripe, so stripe k can only start once the
// k stripes above have stepped it. The step is linear over GF(2) (a shift plus one XOR
// feedback bit, no constant), so k steps are a 32x32 bit matrix applied to the state:
// with that matrix every stripe's starting state is known before any stripe runs, and
// the stripes can run in any order, on any thread, with the reference's output.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace filmgrain::vfgs {

// The linear map "k steps of lfsr_next" as its 32 columns: column i is the state that
// the single-bit state (1 << i) becomes.
class LfsrJump {
public:
    // The map of `steps` steps (0 = identity), by squaring the one-step matrix.
    explicit LfsrJump(uint64_t steps);

    uint32_t apply(uint32_t state) const {
        uint32_t out = 0;
        for (int i = 0; i < 32; ++i) out ^= column_[static_cast<std::size_t>(i)] & (0u - ((state >> i) & 1u));
        return out;
    }

private:
    LfsrJump() = default;
    // this map followed by `after`
    LfsrJump then(const LfsrJump& after) const;
    std::array<uint32_t, 32> column_{};
};

}  // namespace filmgrain::vfgs

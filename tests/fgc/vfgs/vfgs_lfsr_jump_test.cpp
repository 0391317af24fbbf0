// Jump-ahead of the VFGS LFSR (vfgs_lfsr_jump.hpp) and the stripe starting states built
// on it (vfgs_stripe_states.hpp): the same states as stepping the register one block at a
// time, as the reference does.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "fgc/vfgs/vfgs_lfsr_jump.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "fgc/vfgs/vfgs_stripe_states.hpp"

using namespace filmgrain::vfgs;

TEST(VfgsLfsrJump, EqualsSteppingForManyCounts) {
    std::mt19937 rng(25);
    std::vector<uint64_t> counts = {0, 1, 2, 3, 31, 32, 33, 63, 64, 65, 120, 121, 240, 255, 256, 4095, 4096, 8160, 65535};
    for (int i = 0; i < 40; ++i) counts.push_back(rng() % 200000);
    const uint32_t states[] = {kDefaultLfsrState, 1u, 0x80000000u, 0xFFFFFFFFu, lfsr_state_from_seed(12345), 0u};
    for (uint64_t k : counts) {
        const LfsrJump jump(k);
        for (uint32_t s : states) EXPECT_EQ(jump.apply(s), lfsr_advance(s, static_cast<uint32_t>(k))) << "k " << k << " state " << s;
        const uint32_t r = rng();
        EXPECT_EQ(jump.apply(r), lfsr_advance(r, static_cast<uint32_t>(k))) << "k " << k << " state " << r;
    }
}

// Counts too large to step: a jump of a + b is the jump of a followed by b, and 2^32 + 7
// steps are checked against stepping 2^32 + 7 times in chunks of one jump of 2^20.
TEST(VfgsLfsrJump, LargeCountsCompose) {
    std::mt19937 rng(7);
    for (int i = 0; i < 20; ++i) {
        const uint64_t a = (uint64_t(rng()) << 20) | rng(), b = (uint64_t(rng()) << 12) | rng();
        const uint32_t s = rng();
        EXPECT_EQ(LfsrJump(a + b).apply(s), LfsrJump(b).apply(LfsrJump(a).apply(s))) << a << " + " << b;
    }
    const LfsrJump chunk(uint64_t(1) << 20);
    uint32_t s = kDefaultLfsrState;
    for (int i = 0; i < 4096; ++i) s = chunk.apply(s);  // 2^32 steps
    EXPECT_EQ(lfsr_advance(s, 7), LfsrJump((uint64_t(1) << 32) + 7).apply(kDefaultLfsrState));
    EXPECT_EQ(LfsrJump(~uint64_t(0)).apply(0u), 0u);  // linear: the zero state stays
}

// The starting states of a frame's stripes and the cursor afterwards are what the serial
// walk of add_grain_frame() gives, frame after frame.
TEST(VfgsLfsrJump, StripeStatesFollowTheSerialWalk) {
    for (int nb : {9, 12, 120, 240}) {
        const LfsrJump step(static_cast<uint64_t>(nb));
        LfsrCursor serial{kDefaultLfsrState, kDefaultLfsrState}, planned = serial;
        std::vector<uint32_t> starts;
        for (int frame = 0; frame < 3; ++frame) {
            const int ns = 8 + frame * 30;
            plan_stripe_states(planned, ns, step, starts);
            ASSERT_EQ(starts.size(), static_cast<size_t>(ns) + 1);
            for (int k = 0; k < ns; ++k) {
                if (k > 0) {
                    serial.upper = serial.stripe;
                    serial.stripe = lfsr_advance(serial.stripe, static_cast<uint32_t>(nb));
                }
                EXPECT_EQ(starts[static_cast<size_t>(k) + 1], serial.stripe) << "nb " << nb << " frame " << frame << " k " << k;
                if (k > 0) EXPECT_EQ(starts[static_cast<size_t>(k)], serial.upper);
            }
            EXPECT_EQ(planned.stripe, serial.stripe);
            EXPECT_EQ(planned.upper, serial.upper);
        }
        std::vector<uint32_t> blocks(static_cast<size_t>(nb));
        fill_block_states(0x1234567u, nb, blocks.data());
        for (int b = 0; b < nb; ++b) EXPECT_EQ(blocks[static_cast<size_t>(b)], lfsr_advance(0x1234567u, static_cast<uint32_t>(b)));
    }
}

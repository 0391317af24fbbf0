// AV1 spec 7.18.3.2 random number process and the seeds of 7.18.3.3 / 7.18.3.5.
#include <gtest/gtest.h>

#include <set>

#include "av1/block_synthesis.hpp"
#include "av1/random_number.hpp"

using namespace filmgrain::av1;

TEST(Av1RandomNumber, HandComputedSteps) {
    // State 1: feedback bit = bit0 ^ bit1 ^ bit3 ^ bit12 = 1, so the register
    // becomes 0x8000; the top 8 bits are 0x80.
    RandomNumberGenerator rng(1);
    EXPECT_EQ(rng.get(8), 0x80);
    EXPECT_EQ(rng.state(), 0x8000);
    // 0x8000 has none of the tap bits set: plain shift to 0x4000.
    EXPECT_EQ(rng.get(8), 0x40);
    EXPECT_EQ(rng.state(), 0x4000);
    // The same shift seen through 11 and 16 bit reads.
    EXPECT_EQ(rng.get(11), 0x2000 >> 5);
    EXPECT_EQ(rng.get(16), 0x1000);
}

TEST(Av1RandomNumber, TapsAndBitWidth) {
    // 0x1000 has only bit 12 set: feedback 1.
    RandomNumberGenerator a(0x1000);
    a.get(1);
    EXPECT_EQ(a.state(), 0x8800);
    // 0x000B: bits 0,1,3 -> 1^1^1 = 1.
    RandomNumberGenerator b(0x000B);
    EXPECT_EQ(b.get(1), 1);
    EXPECT_EQ(b.state(), 0x8005);
    // 0x0003: bits 0,1 -> 0.
    RandomNumberGenerator c(0x0003);
    EXPECT_EQ(c.get(4), 0);
    EXPECT_EQ(c.state(), 0x0001);
}

TEST(Av1RandomNumber, ZeroIsAFixedPoint) {
    RandomNumberGenerator rng(0);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(rng.get(11), 0);
}

TEST(Av1RandomNumber, MaximalPeriod) {
    RandomNumberGenerator rng(1);
    int n = 0;
    std::set<uint16_t> seen;
    do {
        rng.get(1);
        seen.insert(rng.state());
        ++n;
    } while (rng.state() != 1 && n < 70000);
    EXPECT_EQ(n, 65535);
    EXPECT_EQ(seen.size(), 65535u);
}

TEST(Av1RandomNumber, Seeds) {
    EXPECT_EQ(luma_template_seed(0x1234), 0x1234);
    EXPECT_EQ(cb_template_seed(0x1234), 0x1234 ^ 0xb524);
    EXPECT_EQ(cr_template_seed(0x1234), 0x1234 ^ 0x49d8);
    // stripe 0: (178 << 8) ^ 105; stripe 1: (215 << 8) ^ (278 & 255 = 22).
    EXPECT_EQ(stripe_seed(0, 0), 0xB269);
    EXPECT_EQ(stripe_seed(0, 1), 0xD716);
    EXPECT_EQ(stripe_seed(0xFFFF, 0), 0xFFFF ^ 0xB269);
    // Only the low 8 bits of the products matter: stripe 256 equals stripe 0.
    EXPECT_EQ(stripe_seed(77, 256), stripe_seed(77, 0));
}

TEST(Av1RandomNumber, StripeOffsetsFollowTheStripeSeed) {
    const auto offs = stripe_block_offsets(22463, 3, 5);
    ASSERT_EQ(offs.size(), 5u);
    RandomNumberGenerator rng(stripe_seed(22463, 3));
    for (auto o : offs) EXPECT_EQ(o, rng.get(8));
}

// Piecewise-linear scaling function (AV1 spec 7.18.3.4, scale_lut of 7.18.3.5).
#include <gtest/gtest.h>

#include "av1/scaling_lookup.hpp"

using filmgrain::av1::ScalingLookup;

namespace {
const int kValues[] = {16, 32};
const int kScalings[] = {20, 52};
}  // namespace

TEST(Av1ScalingLookup, EmptyIsZero) {
    for (int bd : {8, 10, 12}) {
        ScalingLookup s(nullptr, nullptr, 0, bd);
        for (int i = 0; i < (1 << bd); i += 7) EXPECT_EQ(s(i), 0);
    }
}

TEST(Av1ScalingLookup, EightBitInterpolation) {
    ScalingLookup s(kValues, kScalings, 2, 8);
    EXPECT_EQ(s(0), 20);
    EXPECT_EQ(s(15), 20);
    EXPECT_EQ(s(16), 20);
    // slope 32/16 = 2 in 16.16: 20 + ((x * 131072 + 32768) >> 16)
    EXPECT_EQ(s(17), 22);
    EXPECT_EQ(s(24), 36);
    EXPECT_EQ(s(31), 50);
    EXPECT_EQ(s(32), 52);
    EXPECT_EQ(s(255), 52);
}

TEST(Av1ScalingLookup, DecreasingSegmentRoundsTowardsMinusInfinity) {
    const int v[] = {0, 10}, sc[] = {100, 0};
    ScalingLookup s(v, sc, 2, 8);
    // delta = -100 * ((65536 + 5) / 10) = -655400
    EXPECT_EQ(s(0), 100);
    EXPECT_EQ(s(1), 90);  // (-655400 + 32768) >> 16 = -10
    EXPECT_EQ(s(5), 50);  // (-3277000 + 32768) >> 16 = -50
    EXPECT_EQ(s(9), 10);
    EXPECT_EQ(s(10), 0);
}

TEST(Av1ScalingLookup, SinglePointIsConstant) {
    const int v[] = {100}, sc[] = {77};
    ScalingLookup s(v, sc, 1, 10);
    for (int i = 0; i < 1024; i += 13) EXPECT_EQ(s(i), 77);
}

TEST(Av1ScalingLookup, TenBitInterpolatesLowBits) {
    ScalingLookup s(kValues, kScalings, 2, 10);
    EXPECT_EQ(s(64), 20);          // 16 << 2
    EXPECT_EQ(s(65), 20 + ((2 * 1 + 2) >> 2));  // between lut[16]=20 and lut[17]=22
    EXPECT_EQ(s(66), 21);
    EXPECT_EQ(s(67), 20 + ((2 * 3 + 2) >> 2));
    EXPECT_EQ(s(68), 22);
    EXPECT_EQ(s(128), 52);
    EXPECT_EQ(s(1023), 52);  // x == 255 has no successor
    EXPECT_EQ(s(0), 20);
}

TEST(Av1ScalingLookup, TwelveBitInterpolatesLowBits) {
    ScalingLookup s(kValues, kScalings, 2, 12);
    EXPECT_EQ(s(256), 20);
    EXPECT_EQ(s(256 + 3), 20);  // (2*3 + 8) >> 4 = 0
    EXPECT_EQ(s(256 + 4), 21);  // (2*4 + 8) >> 4 = 1
    EXPECT_EQ(s(256 + 8), 21);
    EXPECT_EQ(s(256 + 12), 22);
    EXPECT_EQ(s(4095), 52);
}

TEST(Av1ScalingLookup, HighBitDepthNegativeSlope) {
    const int v[] = {0, 1}, sc[] = {10, 0};
    ScalingLookup s(v, sc, 2, 10);
    // lut[0] = 10, lut[1] = 0: 10 + ((-10 * rem + 2) >> 2)
    EXPECT_EQ(s(0), 10);
    EXPECT_EQ(s(1), 10 + ((-10 + 2) >> 2));  // 8
    EXPECT_EQ(s(2), 5);
    EXPECT_EQ(s(3), 10 + ((-30 + 2) >> 2));  // 3
    EXPECT_EQ(s(4), 0);
}

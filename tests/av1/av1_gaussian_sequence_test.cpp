// Gaussian_Sequence table of AV1 spec 7.18.3.3.
#include <gtest/gtest.h>

#include <numeric>

#include "av1/gaussian_sequence.hpp"

using filmgrain::av1::kGaussianSequence;

TEST(Av1GaussianSequence, SpotValues) {
    EXPECT_EQ(kGaussianSequence[0], 56);
    EXPECT_EQ(kGaussianSequence[1], 568);
    EXPECT_EQ(kGaussianSequence[2], -180);
    EXPECT_EQ(kGaussianSequence[1023], 320);
    EXPECT_EQ(kGaussianSequence[2047], -484);
}

TEST(Av1GaussianSequence, Aggregates) {
    long sum = 0, abs_sum = 0;
    int lo = 0, hi = 0;
    for (int v : kGaussianSequence) {
        sum += v;
        abs_sum += v < 0 ? -v : v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        EXPECT_EQ(v % 4, 0);  // 12-bit values on a 4-step grid
    }
    EXPECT_EQ(sum, 1120);
    EXPECT_EQ(abs_sum, 837192);
    EXPECT_EQ(lo, -1752);
    EXPECT_EQ(hi, 1688);
}

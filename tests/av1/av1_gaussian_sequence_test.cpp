// Gaussian_Sequence table of AV1 spec 7.18.3.3.
#include <gtest/gtest.h>

#include <numeric>

#include "av1/gaussian_sequence.hpp"
#include "core/md5.hpp"

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

// The whole table against an independent copy: the MD5 of the 2048 values as int16
// little-endian, as dav1d stores dav1d_gaussian_sequence, read from the bytes of Debian 12's
// libdav1d 1.0.0 and of dav1d 1.5.3 built from source (both agree).
TEST(Av1GaussianSequence, WholeTableEqualsDav1ds) {
    unsigned char bytes[4096];
    for (int i = 0; i < 2048; i++) {
        const auto v = static_cast<uint16_t>(kGaussianSequence[i]);
        bytes[2 * i] = static_cast<unsigned char>(v);
        bytes[2 * i + 1] = static_cast<unsigned char>(v >> 8);
    }
    EXPECT_EQ(filmgrain::md5_hex(bytes, sizeof(bytes)), "1a0428fb96e09c2a1cb767be699be2eb");
}

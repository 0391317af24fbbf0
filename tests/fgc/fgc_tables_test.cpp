// Tables and transforms of the FGC model, checked against their definitions.
#include <gtest/gtest.h>

#include <cmath>

#include "core/md5.hpp"
#include "fgc/fgc_tables.hpp"
#include "fgc/pseudo_random.hpp"

using namespace filmgrain::fgc;

TEST(FgcLfsr, FeedbackIsXnorOfBits30And2) {
    EXPECT_EQ(lfsr_next(0u), 1u);              // both bits 0 -> feedback 1
    EXPECT_EQ(lfsr_next(1u), 3u);
    EXPECT_EQ(lfsr_next(4u), 8u);              // bit 2 set -> feedback 0
    EXPECT_EQ(lfsr_next(1u << 30), 1u << 31);  // bit 30 set -> feedback 0
    EXPECT_EQ(lfsr_next((1u << 30) | 4u), (1u << 31) | 8u | 1u);  // both set -> 1
    EXPECT_EQ(lfsr_next(0x80000000u), 1u);     // bit 31 shifts out
}

TEST(FgcLfsr, SequenceFromFirstSeedIsAnchored) {
    // Anchored to constants from an independent transcription of the RDD 5 / H.274 generator
    // (a 32-entry bit array shifted up by one, the new bit 0 = NOT(bit 2 XOR bit 30)), not to
    // the implementation under test: Seed_LUT[0] = 747538460 (0x2c8e881c), its first eight
    // successors, and after 1000 steps the state and a fold of every state (acc = acc*31 + x).
    ASSERT_EQ(kSeedLut[0], 0x2c8e881cu);
    const uint32_t first[8] = {0x591d1038, 0xb23a2070, 0x647440e1, 0xc8e881c2,
                               0x91d10384, 0x23a20708, 0x47440e11, 0x8e881c22};
    uint32_t x = kSeedLut[0], acc = 0;
    for (int i = 0; i < 1000; i++) {
        x = lfsr_next(x);
        acc = acc * 31u + x;
        if (i < 8) EXPECT_EQ(x, first[i]) << "step " << i + 1;
    }
    EXPECT_EQ(x, 0x7ec3e221u);
    EXPECT_EQ(acc, 0x07775bb6u);
}

TEST(FgcTables, GaussianTableIsRdd5s) {
    long sum = 0, sq = 0;
    int mn = 127, mx = -127;
    for (int8_t v : kGaussianLut) {
        sum += v;
        sq += v * v;
        mn = std::min<int>(mn, v);
        mx = std::max<int>(mx, v);
    }
    EXPECT_EQ(sum, 451);  // the RDD 5 table's checksum
    EXPECT_EQ(kGaussianLut[0], -11);
    EXPECT_EQ(kGaussianLut[2047], 47);
    EXPECT_GE(mn, -127);
    EXPECT_LE(mx, 127);
    const double sd = std::sqrt(double(sq) / 2048);
    EXPECT_NEAR(sd, 55, 10) << "a zero-mean Gaussian table of standard deviation ~ 50..60";
    EXPECT_EQ(kSeedLut[0], 747538460u);
    EXPECT_EQ(kSeedLut[255], 1358954497u);
}

// The whole tables against an independent copy: the MD5 of the 2048 int8 Gaussian values and
// of the 256 seeds (uint32, little-endian) as FFmpeg's h274 stores them, read from the bytes of
// Debian 12's libavcodec 59 (FFmpeg 5.1) and Debian 13's libavcodec 61 (FFmpeg 7.1), which
// agree with each other and with HM's SEIFilmGrainSynthesizer.cpp. One wrong entry anywhere
// changes the hash; the spot values above say where to look.
TEST(FgcTables, WholeTablesEqualFfmpegsH274Tables) {
    static_assert(sizeof(kGaussianLut) == 2048 && sizeof(kSeedLut) == 1024);
    EXPECT_EQ(filmgrain::md5_hex(kGaussianLut, sizeof(kGaussianLut)), "2acb462fdeec947a5f8a10d4db9abd74");
    unsigned char seeds[1024];
    for (int i = 0; i < 256; i++)
        for (int b = 0; b < 4; b++) seeds[4 * i + b] = static_cast<unsigned char>(kSeedLut[i] >> (8 * b));
    EXPECT_EQ(filmgrain::md5_hex(seeds, sizeof(seeds)), "cf0c50b25fcc017fa5cf48277b01f763");
}

// The integer matrices approximate the orthonormal DCT-2 basis scaled by 64*sqrt(2) (VVC)
// and 32*sqrt(2) (RDD 5): every entry within 2 (resp. 1) of its real-valued definition.
TEST(FgcTransforms, VvcMatrixMatchesFloatDct) {
    for (int k = 0; k < 64; k++)
        for (int n = 0; n < 64; n++) {
            double ideal = (k == 0 ? 64.0 : 64.0 * std::sqrt(2.0) * std::cos(M_PI * k * (2 * n + 1) / 128.0));
            EXPECT_NEAR(kVvcDct2_64[k][n], ideal, 2.0) << k << "," << n;
        }
    EXPECT_EQ(kVvcDct2_64[1][0], 91);
    EXPECT_EQ(kVvcDct2_64[32][0], 64);
}

TEST(FgcTransforms, Rdd5MatrixMatchesFloatDct) {
    for (int k = 0; k < 64; k++)
        for (int n = 0; n < 64; n++) {
            double ideal = (k == 0 ? 32.0 : 32.0 * std::sqrt(2.0) * std::cos(M_PI * k * (2 * n + 1) / 128.0));
            EXPECT_NEAR(kRdd5Idct64[k][n], ideal, 1.0) << k << "," << n;
        }
}

TEST(FgcTransforms, RowsAreNearlyOrthogonal) {
    for (int a = 0; a < 64; a++)
        for (int b = 0; b < 64; b++) {
            long dot = 0;
            for (int n = 0; n < 64; n++) dot += long(kVvcDct2_64[a][n]) * kVvcDct2_64[b][n];
            if (a == b) EXPECT_NEAR(dot, 262144, 262144 * 0.01);
            else EXPECT_LT(std::abs(dot), 262144 * 0.01);
        }
}

TEST(FgcTables, DeblockFactorsRiseToUnity) {
    for (int i = 1; i < 13; i++) EXPECT_GE(kDeblockFactor[i], kDeblockFactor[i - 1]);
    EXPECT_EQ(kDeblockFactor[0], 64);
    EXPECT_EQ(kDeblockFactor[12], 128);
}

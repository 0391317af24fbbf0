// Noise application and clipping (AV1 spec 7.18.3.5).
#include <gtest/gtest.h>

#include <vector>

#include "av1/grain_blending.hpp"

using namespace filmgrain::av1;

TEST(Av1GrainBlending, ClipLimits) {
    auto c = clip_limits(false, 8, 2);
    EXPECT_EQ(c.min_value, 0);
    EXPECT_EQ(c.max_luma, 255);
    EXPECT_EQ(c.max_chroma, 255);
    c = clip_limits(false, 12, 0);
    EXPECT_EQ(c.max_luma, 4095);
    EXPECT_EQ(c.max_chroma, 4095);
    c = clip_limits(true, 8, 1);
    EXPECT_EQ(c.min_value, 16);
    EXPECT_EQ(c.max_luma, 235);
    EXPECT_EQ(c.max_chroma, 240);
    c = clip_limits(true, 10, 9);
    EXPECT_EQ(c.min_value, 64);
    EXPECT_EQ(c.max_luma, 940);
    EXPECT_EQ(c.max_chroma, 960);
    // MC_IDENTITY: chroma planes hold colour channels with luma's range.
    c = clip_limits(true, 8, 0);
    EXPECT_EQ(c.max_chroma, 235);
    c = clip_limits(true, 12, 0);
    EXPECT_EQ(c.min_value, 256);
    EXPECT_EQ(c.max_chroma, 3760);
}

TEST(Av1GrainBlending, LumaRow) {
    const int v[] = {0}, s[] = {64};
    ScalingLookup lut(v, s, 1, 8);
    const uint8_t src[] = {100, 100, 100, 250, 10, 100};
    const int16_t noise[] = {10, -10, 3, 127, -128, -1};
    uint8_t dst[6];
    blend_luma_row<uint8_t>(src, dst, noise, 6, lut, 8, 16, 235);
    // Round2(64 * n, 8) = (64n + 128) >> 8
    EXPECT_EQ(dst[0], 100 + ((640 + 128) >> 8));   // +3
    EXPECT_EQ(dst[1], 100 + ((-640 + 128) >> 8));  // -2
    EXPECT_EQ(dst[2], 100 + 1);
    EXPECT_EQ(dst[3], 235);  // clipped to restricted max
    EXPECT_EQ(dst[4], 16);   // 10 - 32 clipped to restricted min
    EXPECT_EQ(dst[5], 100);  // (-64 + 128) >> 8 = 0
}

TEST(Av1GrainBlending, ChromaIndexFromMultipliers) {
    // Scaling 0 below 128 and 255 from 128 on: the noise tells which side
    // the merged index fell.
    const int v[] = {127, 128}, s[] = {0, 255};
    ScalingLookup lut(v, s, 2, 8);
    const uint8_t luma[] = {200, 201, 90};  // odd luma width 3
    const uint8_t src[] = {50, 60};
    const int16_t noise[] = {64, 64};
    uint8_t dst[2];
    // merged = clip((avg * luma_mult + src * mult) >> 6 + offset)
    ChromaScalingIndex idx{false, 0, 64, 0};  // merged = luma average
    blend_chroma_row<uint8_t>(src, dst, luma, 3, noise, 2, 1, idx, lut, 8, 8, 0, 255);
    EXPECT_EQ(dst[0], 50 + 64);  // avg (200+201+1)>>1 = 201 -> 255
    EXPECT_EQ(dst[1], 60);       // odd width: avg of 90 with itself = 90 -> 0
    idx = {false, 64, 0, 100};   // merged = src + 100
    blend_chroma_row<uint8_t>(src, dst, luma, 3, noise, 2, 1, idx, lut, 8, 8, 0, 255);
    EXPECT_EQ(dst[0], 50 + 64);  // 50 + 100 = 150 -> 255
    EXPECT_EQ(dst[1], 60 + 64);
    idx = {false, 64, 0, -256};  // merged = clip(src - 256) = 0
    blend_chroma_row<uint8_t>(src, dst, luma, 3, noise, 2, 1, idx, lut, 8, 8, 0, 255);
    EXPECT_EQ(dst[0], 50);
    idx = {true, 0, 0, 0};  // chroma_scaling_from_luma: merged = luma average
    blend_chroma_row<uint8_t>(src, dst, luma, 3, noise, 2, 1, idx, lut, 8, 8, 0, 255);
    EXPECT_EQ(dst[0], 114);
    EXPECT_EQ(dst[1], 60);
    // 4:4:4: no averaging, chroma x maps to luma x.
    blend_chroma_row<uint8_t>(src, dst, luma, 3, noise, 2, 0, idx, lut, 8, 8, 0, 255);
    EXPECT_EQ(dst[0], 114);
    EXPECT_EQ(dst[1], 124);
}

TEST(Av1GrainBlending, HighBitDepthOffsetIsScaled) {
    // 10 bit: the offset is in 8-bit units, shifted up by 2.
    const int v[] = {127, 128}, s[] = {0, 255};
    filmgrain::av1::ScalingLookup lut(v, s, 2, 10);
    const uint16_t luma[] = {0, 0};
    const uint16_t src[] = {400};
    const int16_t noise[] = {100};
    uint16_t dst[1];
    // merged = 400 + 120 * 4 = 880 -> 10-bit index 880 (8-bit 220): scale 255.
    ChromaScalingIndex idx{false, 64, 0, 120};
    blend_chroma_row<uint16_t>(src, dst, luma, 2, noise, 1, 1, idx, lut, 8, 10, 0, 1023);
    EXPECT_EQ(dst[0], 400 + ((255 * 100 + 128) >> 8));
    // merged = 400 - 120 * 4 = -80 -> clipped to 0: scale 0.
    idx = {false, 64, 0, -120};
    blend_chroma_row<uint16_t>(src, dst, luma, 2, noise, 1, 1, idx, lut, 8, 10, 0, 1023);
    EXPECT_EQ(dst[0], 400);
}

// Stage tests of the FGC frequency-filtering model: templates, randomization, adaptation,
// deblocking and blending.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/frame_buffer.hpp"
#include "fgc/blending.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/grain_scaling.hpp"
#include "fgc/fgc_tables.hpp"
#include "fgc/local_adaptation.hpp"
#include "fgc/pseudo_random.hpp"
#include "fgc/template_generation.hpp"

using namespace filmgrain;
using namespace filmgrain::fgc;

namespace {
struct Stats {
    double mean = 0, sd = 0, lag1_h = 0, lag1_v = 0;
};
Stats stats(const GrainTemplate& t) {
    double s = 0, s2 = 0, ch = 0, cv = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            s += t[y][x];
            s2 += t[y][x] * t[y][x];
            if (x + 1 < 64) ch += t[y][x] * t[y][x + 1];
            if (y + 1 < 64) cv += t[y][x] * t[y + 1][x];
        }
    Stats r;
    r.mean = s / 4096;
    const double var = s2 / 4096 - r.mean * r.mean;
    r.sd = std::sqrt(var);
    r.lag1_h = ch / (64 * 63) / var;
    r.lag1_v = cv / (64 * 63) / var;
    return r;
}
}  // namespace

TEST(FgcTemplates, CoefficientsOnlyInsideTheCutOffBand) {
    int32_t c[64][64];
    fill_template_coefficients(5, 3, c);
    int nonzero_outside = 0, nonzero_inside = 0;
    for (int k = 0; k < 64; k++)
        for (int l = 0; l < 64; l++) {
            const bool inside = k < 4 * (5 + 1) && l < 4 * (3 + 1);
            if (c[k][l]) (inside ? nonzero_inside : nonzero_outside)++;
        }
    EXPECT_EQ(nonzero_outside, 0);
    EXPECT_GT(nonzero_inside, 300);
    EXPECT_EQ(c[0][0], 0) << "DC is removed";
    // The first group comes from Gaussian_LUT at Seed_LUT[h-2 + 13(v-2)].
    const uint32_t seed = kSeedLut[3 + 13 * 1];
    EXPECT_EQ(c[1][0], kGaussianLut[(seed + 1) % 2048]);
    EXPECT_EQ(c[3][0], kGaussianLut[(seed + 3) % 2048]);
    EXPECT_EQ(c[4][0], kGaussianLut[lfsr_next(seed) % 2048]);
}

TEST(FgcTemplates, StatisticsFollowTheCutOffs) {
    for (auto tr : {TemplateTransform::kRdd5Matrix, TemplateTransform::kVvcDct2}) {
        const Stats fine = stats(make_grain_template(14, 14, tr, 8));
        const Stats coarse = stats(make_grain_template(2, 2, tr, 8));
        const Stats wide = stats(make_grain_template(14, 2, tr, 8));
        EXPECT_NEAR(fine.mean, 0, 3);
        EXPECT_NEAR(coarse.mean, 0, 6);
        // Low cut-offs make smooth, strongly correlated grain; high ones nearly white grain.
        EXPECT_GT(coarse.lag1_h, 0.8);
        EXPECT_GT(coarse.lag1_v, 0.8);
        EXPECT_LT(fine.lag1_h, 0.5);
        // h high, v low: correlated vertically, not horizontally.
        EXPECT_GT(wide.lag1_v, wide.lag1_h + 0.3);
        EXPECT_GT(fine.sd, 5);
    }
}

TEST(FgcTemplates, PredeblockScalesBlockEdgeRows) {
    GrainTemplate t;
    for (auto& row : t) row.fill(100);
    predeblock_template_rows(t, 2, 8);  // factor 64/128
    EXPECT_EQ(t[0][5], 50);
    EXPECT_EQ(t[7][5], 50);
    EXPECT_EQ(t[8][5], 50);
    EXPECT_EQ(t[3][5], 100);
    GrainTemplate n;
    for (auto& row : n) row.fill(-100);
    predeblock_template_rows(n, 3, 16);  // 71/128, flooring like HM's shift
    EXPECT_EQ(n[16][0], int8_t((-100 * 71) >> 7));
    EXPECT_EQ(n[15][0], int8_t((-100 * 71) >> 7));
    EXPECT_EQ(n[8][0], -100);
}

TEST(FgcScaling, ScaleSignAndShiftFloorLikeTheReference) {
    // (sign * scale * t) >> shift with an arithmetic shift: negative products round towards
    // minus infinity, so -127 * 255 >> 8 is -127 (not -126), +127 * 255 >> 8 is 126.
    const int8_t t[6] = {127, -127, 1, -1, 0, 64};
    int32_t g[6];
    scale_template_row(t, 255, 8, g, 6);
    EXPECT_EQ(std::vector<int32_t>(g, g + 6), (std::vector<int32_t>{126, -127, 0, -1, 0, 63}));
    scale_template_row(t, -255, 8, g, 6);  // a negative block
    EXPECT_EQ(std::vector<int32_t>(g, g + 6), (std::vector<int32_t>{-127, 126, -1, 0, 0, -64}));
    // 10-bit scale 1020 (= 255 << 2) with log2_scale_factor 2: shift 8, grain up to 506
    scale_template_row(t, 1020, 8, g, 2);
    EXPECT_EQ(g[0], 506);
    EXPECT_EQ(g[1], -507);
    // count: nothing past it is written
    g[3] = 12345;
    scale_template_row(t, 255, 8, g, 3);
    EXPECT_EQ(g[3], 12345);
}

TEST(FgcTemplates, CacheBuildsOnlyWhatIsAsked) {
    TemplateCache cache(TemplateTransform::kVvcDct2, 8);
    EXPECT_EQ(cache.built_count(), 0);
    cache.ensure(4, 6);
    cache.ensure(4, 6);
    cache.ensure(10, 2);
    EXPECT_EQ(cache.built_count(), 2);
    EXPECT_EQ(cache.get(4, 6), make_grain_template(4, 6, TemplateTransform::kVvcDct2, 8));
    cache.reconfigure(TemplateTransform::kVvcDct2, 16);
    EXPECT_EQ(cache.built_count(), 0);
}

TEST(FgcRandomization, OffsetsStayInsideTheTemplate) {
    uint32_t s = 12345;
    for (int i = 0; i < 20000; i++, s = lfsr_next(s)) {
        for (int bs : {8, 16, 32}) {
            const BlockOffset o = block_offset_from_state(s, bs);
            const int span = bs == 8 ? 16 : bs;  // an 8x8 pair shares one 16x16 offset
            EXPECT_EQ(o.x % 4, 0);
            EXPECT_EQ(o.y % 8, 0);
            EXPECT_LE(o.x + span, 64);
            EXPECT_LE(o.y + span, 64);
            EXPECT_EQ(o.sign, (s & 1) ? -1 : 1);
        }
    }
}

TEST(FgcRandomization, SeedsUseColourOffsetsAndWrap) {
    EXPECT_EQ(component_seed(0, 0), kSeedLut[0]);
    EXPECT_EQ(component_seed(0, 1), kSeedLut[85]);
    EXPECT_EQ(component_seed(0, 2), kSeedLut[170]);
    EXPECT_EQ(component_seed(200, 1), kSeedLut[(200 + 85) & 255]);
    EXPECT_EQ(component_seed(-1, 0), kSeedLut[255]);
    std::vector<uint32_t> st;
    fill_block_states(77, 3, 2, st);
    ASSERT_EQ(st.size(), 6u);
    EXPECT_EQ(st[0], 77u);
    EXPECT_EQ(st[5], lfsr_next(lfsr_next(lfsr_next(lfsr_next(lfsr_next(77u))))));
}

// fill_block_states takes three LFSR steps at a time: every state must still be the
// one-step chain's, for any count (remainders 0, 1, 2) and seeds with the high bits set.
TEST(FgcRandomization, BlockStatesFollowTheOneStepChain) {
    std::mt19937 rng(7);
    for (int iter = 0; iter < 300; iter++) {
        const uint32_t seed = iter == 0 ? 0u : iter == 1 ? 0xFFFFFFFFu : uint32_t(rng());
        const int bx = 1 + int(rng() % 40), by = 1 + int(rng() % 5);
        std::vector<uint32_t> st;
        fill_block_states(seed, bx, by, st);
        ASSERT_EQ(st.size(), std::size_t(bx * by));
        uint32_t s = seed;
        for (std::size_t i = 0; i < st.size(); i++, s = lfsr_next(s)) ASSERT_EQ(st[i], s) << "seed " << seed << " i " << i;
        EXPECT_EQ(lfsr_next2(seed), lfsr_next(lfsr_next(seed)));
        EXPECT_EQ(lfsr_next3(seed), lfsr_next(lfsr_next(lfsr_next(seed))));
    }
}

TEST(FgcAdaptation, AveragesInsideAndReplicated) {
    FrameBuffer f(20, 12, PixelFormat{ChromaFormat::k400, 10});
    FrameView v = f.view();
    for (int y = 0; y < 12; y++)
        for (int x = 0; x < 20; x++) v.planes[0].row<uint16_t>(y)[x] = uint16_t(x < 16 ? 400 : 800);
    EXPECT_EQ(block_average_inside<uint16_t>(v.planes[0], 0, 0, 8, 10), 100);
    // 4 columns x 4 rows inside at (16, 8): all 800 -> 200
    EXPECT_EQ(block_average_inside<uint16_t>(v.planes[0], 16, 8, 8, 10), 200);
    // replicated: the same block reads its edge sample for everything outside
    EXPECT_EQ(block_average_replicated<uint16_t>(v.planes[0], 16, 8, 8, 10), 200);
    EXPECT_EQ(block_average_replicated<uint16_t>(v.planes[0], 8, 0, 16, 10), (8 * 400 + 8 * 800) * 16 / 256 / 4);
}

TEST(FgcDeblocking, FiltersBothSidesFromUnfilteredValues) {
    std::vector<int32_t> g(2 * 20, 0);
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 18; x++) g[y * 20 + x] = x < 8 ? 40 : -40;
    deblock_stripe_vertical_edges(g.data(), 20, 2, 18, 8);
    EXPECT_EQ(g[6], 40);
    EXPECT_EQ(g[7], (40 + 2 * 40 - 40) >> 2);
    EXPECT_EQ(g[8], (40 - 2 * 40 - 40) >> 2);
    EXPECT_EQ(g[9], -40);
    // the edge at 16 lies between two equal blocks: unchanged
    EXPECT_EQ(g[15], -40);
    EXPECT_EQ(g[16], -40);
    EXPECT_EQ(g[20 + 7], g[7]);
}

TEST(FgcBlending, ClipsAtZeroAndMaxForEveryBitDepth) {
    for (int bd = 8; bd <= 16; bd++) {
        const int maxv = (1 << bd) - 1;
        std::vector<uint16_t> src = {0, 1, uint16_t(maxv), uint16_t(maxv - 1), uint16_t(1 << (bd - 1))};
        std::vector<int32_t> grain = {-5, -100, 7, 100, 3};
        std::vector<uint16_t> dst(src.size());
        blend_row_additive<uint16_t>(src.data(), dst.data(), grain.data(), int(src.size()), bd);
        EXPECT_EQ(dst[0], 0);
        EXPECT_EQ(dst[1], 0);
        EXPECT_EQ(dst[2], maxv);
        EXPECT_EQ(dst[3], maxv);
        EXPECT_EQ(dst[4], (1 << (bd - 1)) + (3 << (bd - 8))) << "grain is scaled by 2^(bd-8)";
    }
    std::vector<uint8_t> s8 = {250, 3}, d8(2);
    std::vector<int32_t> g8 = {10, -10};
    blend_row_additive<uint8_t>(s8.data(), d8.data(), g8.data(), 2, 8);
    EXPECT_EQ(d8[0], 255);
    EXPECT_EQ(d8[1], 0);
}

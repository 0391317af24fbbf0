// VFGS templates (TR 23002-9 clause 7.5 / Annex B.2.2): frequency-filtering
// templates through the VVC DCT-2 matrix, AR templates, template pools.
#include <gtest/gtest.h>

#include <cmath>

#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "fgc/vfgs/vfgs_tables.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

struct Stats {
    double mean = 0, sd = 0, hcorr = 0;  // lag-1 horizontal correlation
    int maxabs = 0;
};

Stats stats(const GrainTemplate& t, int n) {
    Stats s;
    double sum = 0, sq = 0, lag = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            sum += t[y][x];
            sq += double(t[y][x]) * t[y][x];
            if (x + 1 < n) lag += double(t[y][x]) * t[y][x + 1];
            s.maxabs = std::max(s.maxabs, std::abs(int(t[y][x])));
        }
    const double cnt = double(n) * n;
    s.mean = sum / cnt;
    s.sd = std::sqrt(sq / cnt - s.mean * s.mean);
    s.hcorr = (lag / (n * (n - 1))) / (sq / cnt);
    return s;
}

ResolvedParams luma_rows(int model, const std::vector<std::array<int, 6>>& rows) {
    ResolvedParams r;
    r.model_id = model;
    r.log2_scale_factor = r.signalled_log2_scale_factor = 5;
    r.comp[0].present = true;
    int lo = 0;
    for (const auto& v : rows) {
        r.comp[0].intervals.push_back({lo, lo + 9, v});
        lo += 10;
    }
    return r;
}

}  // namespace

TEST(VfgsTables, Shapes) {
    EXPECT_EQ(kGaussianLut[0], -11);
    EXPECT_EQ(kGaussianLut[2047], 47);
    EXPECT_EQ(kSeedLut[0], 747538460u);
    EXPECT_EQ(kSeedLut[255], 1358954497u);
    // VVC DCT-2: first row flat 64, row 1 runs 91 .. -91, the 32-point basis rows are the even rows.
    for (int n = 0; n < 64; ++n) EXPECT_EQ(fgc::kVvcDct2_64[0][n], 64);
    EXPECT_EQ(fgc::kVvcDct2_64[1][0], 91);
    EXPECT_EQ(fgc::kVvcDct2_64[1][63], -91);
    EXPECT_EQ(fgc::kVvcDct2_64[32][0], 64);
    EXPECT_EQ(fgc::kVvcDct2_64[32][1], -64);
    // Rows are nearly orthogonal with norm ~ 64 * 64 * 64.
    long long dot = 0, norm = 0;
    for (int n = 0; n < 64; ++n) {
        dot += fgc::kVvcDct2_64[3][n] * fgc::kVvcDct2_64[5][n];
        norm += fgc::kVvcDct2_64[5][n] * fgc::kVvcDct2_64[5][n];
    }
    EXPECT_LT(std::llabs(dot), 200);
    EXPECT_NEAR(double(norm), 64.0 * 64 * 64, 64.0 * 64 * 64 * 0.01);
}

TEST(VfgsTemplates, FrequencyLumaStatistics) {
    const GrainTemplate wide = make_frequency_template_luma(14, 14);
    const GrainTemplate narrow = make_frequency_template_luma(2, 2);
    const Stats sw = stats(wide, 64), sn = stats(narrow, 64);
    // DC is removed: zero mean (up to rounding), values within +-127.
    EXPECT_LT(std::fabs(sw.mean), 0.5);
    EXPECT_LT(std::fabs(sn.mean), 0.5);
    EXPECT_LE(sw.maxabs, 127);
    EXPECT_GT(sw.sd, 5.0);
    // A low cut-off keeps only low frequencies: strongly correlated neighbours.
    EXPECT_GT(sn.hcorr, 0.9);
    EXPECT_LT(sw.hcorr, sn.hcorr);
    // Deterministic (no state outside the function).
    EXPECT_EQ(make_frequency_template_luma(14, 14), wide);
}

TEST(VfgsTemplates, FrequencyCutoffsOnlyRemoveCoefficients) {
    // The LFSR steps over every group whatever the cut-off, so the template of a
    // lower vertical cut-off is a band-limited version of the same noise: its
    // correlation with the wider one is clearly positive.
    const GrainTemplate a = make_frequency_template_luma(8, 8), b = make_frequency_template_luma(8, 14);
    double ab = 0, aa = 0, bb = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            ab += a[y][x] * b[y][x];
            aa += a[y][x] * a[y][x];
            bb += b[y][x] * b[y][x];
        }
    EXPECT_GT(ab / std::sqrt(aa * bb), 0.5);
}

TEST(VfgsTemplates, FrequencyChromaIs32x32) {
    const GrainTemplate t = make_frequency_template_chroma420(14, 14);
    const Stats s = stats(t, 32);
    EXPECT_LT(std::fabs(s.mean), 0.5);
    EXPECT_GT(s.sd, 5.0);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            if (y >= 32 || x >= 32) {
                ASSERT_EQ(t[y][x], 0) << y << "," << x;
            }
        }
}

TEST(VfgsTemplates, ArWithoutCoefficientsIsHalfAmplitudeNoise) {
    // All AR weights 0: buf = (Gaussian_LUT[r & 2047] + 1) >> 1 with r stepping
    // once per sample of the 82-wide buffer; the template is buf[9+y][9+x].
    const GrainTemplate t = make_ar_template_luma({100, 0, 0, 0, 32, 0}, 5);
    for (int y : {0, 1, 40, 63})
        for (int x : {0, 5, 63}) {
            const uint32_t r = lfsr_advance(kSeedLut[0], static_cast<uint32_t>((9 + y) * 82 + 9 + x));
            EXPECT_EQ(t[y][x], (kGaussianLut[r & 2047] + 1) >> 1) << y << "," << x;
        }
}

TEST(VfgsTemplates, ArLeftWeightCorrelatesHorizontally) {
    const Stats white = stats(make_ar_template_luma({100, 0, 0, 0, 32, 0}, 5), 64);
    const Stats ar = stats(make_ar_template_luma({100, 20, 0, 0, 32, 0}, 5), 64);
    EXPECT_LT(std::fabs(white.hcorr), 0.1);
    EXPECT_GT(ar.hcorr, 0.4);
    EXPECT_GT(ar.sd, white.sd);
    EXPECT_LE(ar.maxabs, 127);
}

TEST(VfgsTemplates, PoolSharesEqualRowsAndSortsByLowerBound) {
    // Rows 0 and 2 have equal values [1..5] (the scale [0] does not matter).
    ResolvedParams r = luma_rows(0, {{10, 4, 4, 0, 0, 0}, {20, 8, 8, 0, 0, 0}, {30, 4, 4, 0, 0, 0}});
    // Make the signalled order differ from the intensity order.
    r.comp[0].intervals[0].lower = 100;
    r.comp[0].intervals[0].upper = 120;
    const TemplatePools pools = select_template_pools(r);
    ASSERT_EQ(pools.luma.count, 2);
    EXPECT_EQ(pools.luma.slot[0].interval, 1);  // lower bound 10
    EXPECT_EQ(pools.luma.slot[1].interval, 0);  // lower bound 100
    EXPECT_EQ(find_template_slot(pools, r, 0, 2), 1);
    EXPECT_EQ(pools.chroma.count, 0);
}

TEST(VfgsTemplates, PoolKeepsFirstEightAndDropsTheRest) {
    std::vector<std::array<int, 6>> rows;
    for (int i = 0; i < 10; ++i) rows.push_back({50, 2 + i, 2 + i, 0, 0, 0});
    const ResolvedParams r = luma_rows(0, rows);
    const TemplatePools pools = select_template_pools(r);
    EXPECT_EQ(pools.luma.count, kMaxTemplates);
    EXPECT_EQ(find_template_slot(pools, r, 0, 7), 7);
    EXPECT_EQ(find_template_slot(pools, r, 0, 8), -1);
    EXPECT_EQ(find_template_slot(pools, r, 0, 9), -1);
    // Dropped rows take the template of the nearest lower intensity.
    const auto luts = build_luts(r, pools);
    EXPECT_EQ(luts[0].tmpl[79], 7);
    EXPECT_EQ(luts[0].tmpl[80], 7);
    EXPECT_EQ(luts[0].tmpl[99], 7);
    EXPECT_EQ(luts[0].scale[99], 50);
    EXPECT_EQ(luts[0].scale[100], 0);
}

TEST(VfgsTemplates, CbAndCrShareTheChromaPool) {
    ResolvedParams r;
    r.model_id = 0;
    r.log2_scale_factor = 5;
    r.comp[1].present = r.comp[2].present = true;
    r.comp[1].intervals = {{0, 127, {40, 6, 6, 0, 0, 0}}, {128, 255, {40, 10, 10, 0, 0, 0}}};
    r.comp[2].intervals = {{0, 255, {40, 10, 10, 0, 0, 0}}};
    const TemplatePools pools = select_template_pools(r);
    EXPECT_EQ(pools.chroma.count, 2);
    EXPECT_EQ(find_template_slot(pools, r, 2, 0), find_template_slot(pools, r, 1, 1));
}

TEST(VfgsTemplates, EmptySlotQuirkMirrorsTheReference) {
    // VFGS compares a candidate's values [1..5] with an empty pool slot as if
    // that slot held luma interval 0's values [0..4]. Row 1 below matches in
    // that way, so it gets no slot of its own and its intensities point at the
    // (stale) slot 1. Checked against the reference binary.
    const ResolvedParams r = luma_rows(0, {{5, 5, 5, 0, 0, 0}, {100, 5, 5, 5, 0, 0}});
    const TemplatePools pools = select_template_pools(r);
    EXPECT_EQ(pools.luma.count, 1);
    EXPECT_EQ(find_template_slot(pools, r, 0, 1), 1);
    EXPECT_EQ(build_luts(r, pools)[0].tmpl[15], 1);
}

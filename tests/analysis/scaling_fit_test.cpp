// The level-curve fits on hand-made observations: AV1 points stay inside the observed
// intensities, and the accuracy criterion counts every band alike.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "analysis/fgc_estimation.hpp"
#include "analysis/scaling_fit.hpp"

namespace filmgrain::analysis {
namespace {

// `count` blocks per intensity in [lo, hi] with level(i) and a little sampling spread.
void add_blocks(std::vector<BlockSample>& out, int lo, int hi, int count, double (*level)(int), unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> spread(0.0f, 0.02f);
    for (int i = lo; i <= hi; i++)
        for (int k = 0; k < count; k++) out.push_back({float(i) + 0.5f, float(level(i) * (1.0 + spread(rng)))});
}

TEST(ScalingFit, PointsStayInsideTheObservedIntensities) {
    // Chroma-like observations: a few dozen values around 128, level rising with intensity.
    std::vector<BlockSample> blocks;
    add_blocks(blocks, 104, 151, 3, [](int i) { return 1.5 + 0.04 * (i - 104); }, 1);
    const LevelCurve curve = fit_level_curve(blocks);
    const auto points = fit_piecewise_linear(curve, 10, 0.05);
    ASSERT_FALSE(points.empty());
    EXPECT_GE(points.front().value, curve.observed_low);
    EXPECT_LE(points.back().value, curve.observed_high);
    // Beyond the observations the description holds the end levels: no slope continued into
    // intensities nobody measured (at 255 the slope would have reached 5.6).
    const auto f = evaluate_piecewise_linear(points);
    const double top = 1.5 + 0.04 * 47;
    EXPECT_NEAR(f[255], top, 0.1 * top);
    EXPECT_NEAR(f[0], 1.5, 0.15);
    EXPECT_LE(worst_band_error(curve, f), 0.05);
}

TEST(ScalingFit, WorstBandErrorCountsEveryBandAlike) {
    // Many midtone blocks at level 3, a dark band seen in few blocks at level 2.
    std::vector<BlockSample> blocks;
    add_blocks(blocks, 32, 47, 1, [](int) { return 2.0; }, 2);
    add_blocks(blocks, 48, 223, 12, [](int) { return 3.0; }, 3);
    const LevelCurve curve = fit_level_curve(blocks);
    std::vector<double> flat(256, 0.0);
    double s = 0, w = 0;
    for (int i = 0; i < 256; i++) s += curve.weight[i] * curve.level[i], w += curve.weight[i];
    for (double& v : flat) v = s / w;  // one interval at the count-weighted mean
    int band = -1;
    const double e = worst_band_error(curve, flat, &band);
    EXPECT_GT(e, 0.3) << "the dark band is a third too strong under one interval";
    EXPECT_EQ(band, 32);
    // FGC: the darks get an interval of their own, at their own level.
    FgcTarget t;
    t.accuracy = 0.05;
    FgcComponentReport rep;
    choose_intervals(curve, t, rep);
    EXPECT_TRUE(rep.accurate);
    ASSERT_GE(rep.intervals.size(), 2u);
    for (const auto& iv : rep.intervals)
        if (iv.upper <= 40) EXPECT_NEAR(iv.level, 2.0, 0.1);
    bool dark_covered = false;
    for (const auto& iv : rep.intervals)
        if (iv.lower <= 36 && iv.upper >= 44) dark_covered = std::fabs(iv.level - 2.0) < 0.1;
    EXPECT_TRUE(dark_covered);
}

TEST(ScalingFit, ChromaGrainByItsTypicalLevel) {
    // Grain-free chroma: the denoiser's floor everywhere, a few leaked texture blocks lifting
    // one sub-range over the threshold.
    std::vector<BlockSample> blocks;
    add_blocks(blocks, 100, 160, 2, [](int) { return 0.15; }, 4);
    add_blocks(blocks, 128, 131, 6, [](int) { return 0.9; }, 5);
    LevelCurve curve;
    EXPECT_NE(fit_component_curve(blocks, 8, curve, true), "") << "chroma at the floor has no grain";
    EXPECT_EQ(fit_component_curve(blocks, 8, curve, false), "") << "luma's rule: the largest band";
    // Real chroma grain over a narrow range is kept.
    std::vector<BlockSample> grain;
    add_blocks(grain, 120, 136, 4, [](int) { return 1.2; }, 6);
    EXPECT_EQ(fit_component_curve(grain, 8, curve, true), "");
    // 10 bits: the threshold scales.
    for (auto& b : grain) b.sigma *= 0.25f;  // 0.3 code values at 10 bits = 0.075 at 8
    EXPECT_NE(fit_component_curve(grain, 10, curve, true), "");
}

}  // namespace
}  // namespace filmgrain::analysis

// Grain statistics on synthetic grain whose properties are known by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stats/grain_statistics.hpp"

using namespace filmgrain;
using namespace filmgrain::stats;

namespace {

FloatPlane white(int w, int h, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(0.f, float(sigma));
    FloatPlane f(w, h);
    for (float& v : f.v) v = n(rng);
    return f;
}

TEST(GrainStatistics, WhiteNoiseHasDeltaAutocovarianceAndFlatSpectrum) {
    const double s = 0.05;
    const FloatPlane g = white(256, 256, s, 1);
    const Autocovariance c = autocovariance(g, 3);
    const double var = s * s, sd = var * std::sqrt(2.0 / (256 * 256));  // sd of a sample (co)variance
    EXPECT_NEAR(c.at(0, 0), var, 5 * sd);
    for (auto [dx, dy] : {std::pair{1, 0}, {0, 1}, {2, -3}, {-1, -1}}) EXPECT_NEAR(c.at(dx, dy), 0, 5 * var / 256);
    EXPECT_EQ(c.at(2, -3), c.at(-2, 3));
    const PowerSpectrum ps = power_spectrum(g, 32);
    // 64 tiles, each periodogram bin ~ exponential: the radial means are within 15%.
    for (std::size_t r = 2; r < ps.radial.size(); r++) EXPECT_NEAR(ps.radial[r], var, 0.15 * var) << r;
    const GrainSize size = grain_size(c);
    EXPECT_LT(size.correlation_length, 1.0);
}

TEST(GrainStatistics, SmoothedNoiseIsLarger) {
    // Box-filtering white noise over k x k makes the autocorrelation a tent of half-width k.
    const FloatPlane w = white(200, 200, 1, 2);
    double prev = 0;
    for (int k : {1, 3, 5}) {
        FloatPlane g(200 - k, 200 - k);
        for (int y = 0; y < g.height; y++)
            for (int x = 0; x < g.width; x++) {
                double s = 0;
                for (int j = 0; j < k; j++)
                    for (int i = 0; i < k; i++) s += w.at(x + i, y + j);
                g.at(x, y) = float(s / k);
            }
        const GrainSize size = grain_size(autocovariance(g, 8));
        // tent: rho(d) = 1 - d/k crosses 1/e at d = k (1 - 1/e)
        EXPECT_NEAR(size.correlation_length, k * (1 - std::exp(-1.0)), 0.15 * k + 0.1) << k;
        EXPECT_GT(size.equivalent_diameter, prev);
        prev = size.equivalent_diameter;
    }
}

TEST(GrainStatistics, VarianceFollowsIntensity) {
    FloatPlane clean(256, 64), grainy(256, 64);
    const FloatPlane n = white(256, 64, 1, 3);
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 256; x++) {
            clean.at(x, y) = x / 256.f;
            grainy.at(x, y) = clean.at(x, y) + 0.1f * clean.at(x, y) * n.at(x, y);
        }
    const auto bins = variance_vs_intensity(clean, grain_of(clean, grainy), 4);
    ASSERT_EQ(bins.size(), 4u);
    for (const IntensityBin& b : bins) {
        EXPECT_EQ(b.count, 64 * 64);
        // E[(0.1 u n)^2] over u uniform in [lo, hi)
        const double expect = 0.01 * (b.hi * b.hi * b.hi - b.lo * b.lo * b.lo) / (3 * (b.hi - b.lo));
        EXPECT_NEAR(b.variance, expect, 0.1 * expect + 1e-7);
    }
}

TEST(GrainStatistics, BlendedBlockBoundariesLoseVariance) {
    // Independent noise per 16-wide block, the two columns at each seam replaced by the
    // average of both blocks' noise: variance halves there.
    const int b = 16;
    const FloatPlane a = white(256, 128, 1, 4), c = white(256, 128, 1, 5);
    FloatPlane g = a;
    for (int y = 0; y < 128; y++)
        for (int x = 0; x < 256; x++)
            if (x % b == 0 || x % b == b - 1) g.at(x, y) = float((a.at(x, y) + c.at(x, y)) / std::sqrt(2.0) / std::sqrt(2.0));
    const BoundaryVariance bv = block_boundary_variance(g, b);
    EXPECT_NEAR(bv.column_ratio(), 0.5, 0.05);
    EXPECT_NEAR(bv.row_ratio(), 1.0, 0.05);  // a row at a seam has the same mix of columns
    EXPECT_NEAR(block_boundary_variance(a, b).column_ratio(), 1.0, 0.05);
}

TEST(GrainStatistics, RepeatedTemplatesCorrelateAtTheirPeriod) {
    const FloatPlane t = white(32, 32, 1, 6);
    FloatPlane g(256, 256);
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) g.at(x, y) = t.at(x % 32, y % 32);
    const auto at = repetition_at_periods(g, {32, 17});
    ASSERT_EQ(at.size(), 6u);
    for (int i = 0; i < 3; i++) EXPECT_NEAR(at[i].correlation, 1.0, 1e-6);
    for (int i = 3; i < 6; i++) EXPECT_LT(std::abs(at[i].correlation), 0.1);
    const auto top = strongest_repetitions(g, 8, 40, 3);
    for (const auto& p : top) EXPECT_TRUE((p.dx == 32 || p.dx == 0) && (p.dy == 32 || p.dy == 0)) << p.dx << "," << p.dy;
    const FloatPlane w = white(256, 256, 1, 7);
    EXPECT_LT(strongest_repetitions(w, 8, 40, 1)[0].correlation, 0.05);
}

TEST(GrainStatistics, FrameToFrameCorrelation) {
    const FloatPlane a = white(128, 128, 1, 8), b = white(128, 128, 1, 9);
    EXPECT_NEAR(frame_to_frame_correlation(a, a), 1.0, 1e-9);
    EXPECT_NEAR(frame_to_frame_correlation(a, b), 0.0, 5.0 / 128);
    FloatPlane mix(128, 128);
    for (std::size_t i = 0; i < mix.v.size(); i++) mix.v[i] = 0.6f * a.v[i] + 0.8f * b.v[i];
    EXPECT_NEAR(frame_to_frame_correlation(a, mix), 0.6, 5.0 / 128);
    EXPECT_THROW(frame_to_frame_correlation(a, FloatPlane(3, 3)), std::exception);
}

}  // namespace

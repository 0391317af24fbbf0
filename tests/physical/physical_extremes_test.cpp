// Numerical stability of the Boolean model at the extremes of its parameters: every case
// asserts finite output in [0, 1] and a sample mean equal to the (clamped) grey level within
// 5 standard deviations, the deviation computed from the closed-form covariance, and each
// case's window is checked to be narrow enough (5 sd < 0.1) to catch a biased coverage.
#include <gtest/gtest.h>

#include <cmath>

#include "physical/boolean_covariance.hpp"
#include "physical/boolean_model.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

struct Extreme {
    const char* name;
    double radius, radius_sigma, grey, zoom;
    int samples, size;
    double filter_sigma = 0.8;
    // Independent pictures (seeds) averaged: where grains are large against the picture one
    // picture's mean varies too much to test it (sd / sqrt(seeds) is what is tested).
    int seeds = 1;
};

// Standard deviation of the mean of an output picture of w x h pixels, from the expected
// covariance of the N-sample output (summed over the lags it reaches).
double mean_sd(const BooleanModelParams& p, double grey, int w, int h) {
    const BooleanCovariance c(p, grey);
    const int reach = int(std::ceil((c.coverage_support() + 6 * p.filter_sigma / p.zoom) * p.zoom)) + 1;
    double s = 0;
    for (int dy = -std::min(reach, h - 1); dy <= std::min(reach, h - 1); dy++)
        for (int dx = -std::min(reach, w - 1); dx <= std::min(reach, w - 1); dx++)
            s += c.expected_monte_carlo(dx, dy, p.samples) * (w - std::abs(dx)) * (h - std::abs(dy));
    return std::sqrt(std::max(s, 0.0)) / (double(w) * h);
}

// Half-width of the window each case tests its mean in: a coverage 1 - exp(-lambda pi r^2)
// with lambda off by 5 % moves the mean at grey 0.5 by 0.017.
constexpr double kWindow = 0.015;

class BooleanExtremes : public ::testing::TestWithParam<Extreme> {};

TEST_P(BooleanExtremes, FiniteBoundedAndUnbiased) {
    const Extreme e = GetParam();
    BooleanModelParams p;
    p.radius_mean = e.radius;
    p.radius_sigma = e.radius_sigma;
    p.zoom = e.zoom;
    p.samples = e.samples;
    p.filter_sigma = e.filter_sigma;
    p.threads = 2;
    const FloatPlane u(e.size, e.size, float(e.grey));
    // As many independent pictures as make 5 sd of the mean at most kWindow (from the
    // closed-form sd of one picture's mean), so that a coverage biased by a few percent fails.
    const int w1 = zoomed_size(e.size, e.zoom);
    const double sd1 = mean_sd(p, double(float(e.grey)), w1, w1);
    const int seeds = std::max(e.seeds, int(std::ceil(std::pow(5 * sd1 / kWindow, 2))));
    ASSERT_LE(seeds, 2000) << e.name << ": one picture's mean has sd " << sd1 << "; make the picture larger";
    double mean = 0;
    FloatPlane out;
    for (int k = 0; k < seeds; k++) {
        render_boolean_model(u, p, {}, uint64_t(17 + k), out);
        ASSERT_EQ(out.width, zoomed_size(e.size, e.zoom));
        double m = 0;
        for (float v : out.v) {
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GE(v, 0.f);
            ASSERT_LE(v, 1.f);
            m += v;
        }
        mean += m / double(out.v.size());
    }
    mean /= seeds;
    const double expected = std::min(double(float(e.grey)), 1 - p.grey_epsilon);
    const double sd = sd1 / std::sqrt(double(seeds));
    ASSERT_LE(5 * sd, kWindow + 1e-12);
    EXPECT_NEAR(mean, expected, 5 * sd + 1e-6) << e.name << " sd " << sd;
}

INSTANTIATE_TEST_SUITE_P(
    Extremes, BooleanExtremes,
    ::testing::Values(Extreme{"grey 0", 0.1, 0, 0.0, 1, 16, 32}, Extreme{"grey 1e-4", 0.1, 0, 1e-4, 1, 32, 64},
                      Extreme{"grey 1 (epsilon guard)", 0.1, 0, 1.0, 1, 16, 32},
                      Extreme{"grey 1 - 1e-6", 0.2, 0, 1 - 1e-6, 1, 16, 32},
                      Extreme{"grey 0.9999 small radius", 0.02, 0, 0.9999, 1, 8, 12},
                      Extreme{"tiny radius", 0.01, 0, 0.5, 1, 16, 12}, Extreme{"large radius", 3, 0, 0.5, 1, 8, 128},
                      Extreme{"sigma_r 10x mu_r", 0.05, 0.5, 0.4, 1, 32, 48, 0.8, 8},
                      Extreme{"sigma_r 50x mu_r", 0.1, 5, 0.6, 1, 16, 48, 0.8, 48}, Extreme{"zoom 0.05", 0.3, 0, 0.5, 0.05, 64, 200},
                      Extreme{"zoom 16", 0.3, 0, 0.5, 16, 16, 6, 0.8, 8}, Extreme{"N = 1", 0.1, 0, 0.3, 1, 1, 64},
                      Extreme{"no filter", 0.3, 0, 0.7, 1, 4, 64, 0.0}),
    [](const ::testing::TestParamInfo<Extreme>& i) { return "case" + std::to_string(i.index); });

// Grains far larger than the picture (radius 40 pixels on 16x16): each picture is nearly one
// Bernoulli draw, black or white almost everywhere, so one picture's mean says little (its sd,
// from the covariance, is about 0.3). The mean over K = 4096 independent seeds has sd / 64, and
// the spread of the K means must itself be that sd (a renderer that finds only nearby grains
// makes every picture black: mean 0, spread 0).
TEST(BooleanExtremes, HugeGrainsAreUnbiasedOverSeeds) {
    BooleanModelParams p;
    p.radius_mean = 40;
    p.samples = 4;
    p.threads = 2;
    const int n = 16, seeds = 4096;
    const double grey = 0.5;
    double s1 = 0, s2 = 0;
    for (int seed = 1; seed <= seeds; seed++) {
        FloatPlane out;
        render_boolean_model(FloatPlane(n, n, float(grey)), p, {}, uint64_t(seed), out);
        double m = 0;
        for (float v : out.v) m += v;
        m /= out.v.size();
        s1 += m;
        s2 += m * m;
    }
    const double mean = s1 / seeds, spread = std::sqrt((s2 - s1 * s1 / seeds) / (seeds - 1));
    const double sd_one = mean_sd(p, grey, n, n);
    ASSERT_GT(sd_one, 0.2);  // the premise: one picture cannot test the mean
    EXPECT_NEAR(mean, grey, 4 * sd_one / std::sqrt(double(seeds))) << "sd of one picture's mean " << sd_one;
    // The sample sd of K normal-ish means is within about 4 / sqrt(2 (K - 1)) of its value
    // relatively (the means are bounded in [0, 1]; with this many the bound is close enough).
    EXPECT_NEAR(spread / sd_one, 1.0, 4 / std::sqrt(2.0 * (seeds - 1))) << "spread " << spread << " sd " << sd_one;
}

TEST(BooleanExtremes, OneSampleGivesBinaryOutputWithBernoulliVariance) {
    BooleanModelParams p;
    p.samples = 1;
    p.radius_mean = 0.1;
    const double grey = 0.3;
    FloatPlane out;
    render_boolean_model(FloatPlane(128, 128, float(grey)), p, {}, 4, out);
    double s1 = 0, s2 = 0;
    for (float v : out.v) {
        ASSERT_TRUE(v == 0.f || v == 1.f);
        s1 += v;
        s2 += v * v;
    }
    const double m = s1 / out.v.size(), var = s2 / out.v.size() - m * m;
    EXPECT_NEAR(var, m * (1 - m), 1e-9);  // a 0/1 variable
    EXPECT_NEAR(m, grey, 5 * mean_sd(p, grey, 128, 128));
}

TEST(BooleanExtremes, ToleranceBelowReachIsCappedAtMaxSamples) {
    BooleanModelParams p;
    p.radius_mean = 0.2;
    p.tolerance = 1e-4;  // would need 25 million samples at grey 0.5
    p.max_samples = 256;
    FloatPlane out;
    const RenderReport r = render_boolean_model(FloatPlane(8, 8, 0.5f), p, {}, 1, out);
    EXPECT_EQ(r.max_samples, 256);
    EXPECT_EQ(r.min_samples, 256);
    for (float v : out.v) ASSERT_TRUE(std::isfinite(v) && v >= 0 && v <= 1);
}

TEST(BooleanExtremes, EdgePixelsAreNotDarkened) {
    // Intensity continues past the picture edge, so a border pixel has the same mean.
    BooleanModelParams p;
    p.radius_mean = 0.5;
    p.samples = 64;
    const int n = 64;
    FloatPlane out;
    render_boolean_model(FloatPlane(n, n, 0.5f), p, {}, 2, out);
    double border = 0;
    for (int i = 0; i < n; i++) border += out.at(i, 0) + out.at(0, i) + out.at(i, n - 1) + out.at(n - 1, i);
    border /= 4 * n;
    // 256 border pixels along lines: sd of their mean <= sqrt(C(0) * 2 * reach / 256)
    const BooleanCovariance c(p, 0.5);
    EXPECT_NEAR(border, 0.5, 5 * std::sqrt(c.expected_monte_carlo(0, 0, 64) * 2 * 5 / (4.0 * n)));
}

}  // namespace

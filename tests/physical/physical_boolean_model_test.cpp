// The Boolean-model renderer against its closed-form statistics (boolean_covariance.hpp):
// sample mean = grey level and sample (co)variance = the covariance for the realized Monte
// Carlo offsets, within tolerances computed from that same covariance (the variance of a
// spatial average of a correlated field), at several radii, grey levels and N.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "filmgrain/error.hpp"
#include "physical/boolean_covariance.hpp"
#include "physical/boolean_model.hpp"
#include "physical/monte_carlo_offsets.hpp"
#include "boolean_render_split.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

struct Moments {
    double mean = 0, var = 0, cov_x1 = 0, cov_y1 = 0, cov_d1 = 0;
};

Moments moments(const FloatPlane& f) {
    Moments m;
    const double n = double(f.v.size());
    for (float v : f.v) m.mean += v;
    m.mean /= n;
    double cx = 0, cy = 0, cd = 0, v2 = 0;
    int nx = 0, ny = 0, nd = 0;
    for (int y = 0; y < f.height; y++)
        for (int x = 0; x < f.width; x++) {
            const double a = f.at(x, y) - m.mean;
            v2 += a * a;
            if (x + 1 < f.width) cx += a * (f.at(x + 1, y) - m.mean), nx++;
            if (y + 1 < f.height) cy += a * (f.at(x, y + 1) - m.mean), ny++;
            if (x + 1 < f.width && y + 1 < f.height) cd += a * (f.at(x + 1, y + 1) - m.mean), nd++;
        }
    m.var = v2 / n;
    m.cov_x1 = cx / nx;
    m.cov_y1 = cy / ny;
    m.cov_d1 = cd / nd;
    return m;
}

// Variance of the spatial mean over an M-pixel square, and the standard deviation of a
// sample covariance, from the covariance function c(dx, dy) (Gaussian-field approximation:
// Var(mean) = sum_d c(d) / M, Var(sample cov) ~ sum_d c(d)^2 / M * 2).
struct Tolerances {
    double mean_sd, cov_sd;
};

template <typename Cov>
Tolerances tolerances(Cov&& c, int pixels, int reach) {
    double s1 = 0, s2 = 0;
    for (int dy = -reach; dy <= reach; dy++)
        for (int dx = -reach; dx <= reach; dx++) {
            const double v = c(dx, dy);
            s1 += v;
            s2 += v * v;
        }
    return {std::sqrt(std::max(s1, 0.0) / pixels), std::sqrt(2 * s2 / pixels)};
}

struct Case {
    double radius, radius_sigma, grey, zoom;
    int samples, size;
};

class BooleanStatistics : public ::testing::TestWithParam<Case> {};

TEST_P(BooleanStatistics, MeanAndCovarianceMatchClosedForm) {
    const Case c = GetParam();
    BooleanModelParams p;
    p.radius_mean = c.radius;
    p.radius_sigma = c.radius_sigma;
    p.zoom = c.zoom;
    p.samples = c.samples;
    p.threads = 2;
    p.seed = 7;
    const FloatPlane u(c.size, c.size, float(c.grey));
    FloatPlane out;
    const uint64_t plane_seed = 11;
    render_boolean_model(u, p, {}, plane_seed, out);
    const Moments m = moments(out);

    const BooleanCovariance cov(p, c.grey);
    std::vector<double> xi = monte_carlo_offsets(p, plane_seed, c.samples);
    auto cf = [&](int dx, int dy) { return cov.given_offsets(dx, dy, xi); };
    const int reach = int(std::ceil((cov.coverage_support() + 5 * p.filter_sigma / p.zoom) * p.zoom));
    const Tolerances tol = tolerances(cf, int(out.v.size()), reach);

    // 5 standard deviations (plus float rounding) for every comparison.
    EXPECT_NEAR(m.mean, double(float(c.grey)), 5 * tol.mean_sd + 1e-6);
    // The sample variance about the sample mean loses Var(mean).
    EXPECT_NEAR(m.var, cf(0, 0) - tol.mean_sd * tol.mean_sd, 5 * tol.cov_sd);
    EXPECT_NEAR(m.cov_x1, cf(1, 0), 5 * tol.cov_sd);
    EXPECT_NEAR(m.cov_y1, cf(0, 1), 5 * tol.cov_sd);
    EXPECT_NEAR(m.cov_d1, cf(1, 1), 5 * tol.cov_sd);
    // The realized covariance is itself close to its mean over offsets, C/N + (1-1/N) C_s.
    EXPECT_NEAR(cf(0, 0), cov.expected_monte_carlo(0, 0, c.samples), 0.35 * cf(0, 0));
}

INSTANTIATE_TEST_SUITE_P(RadiiGreyLevels, BooleanStatistics,
                         ::testing::Values(Case{0.05, 0, 0.5, 1, 64, 128}, Case{0.05, 0, 0.15, 1, 32, 128},
                                           Case{0.3, 0, 0.8, 1, 32, 128}, Case{1.0, 0, 0.4, 1, 16, 128},
                                           Case{0.2, 0.1, 0.6, 1, 32, 128}, Case{0.5, 0, 0.5, 2, 16, 64}));

TEST(BooleanRenderer, PixelWiseAndGrainWiseAgreeExactly) {
    for (const Case c : {Case{0.05, 0, 0.5, 1, 16, 24}, Case{0.7, 0.3, 0.3, 1, 8, 24}, Case{0.4, 0, 0.6, 3, 8, 12}}) {
        BooleanModelParams p;
        p.radius_mean = c.radius;
        p.radius_sigma = c.radius_sigma;
        p.zoom = c.zoom;
        p.samples = c.samples;
        FloatPlane u(c.size, c.size);
        for (int y = 0; y < c.size; y++)
            for (int x = 0; x < c.size; x++) u.at(x, y) = float((x * 7 + y * 3) % 11) / 10.f;
        FloatPlane a, b;
        p.algorithm = BooleanAlgorithm::kPixelWise;
        EXPECT_EQ(render_boolean_model(u, p, {}, 3, a).algorithm, BooleanAlgorithm::kPixelWise);
        p.algorithm = BooleanAlgorithm::kGrainWise;
        EXPECT_EQ(render_boolean_model(u, p, {}, 3, b).algorithm, BooleanAlgorithm::kGrainWise);
        EXPECT_EQ(a.v, b.v) << "radius " << c.radius;
    }
}

TEST(BooleanRenderer, AutomaticChoiceFollowsGrainSize) {
    const FloatPlane u(16, 16, 0.5f);
    FloatPlane out;
    BooleanModelParams p;
    p.samples = 4;
    p.radius_mean = 0.05;
    EXPECT_EQ(render_boolean_model(u, p, {}, 1, out).algorithm, BooleanAlgorithm::kPixelWise);
    p.radius_mean = 4;  // few large grains covering many pixels each
    EXPECT_EQ(render_boolean_model(u, p, {}, 1, out).algorithm, BooleanAlgorithm::kGrainWise);
}

TEST(BooleanRenderer, SameOutputForEveryThreadCountTilingAndRegion) {
    const FloatPlane u = test_support::wavy_plane(80, 70, 0.1, 0.13);
    BooleanModelParams p;
    p.radius_mean = 0.1;
    p.samples = 24;
    p.zoom = 1.5;  // tiles of 48 output pixels: several tiles, the last ones partial
    test_support::expect_render_independent_of_split(u, p, 5, {37, 21, 50, 61});
}

TEST(BooleanRenderer, ToleranceStopsEachPixelAtTheTargetError) {
    const double grey = 0.5, tol = 0.03;
    const FloatPlane u(32, 32, float(grey));
    BooleanModelParams p;
    p.radius_mean = 0.05;
    p.tolerance = tol;
    FloatPlane out;
    const RenderReport rep = render_boolean_model(u, p, {}, 2, out);
    // sqrt(p(1-p)/n) <= tol needs n >= p(1-p)/tol^2; pixel values spread around 0.5, so
    // the N used is at most that for p = 1/2 (rounded up to the 16-sample checks).
    const double n_half = grey * (1 - grey) / (tol * tol);
    EXPECT_LE(rep.max_samples, int(n_half) + 16);
    EXPECT_GE(rep.min_samples, p.min_samples);
    EXPECT_GT(rep.mean_samples, 0.5 * n_half);
    EXPECT_LT(rep.mean_samples, n_half + 16);
    double mean = 0;
    for (float v : out.v) mean += v;
    EXPECT_NEAR(mean / out.v.size(), grey, 0.05);
}

TEST(BooleanRenderer, BlackPlaneIsSkippedAndExact) {
    const FloatPlane u(40, 30, 0.f);
    FloatPlane out;
    BooleanModelParams p;
    const RenderReport rep = render_boolean_model(u, p, {}, 1, out);
    EXPECT_EQ(rep.grains, 0u);
    EXPECT_EQ(rep.tiles, 0);
    for (float v : out.v) ASSERT_EQ(v, 0.f);
}

TEST(BooleanRenderer, InvalidParametersNameFieldValueAndRange) {
    const FloatPlane u(4, 4, 0.5f);
    FloatPlane out;
    BooleanModelParams p;
    p.radius_mean = -1;
    try {
        render_boolean_model(u, p, {}, 1, out);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
        EXPECT_NE(std::string(e.what()).find("radius_mean = -1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(0, 256]"), std::string::npos) << e.what();
    }
    p = {};
    p.radius_mean = 0.001;  // ~2e6 grains per pixel
    EXPECT_THROW(render_boolean_model(u, p, {}, 1, out), Error);
    p = {};
    p.zoom = 0;
    EXPECT_THROW(render_boolean_model(u, p, {}, 1, out), Error);
    p = {};
    EXPECT_THROW(render_boolean_model(u, p, OutputRegion{2, 2, 4, 4}, 1, out), Error);
}

}  // namespace

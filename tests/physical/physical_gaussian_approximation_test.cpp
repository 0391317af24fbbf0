// The Gaussian texture: its kernel's covariance and the covariance measured on a rendered
// picture against the Boolean model's closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "physical/boolean_covariance.hpp"
#include "physical/gaussian_approximation.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

TEST(GaussianApproximation, KernelCovarianceMatchesClosedForm) {
    for (double radius : {0.05, 0.5, 1.5}) {
        BooleanModelParams p;
        p.radius_mean = radius;
        const GaussianApproximation g(p, 64);
        for (int level : {8, 32, 60}) {
            const double u = level / 63.0;
            const double c0 = g.target_covariance(u, 0, 0);
            ASSERT_GT(c0, 0);
            for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {1, 1}, {2, 1}, {3, 0}})
                // 1% of the variance: the spectral square root is exact on its grid, the
                // crop drops 1e-4 of the kernel's energy.
                EXPECT_NEAR(g.kernel_covariance(level, dx, dy), g.target_covariance(u, dx, dy), 0.01 * c0)
                    << "radius " << radius << " level " << level << " lag " << dx << "," << dy;
        }
    }
}

TEST(GaussianApproximation, RenderedCovarianceMatchesClosedForm) {
    BooleanModelParams p;
    p.radius_mean = 0.5;
    p.threads = 2;
    const GaussianApproximation g(p);
    const int n = 256;
    const double grey = 128 / 255.0;
    const FloatPlane u(n, n, float(grey));
    FloatPlane out;
    g.render(u, {}, 3, out);
    EXPECT_EQ(g.kernels_built(), 1);  // one grey level in the picture, one kernel
    double mean = 0;
    for (float v : out.v) mean += v;
    mean /= out.v.size();
    const double c0 = g.target_covariance(grey, 0, 0);
    // sd of a spatial mean of a correlated field: sqrt(sum_d C(d) / M) <= sqrt(25 C0 / M)
    EXPECT_NEAR(mean, grey, 5 * std::sqrt(25 * c0 / (n * n)));
    for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {0, 1}, {2, 2}}) {
        double s = 0;
        int cnt = 0;
        for (int y = 0; y + dy < n; y++)
            for (int x = 0; x + dx < n; x++, cnt++) s += (out.at(x, y) - mean) * (out.at(x + dx, y + dy) - mean);
        // sd of a sample covariance ~ C0 sqrt(2 * (correlated area ~ 25) / M): 5 sd.
        EXPECT_NEAR(s / cnt, g.target_covariance(grey, dx, dy), 5 * c0 * std::sqrt(50.0 / cnt)) << dx << "," << dy;
    }
}

TEST(GaussianApproximation, RegionMatchesFullPictureAndBlackStaysBlack) {
    BooleanModelParams p;
    p.radius_mean = 0.2;
    const GaussianApproximation g(p, 32);
    FloatPlane u(40, 30);
    for (int y = 0; y < 30; y++)
        for (int x = 0; x < 40; x++) u.at(x, y) = x < 10 ? 0.f : float(x) / 40;
    FloatPlane full, roi;
    g.render(u, {}, 9, full);
    g.render(u, {5, 4, 20, 17}, 9, roi);
    for (int y = 0; y < 17; y++)
        for (int x = 0; x < 20; x++) ASSERT_EQ(roi.at(x, y), full.at(x + 5, y + 4));
    for (int y = 0; y < 30; y++)
        for (int x = 0; x < 10; x++) ASSERT_EQ(full.at(x, y), 0.f);
}

TEST(BooleanClosedForm, CoverageCovarianceBasics) {
    EXPECT_NEAR(disc_intersection_area(1, 0), M_PI, 1e-12);
    EXPECT_EQ(disc_intersection_area(1, 2), 0);
    EXPECT_NEAR(disc_intersection_area(1, 1), 2 * M_PI / 3 - std::sqrt(3) / 2, 1e-12);
    for (double sigma : {0.0, 0.3}) {
        BooleanModelParams p;
        p.radius_mean = 0.5;
        p.radius_sigma = sigma;
        for (double u : {0.1, 0.5, 0.9}) {
            const BooleanCovariance c(p, u);
            // Var of a Bernoulli(u); the log-normal lens integral is numerical.
            EXPECT_NEAR(c.coverage(0), u * (1 - u), sigma > 0 ? 1e-5 : 1e-12);
            EXPECT_EQ(c.coverage(c.coverage_support() + 1e-9), 0);
            EXPECT_LE(c.filtered(0), u * (1 - u));
            EXPECT_GT(c.filtered(0), 0);
            // Monotone in distance, and filtering with a tiny sigma changes nothing.
            EXPECT_GE(c.filtered(0.2), c.filtered(0.4));
            BooleanModelParams q = p;
            q.filter_sigma = 1e-4;
            EXPECT_NEAR(BooleanCovariance(q, u).filtered(0.3), c.coverage(0.3), 2e-3 * u * (1 - u));
        }
    }
}

TEST(BooleanClosedForm, LogNormalMomentsMatchSampling) {
    const GrainRadiusLaw law(0.1, 0.2);
    double s1 = 0, s2 = 0;
    const int n = 400000;
    // Riemann sum over the normal quantile function is exact enough: midpoint in z.
    double w = 0;
    for (int i = 0; i < n; i++) {
        const double z = -9 + 18.0 * (i + 0.5) / n;
        const double pz = std::exp(-0.5 * z * z);
        const double r = law.radius_from_normal(z);
        s1 += pz * r;
        s2 += pz * r * r;
        w += pz;
    }
    EXPECT_NEAR(s1 / w, law.mean(), 1e-6);
    EXPECT_NEAR(s2 / w, law.mean_square(), 1e-6);
    EXPECT_NEAR(law.mean(), 0.1, 0.002);  // the cap at the 0.999 quantile removes little
}

}  // namespace

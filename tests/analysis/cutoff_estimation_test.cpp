// Cut-off matching on lag correlations: the lag sums measure what they claim, and each axis
// takes the model that correlates like the observation.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "analysis/cutoff_estimation.hpp"

namespace filmgrain::analysis {
namespace {

// Lag sums with correlation rho^k along x and sigma^k along y.
LagSums geometric(double rho, double sigma) {
    LagSums s;
    s.energy = 1000, s.samples = 1000;
    for (int k = 1; k <= kMaxCorrelationLag; k++) {
        s.x_pairs[k] = s.y_pairs[k] = 500;
        s.x[k] = 500 * std::pow(rho, k);
        s.y[k] = 500 * std::pow(sigma, k);
    }
    return s;
}

CutoffModels models() {
    CutoffModels m;  // finer grain (higher cut-off): less correlated
    for (int c = kMinCutoff; c <= kMaxCutoff; c++) m.lags[c] = geometric(0.95 - 0.06 * c, 0.95 - 0.06 * c);
    return m;
}

TEST(CutoffEstimation, LagSumsMeasureTheCorrelation) {
    // AR(1) along x with rho 0.6, white along y
    cv::Mat g(64, 64, CV_32F);
    cv::RNG rng(3);
    for (int y = 0; y < 64; y++) {
        float prev = 0;
        for (int x = 0; x < 64 + 32; x++) {
            const float v = float(0.6 * prev + rng.gaussian(1.0));
            if (x >= 32) g.at<float>(y, x - 32) = v;
            prev = v;
        }
    }
    LagSums s;
    for (int i = 0; i < 40; i++) {
        cv::Mat h = g.clone();
        cv::RNG r(i);
        for (int y = 0; y < 64; y++) {
            float prev = 0;
            for (int x = 0; x < 96; x++) {
                const float v = float(0.6 * prev + r.gaussian(1.0));
                if (x >= 32) h.at<float>(y, x - 32) = v;
                prev = v;
            }
        }
        accumulate_lags(h, s);
    }
    EXPECT_NEAR(s.rx(1), 0.6, 0.03);
    EXPECT_NEAR(s.rx(2), 0.36, 0.04);
    EXPECT_NEAR(s.ry(1), 0.0, 0.03);
    LagSums none;
    EXPECT_EQ(none.rx(1), 0.0);
}

TEST(CutoffEstimation, EachAxisTakesTheModelThatCorrelatesAlike) {
    const CutoffModels m = models();
    for (int ch : {2, 7, 14})
        for (int cv_ : {3, 8, 13}) {
            const CutoffEstimate e = match_cutoffs(geometric(0.95 - 0.06 * ch, 0.95 - 0.06 * cv_), m);
            EXPECT_EQ(e.horizontal, ch);
            EXPECT_EQ(e.vertical, cv_);
            EXPECT_NEAR(e.horizontal_mismatch, 0.0, 1e-12);
        }
    // between two models: the nearer
    EXPECT_EQ(match_cutoffs(geometric(0.95 - 0.06 * 6.2, 0.5), m).horizontal, 6);
}

TEST(CutoffEstimation, BinsSelectedByIntensity) {
    PlaneObservations obs;
    obs.lags[2] = geometric(0.5, 0.5);  // 8-bit 32..47
    obs.lags[10] = geometric(0.2, 0.2);  // 160..175
    EXPECT_NEAR(lag_sums_in(obs, 0, 100).rx(1), 0.5, 1e-12);
    EXPECT_NEAR(lag_sums_in(obs, 150, 255).rx(1), 0.2, 1e-12);
    EXPECT_NEAR(lag_sums_in(obs, 0, 255).rx(1), 0.35, 1e-12);
}

}  // namespace
}  // namespace filmgrain::analysis

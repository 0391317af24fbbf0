// Cut-off matching on lag correlations: the lag sums measure what they claim, and the pair
// whose model correlates like the observation at the matched lags wins, diagonals included.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "analysis/cutoff_estimation.hpp"

namespace filmgrain::analysis {
namespace {

// Lag sums with correlation rho^k along x and sigma^k along y, and `diagonal` at (1,1) and
// (1,-1) (separable grain: rho * sigma).
LagSums geometric(double rho, double sigma, double diagonal = -1) {
    LagSums s;
    s.energy = 1000, s.samples = 1000;
    for (int k = 1; k <= kMaxCorrelationLag; k++) {
        s.x_pairs[k] = s.y_pairs[k] = 500;
        s.x[k] = 500 * std::pow(rho, k);
        s.y[k] = 500 * std::pow(sigma, k);
    }
    for (int d = 0; d < 2; d++) {
        s.diagonal_pairs[d] = 500;
        s.diagonal[d] = 500 * (diagonal < 0 ? rho * sigma : diagonal);
    }
    return s;
}

double rho_of(int cutoff) { return 0.95 - 0.06 * cutoff; }  // finer grain (higher cut-off): less correlated

CutoffModels models() {
    CutoffModels m;
    for (int h = kMinCutoff; h <= kMaxCutoff; h++)
        for (int v = kMinCutoff; v <= kMaxCutoff; v++) m.pairs[h][v] = geometric(rho_of(h), rho_of(v));
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
    EXPECT_NEAR(s.rd(0), 0.0, 0.03);  // rows independent: nothing on the diagonals
    EXPECT_NEAR(s.rd(1), 0.0, 0.03);
    LagSums none;
    EXPECT_EQ(none.rx(1), 0.0);
    EXPECT_EQ(none.rd(0), 0.0);
}

TEST(CutoffEstimation, DiagonalLagsMeasureTheCorrelation) {
    // g = w(x, y) + w(x + 1, y + 1): correlation 1/2 at (1,1), none at (1,-1) or on the axes
    cv::RNG rng(5);
    LagSums s;
    for (int i = 0; i < 40; i++) {
        cv::Mat w(65, 65, CV_32F);
        rng.fill(w, cv::RNG::NORMAL, 0.0, 1.0);
        cv::Mat g = w(cv::Rect(0, 0, 64, 64)) + w(cv::Rect(1, 1, 64, 64));
        accumulate_lags(g, s);
    }
    EXPECT_NEAR(s.rd(0), 0.5, 0.03);
    EXPECT_NEAR(s.rd(1), 0.0, 0.03);
    EXPECT_NEAR(s.rx(1), 0.0, 0.03);
    EXPECT_NEAR(s.ry(1), 0.0, 0.03);
}

TEST(CutoffEstimation, ThePairThatCorrelatesAlikeWins) {
    const CutoffModels m = models();
    for (int ch : {2, 7, 14})
        for (int cv_ : {3, 8, 13}) {
            const CutoffEstimate e = match_cutoffs(geometric(rho_of(ch), rho_of(cv_)), m);
            EXPECT_EQ(e.horizontal, ch);
            EXPECT_EQ(e.vertical, cv_);
            EXPECT_NEAR(e.mismatch, 0.0, 1e-12);
        }
    // between two models: the nearer
    EXPECT_EQ(match_cutoffs(geometric(rho_of(6) - 0.2 * 0.06, 0.5), m).horizontal, 6);
}

TEST(CutoffEstimation, TheDiagonalsWeighInTheChoice) {
    // Models whose diagonal is no product of the axes: pair (h, v) correlates rho(h) and
    // rho(v) on the axes, and the diagonal rises with h + v. An observation between the axial
    // correlations of cut-offs 8 and 9 on both axes, with the diagonal of pair (9, 9), is pair
    // (9, 9): the axes alone leave it a tie, which per-axis matching breaks without looking.
    CutoffModels m;
    const auto diagonal = [](int h, int v) { return 0.05 * (h + v) - 0.4; };
    for (int h = kMinCutoff; h <= kMaxCutoff; h++)
        for (int v = kMinCutoff; v <= kMaxCutoff; v++) m.pairs[h][v] = geometric(rho_of(h), rho_of(v), diagonal(h, v));
    const double mid = (rho_of(8) + rho_of(9)) / 2;
    for (int pick : {8, 9}) {
        const CutoffEstimate e = match_cutoffs(geometric(mid, mid, diagonal(pick, pick)), m);
        EXPECT_EQ(e.horizontal, pick);
        EXPECT_EQ(e.vertical, pick);
    }
}

// Lag sums of `samples` samples correlating like the separable model of pair (h, v).
LagSums observed_like(int h, int v, double samples) {
    LagSums s = geometric(rho_of(h), rho_of(v));
    const double scale = samples / s.samples;
    for (auto* a : {&s.x, &s.y, &s.x_pairs, &s.y_pairs})
        for (double& e : *a) e *= scale;
    for (auto* a : {&s.diagonal, &s.diagonal_pairs})
        for (double& e : *a) e *= scale;
    s.energy *= scale, s.samples = samples;
    return s;
}

TEST(CutoffEstimation, AnIntervalKeepsThePooledPairUnlessItsOwnFitsBetterThanItsNoise) {
    const CutoffModels m = models();
    CutoffEstimate pooled;
    pooled.horizontal = 10, pooled.vertical = 10;
    // an interval correlating like (9, 10), one step from the pooled pair (mean difference
    // 0.025 over the matched lags): seen in one 64x64 block (twice the standard error 0.041)
    // the step is within the noise, in 8 blocks (0.015) it is not
    EXPECT_EQ(interval_cutoffs(observed_like(9, 10, 4096), pooled, m), std::make_pair(10, 10));
    EXPECT_EQ(interval_cutoffs(observed_like(9, 10, 8 * 4096), pooled, m), std::make_pair(9, 10));
    // far from it: its own pair even in one block
    EXPECT_EQ(interval_cutoffs(observed_like(4, 4, 4096), pooled, m), std::make_pair(4, 4));
    // an interval that is the pooled pair keeps it
    EXPECT_EQ(interval_cutoffs(observed_like(10, 10, 400 * 4096), pooled, m), std::make_pair(10, 10));
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

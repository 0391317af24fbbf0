// Cut-off matching: marginals normalized to shape, the nearest model chosen per axis.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/cutoff_estimation.hpp"

namespace filmgrain::analysis {
namespace {

// An ideal low-pass power: frequencies below 4 (c + 1) carry power, the rest none.
cv::Mat box_power(int ch, int cv_) {
    cv::Mat p = cv::Mat::zeros(kDctBlock, kDctBlock, CV_64F);
    for (int v = 0; v < kDctBlock; v++)
        for (int u = 0; u < kDctBlock; u++)
            if (u < 4 * (ch + 1) && v < 4 * (cv_ + 1)) p.at<double>(v, u) = 3.0;
    return p;
}

CutoffModels box_models() {
    CutoffModels m;
    for (int c = kMinCutoff; c <= kMaxCutoff; c++) {
        PowerMarginal h, v;
        power_marginals(box_power(c, c), h, v);
        m.horizontal[c] = h;
        m.vertical[c] = v;
    }
    return m;
}

TEST(CutoffEstimation, MarginalsAreShapesWithoutDc) {
    PowerMarginal h, v;
    cv::Mat p = box_power(5, 9) * 17.0;
    p.at<double>(0, 0) = 1e6;  // DC: the detrending's leftovers, not grain
    power_marginals(p, h, v);
    double sh = 0, sv = 0;
    for (int i = 0; i < kDctBlock; i++) sh += h[i], sv += v[i];
    EXPECT_NEAR(sh, 1.0, 1e-12);
    EXPECT_NEAR(sv, 1.0, 1e-12);
    EXPECT_EQ(h[0], 0.0);
    EXPECT_GT(h[23], 0.0);
    EXPECT_EQ(h[24], 0.0);
    EXPECT_GT(v[39], 0.0);
    EXPECT_EQ(v[40], 0.0);
}

TEST(CutoffEstimation, EachAxisTakesItsNearestModel) {
    const CutoffModels m = box_models();
    for (int ch : {2, 5, 14})
        for (int cv_ : {3, 8, 13}) {
            const CutoffEstimate e = match_cutoffs(box_power(ch, cv_), m);
            EXPECT_EQ(e.horizontal, ch);
            EXPECT_EQ(e.vertical, cv_);
            EXPECT_NEAR(e.horizontal_mismatch, 0.0, 1e-12);
        }
    // A spectrum between two models goes to the nearer one.
    cv::Mat p = box_power(6, 6);
    for (int v = 0; v < kDctBlock; v++)
        for (int u = 28; u < 29; u++) p.at<double>(v, u) = 0.5;
    EXPECT_EQ(match_cutoffs(p, m).horizontal, 6);
}

}  // namespace
}  // namespace filmgrain::analysis

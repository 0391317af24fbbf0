// The temporal denoiser's parts: global motion found and compensated, the guide obeyed,
// grain variance restored.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "analysis/denoising.hpp"

namespace filmgrain::analysis {
namespace {

cv::Mat textured(int w, int h, unsigned seed) {
    cv::Mat m(h, w, CV_32F);
    cv::RNG rng(seed);
    rng.fill(m, cv::RNG::UNIFORM, 0.0, 200.0);
    cv::GaussianBlur(m, m, cv::Size(0, 0), 4.0);
    cv::normalize(m, m, 40, 200, cv::NORM_MINMAX);
    return m;
}

cv::Mat with_noise(const cv::Mat& m, double sigma, unsigned seed) {
    cv::Mat n(m.size(), CV_32F);
    cv::RNG rng(seed);
    rng.fill(n, cv::RNG::NORMAL, 0.0, sigma);
    return m + n;
}

cv::Mat view_moved(const cv::Mat& big, int x, int y, int w, int h) { return big(cv::Rect(x, y, w, h)).clone(); }

TEST(Denoising, GlobalShiftFoundAndUnmodifiedInputs) {
    const cv::Mat big = textured(400, 300, 1);
    const cv::Mat centre = with_noise(view_moved(big, 40, 40, 256, 192), 3.0, 2);
    const cv::Mat neighbour = with_noise(view_moved(big, 43, 38, 256, 192), 3.0, 3);
    const cv::Mat before = centre.clone();
    EXPECT_EQ(estimate_global_shift(centre, neighbour), cv::Point(-3, 2));
    EXPECT_EQ(cv::norm(centre, before, cv::NORM_INF), 0.0) << "phase correlation must not touch its inputs";
    // Grain alone moves nowhere.
    const cv::Mat flat(192, 256, CV_32F, cv::Scalar(100));
    EXPECT_EQ(estimate_global_shift(with_noise(flat, 3.0, 4), with_noise(flat, 3.0, 5)), cv::Point(0, 0));
}

TEST(Denoising, PannedNeighboursStayTemporalAndRestoreTheGrainLevel) {
    const cv::Mat big = textured(420, 320, 7);
    const double sigma = 3.0;
    std::vector<cv::Mat> frames;
    for (int k = 0; k < 5; k++) frames.push_back(with_noise(view_moved(big, 40 + 3 * k, 40, 256, 192), sigma, 10 + k));
    std::vector<TemporalNeighbour> n;
    for (int k : {0, 1, 3, 4}) n.push_back({&frames[k], estimate_global_shift(frames[2], frames[k]), nullptr});
    // frame k shows big(40 + 3k + x): the centre's x is the first frame's x + 6
    EXPECT_EQ(n[0].shift, cv::Point(6, 0));
    EXPECT_EQ(n[3].shift, cv::Point(-6, 0));
    std::vector<cv::Mat> accepted;
    const GrainEstimate g = denoise_temporal(frames[2], n, 8, &accepted);
    ASSERT_EQ(accepted.size(), 4u);
    const cv::Rect inner(16, 16, 224, 160);
    EXPECT_GT(cv::countNonZero(g.reliable(inner)), int(0.95 * inner.area()));
    cv::Scalar mean, sd;
    cv::meanStdDev(g.grain(inner), mean, sd);
    EXPECT_NEAR(sd[0], sigma, 0.1 * sigma);
    // Without the compensation the moved texture passes for grain (a whole-picture motion
    // raises the robust motion threshold with it).
    std::vector<TemporalNeighbour> still = n;
    for (auto& s : still) s.shift = {0, 0};
    const GrainEstimate u = denoise_temporal(frames[2], still, 8);
    cv::meanStdDev(u.grain(inner), mean, sd);
    EXPECT_GT(sd[0], 1.5 * sigma);
}

TEST(Denoising, GuideVetoesNeighbours) {
    const cv::Mat plane(64, 64, CV_32F, cv::Scalar(80));
    const cv::Mat a = with_noise(plane, 2.0, 1), b = with_noise(plane, 2.0, 2), c = with_noise(plane, 2.0, 3);
    cv::Mat guide = cv::Mat::zeros(64, 64, CV_8U);
    guide(cv::Rect(0, 0, 32, 64)).setTo(255);
    std::vector<TemporalNeighbour> n{{&b, {0, 0}, &guide}, {&c, {0, 0}, &guide}};
    const GrainEstimate g = denoise_temporal(a, n, 8);
    EXPECT_EQ(cv::countNonZero(g.reliable(cv::Rect(32, 0, 32, 64))), 0);
    EXPECT_EQ(cv::countNonZero(g.reliable(cv::Rect(0, 0, 32, 64))), 32 * 64);
}

}  // namespace
}  // namespace filmgrain::analysis

#include "analysis/flat_mask.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "analysis/plane_image.hpp"

namespace filmgrain::analysis {
namespace {

// Canny thresholds follow the residual noise of the picture (the denoiser leaves some
// grain): a multiple of the robust spread of the horizontal Sobel response, never below
// fixed floors that real edges of 8-bit content exceed by far.
cv::Mat edges_at_scale(const cv::Mat& img8) {
    cv::Mat gx;
    cv::Sobel(img8, gx, CV_32F, 1, 0, 3);
    std::vector<float> v;
    for (int y = 1; y < gx.rows - 1; y += 2) {
        const float* r = gx.ptr<float>(y);
        for (int x = 1; x < gx.cols - 1; x += 3) v.push_back(std::fabs(r[x]));
    }
    double spread = 0.0;
    if (!v.empty()) {
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        spread = 1.4826 * v[v.size() / 2];
    }
    const double low = std::max(30.0, 3.0 * spread);
    const double high = std::max(90.0, 6.0 * spread);
    cv::Mat edges;
    cv::Canny(img8, edges, low, high, 3, false);
    return edges;
}

}  // namespace

cv::Mat flat_region_mask(const cv::Mat& denoised, int bit_depth) {
    const cv::Mat img8 = to_8bit(denoised, bit_depth);
    const cv::Mat k3 = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
    cv::Mat edges = edges_at_scale(img8);
    cv::dilate(edges, edges, k3, cv::Point(-1, -1), 4);
    // Coarser scales find soft edges the grain residue hides at full resolution.
    const int dilations[] = {3, 2};
    for (int s = 1; s <= 2; s++) {
        const int f = 1 << s;
        if (img8.cols / f < 8 || img8.rows / f < 8) break;
        cv::Mat small, e;
        cv::resize(img8, small, cv::Size(img8.cols / f, img8.rows / f), 0, 0, cv::INTER_AREA);
        e = edges_at_scale(small);
        cv::dilate(e, e, k3, cv::Point(-1, -1), dilations[s - 1]);
        cv::resize(e, e, img8.size(), 0, 0, cv::INTER_NEAREST);
        cv::bitwise_or(edges, e, edges);
    }
    cv::dilate(edges, edges, k3, cv::Point(-1, -1), 2);
    cv::erode(edges, edges, k3, cv::Point(-1, -1), 1);
    cv::Mat flat, in_range;
    cv::bitwise_not(edges, flat);
    cv::inRange(img8, cv::Scalar(kDarkestAnalysedIntensity), cv::Scalar(kBrightestAnalysedIntensity), in_range);
    cv::bitwise_and(flat, in_range, flat);
    return flat;
}

}  // namespace filmgrain::analysis

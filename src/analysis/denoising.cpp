#include "analysis/denoising.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace filmgrain::analysis {
namespace {

// Median of |values| over a regular subsample of the picture (robust spread estimate).
double median_abs(const cv::Mat& m) {
    std::vector<float> v;
    v.reserve(m.total() / 7 + 1);
    const int step = 7;
    for (int y = 0; y < m.rows; y += 3) {
        const float* r = m.ptr<float>(y);
        for (int x = (y / 3) % step; x < m.cols; x += step) v.push_back(std::fabs(r[x]));
    }
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

constexpr double kSpatialSigma = 2.0;

}  // namespace

GrainEstimate denoise_spatial(const cv::Mat& source) {
    GrainEstimate g;
    cv::GaussianBlur(source, g.denoised, cv::Size(0, 0), kSpatialSigma, kSpatialSigma, cv::BORDER_REFLECT);
    g.grain = source - g.denoised;
    g.reliable = cv::Mat::zeros(source.size(), CV_8U);
    return g;
}

GrainEstimate grain_from_denoised(const cv::Mat& source, const cv::Mat& denoised) {
    GrainEstimate g;
    g.denoised = denoised.clone();
    g.grain = source - denoised;
    g.reliable = cv::Mat(source.size(), CV_8U, cv::Scalar(255));
    return g;
}

namespace {

// Mean |a(x, y) - b(x + dx, y + dy)| over the interior both share (every `step`-th sample).
double shifted_difference(const cv::Mat& a, const cv::Mat& b, int dx, int dy, int margin, int step) {
    double sum = 0;
    long long n = 0;
    for (int y = margin; y < a.rows - margin; y += step) {
        const int yb = y + dy;
        if (yb < 0 || yb >= b.rows) continue;
        const float* ra = a.ptr<float>(y);
        const float* rb = b.ptr<float>(yb);
        for (int x = margin; x < a.cols - margin; x += step) {
            const int xb = x + dx;
            if (xb < 0 || xb >= b.cols) continue;
            sum += std::fabs(ra[x] - rb[xb]);
            n++;
        }
    }
    return n ? sum / double(n) : std::numeric_limits<double>::infinity();
}

cv::Point best_shift(const cv::Mat& a, const cv::Mat& b, cv::Point around, int radius, int margin, int step, double* cost) {
    cv::Point best = around;
    double best_cost = std::numeric_limits<double>::infinity();
    for (int dy = around.y - radius; dy <= around.y + radius; dy++)
        for (int dx = around.x - radius; dx <= around.x + radius; dx++) {
            const double c = shifted_difference(a, b, dx, dy, margin, step);
            if (c < best_cost) best_cost = c, best = {dx, dy};
        }
    if (cost) *cost = best_cost;
    return best;
}

}  // namespace

namespace {
constexpr int kCoarse = 4, kCoarseRadius = 8, kFineRadius = kCoarse - 1, kMargin = 8 * kCoarse;
}  // namespace

MotionPicture prepare_motion_picture(const cv::Mat& luma) {
    MotionPicture m;
    if (luma.cols < 4 * kMargin || luma.rows < 4 * kMargin) return m;
    cv::GaussianBlur(luma, m.fine, cv::Size(0, 0), 1.5, 1.5, cv::BORDER_REFLECT);
    cv::resize(m.fine, m.coarse, cv::Size(luma.cols / kCoarse, luma.rows / kCoarse), 0, 0, cv::INTER_AREA);
    return m;
}

cv::Point estimate_global_shift(const MotionPicture& a, const MotionPicture& b) {
    // Block matching of the whole picture, coarse to fine, on low-passed pictures: the grain
    // (independent between pictures) averages out and the content decides. Phase
    // correlation whitens the spectrum, where grain owns the high frequencies: it missed
    // pans by a sample or two and found motion in static grain.
    if (a.fine.empty() || b.fine.empty() || a.fine.size() != b.fine.size()) return {0, 0};
    const cv::Point coarse = best_shift(a.coarse, b.coarse, {0, 0}, kCoarseRadius, kMargin / kCoarse, 1, nullptr);
    double cost = 0;
    const cv::Point fine = best_shift(a.fine, b.fine, coarse * kCoarse, kFineRadius, kMargin, 2, &cost);
    // A clear winner only: on flat content every shift matches alike and nothing moved.
    const double still = shifted_difference(a.fine, b.fine, 0, 0, kMargin, 2);
    return cost < 0.8 * still ? fine : cv::Point(0, 0);
}

cv::Point estimate_global_shift(const cv::Mat& centre, const cv::Mat& neighbour) {
    return estimate_global_shift(prepare_motion_picture(centre), prepare_motion_picture(neighbour));
}

namespace {

// neighbour(x + dx, y + dy) at (x, y); `inside` marks where that sample exists.
void move_by(const cv::Mat& neighbour, cv::Point shift, cv::Mat& moved, cv::Mat& inside) {
    if (shift == cv::Point(0, 0)) {
        moved = neighbour;
        inside = cv::Mat(neighbour.size(), CV_8U, cv::Scalar(255));
        return;
    }
    moved = cv::Mat::zeros(neighbour.size(), neighbour.type());
    inside = cv::Mat::zeros(neighbour.size(), CV_8U);
    const int w = neighbour.cols, h = neighbour.rows;
    const int x0 = std::max(0, -shift.x), x1 = std::min(w, w - shift.x);
    const int y0 = std::max(0, -shift.y), y1 = std::min(h, h - shift.y);
    if (x1 <= x0 || y1 <= y0) return;
    const cv::Rect dst(x0, y0, x1 - x0, y1 - y0);
    neighbour(dst + shift).copyTo(moved(dst));
    inside(dst).setTo(255);
}

}  // namespace

GrainEstimate denoise_temporal(const cv::Mat& f0, const std::vector<TemporalNeighbour>& neighbours, int bit_depth,
                               std::vector<cv::Mat>* accepted) {
    cv::Mat sum = f0.clone();
    cv::Mat count(f0.size(), CV_32F, cv::Scalar(1.0f));
    // Smallest difference treated as motion: a fraction of one 8-bit code value, so that
    // identical (grain-free) neighbours are always accepted.
    const double floor_threshold = 0.5 * double(1 << (bit_depth - 8));
    cv::Mat moved, inside, diff, blurred, accept;
    if (accepted) accepted->clear();
    for (const TemporalNeighbour& n : neighbours) {
        move_by(*n.plane, n.shift, moved, inside);
        cv::subtract(moved, f0, diff);
        diff.setTo(0, inside == 0);
        cv::GaussianBlur(diff, blurred, cv::Size(0, 0), 2.5, 2.5, cv::BORDER_REFLECT);
        // 1.4826 * MAD = the standard deviation of the blurred grain difference where
        // nothing moves; 3 of them separate motion from grain.
        const double thr = std::max(floor_threshold, 3.0 * 1.4826 * median_abs(blurred));
        cv::Mat absb = cv::abs(blurred);
        cv::compare(absb, thr, accept, cv::CMP_LT);
        cv::bitwise_and(accept, inside, accept);
        if (n.guide) cv::bitwise_and(accept, *n.guide, accept);
        cv::add(sum, moved, sum, accept);
        cv::add(count, cv::Scalar(1.0f), count, accept);
        if (accepted) accepted->push_back(accept.clone());
    }
    GrainEstimate g;
    cv::divide(sum, count, g.denoised);
    cv::Mat spatial;
    cv::GaussianBlur(f0, spatial, cv::Size(0, 0), kSpatialSigma, kSpatialSigma, cv::BORDER_REFLECT);
    g.grain.create(f0.size(), CV_32F);
    g.reliable.create(f0.size(), CV_8U);
    for (int y = 0; y < f0.rows; y++) {
        const float* s = f0.ptr<float>(y);
        const float* n = count.ptr<float>(y);
        float* d = g.denoised.ptr<float>(y);
        const float* sp = spatial.ptr<float>(y);
        float* gr = g.grain.ptr<float>(y);
        uint8_t* rel = g.reliable.ptr<uint8_t>(y);
        for (int x = 0; x < f0.cols; x++) {
            if (n[x] >= 2.0f) {
                gr[x] = (s[x] - d[x]) * std::sqrt(n[x] / (n[x] - 1.0f));
                rel[x] = 255;
            } else {
                d[x] = sp[x];
                gr[x] = s[x] - sp[x];
                rel[x] = 0;
            }
        }
    }
    return g;
}

}  // namespace filmgrain::analysis

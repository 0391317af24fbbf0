#include "analysis/scaling_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/core.hpp>

#include "analysis/grain_level.hpp"

namespace filmgrain::analysis {
namespace {

constexpr int kOutlierPasses = 2;
constexpr int kMinPerSubRange = 4;  // fewer observations: the polynomial speaks instead
constexpr int kPolynomialOrder = 4;
constexpr std::size_t kMinObservations = 16;  // flat blocks below which a component is not estimated

double median_of(std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// Weighted least-squares polynomial in x in [0, 1]; returns coefficients low order first.
std::array<double, 5> fit_polynomial(const std::vector<double>& x, const std::vector<double>& y,
                                     const std::vector<double>& w, int order) {
    std::array<double, 5> c{};
    const int n = int(x.size());
    order = std::min(order, n - 1);
    if (order < 0) return c;
    cv::Mat A(n, order + 1, CV_64F), b(n, 1, CV_64F);
    for (int i = 0; i < n; i++) {
        const double sw = std::sqrt(w[i]);
        double p = 1.0;
        for (int k = 0; k <= order; k++, p *= x[i]) A.at<double>(i, k) = p * sw;
        b.at<double>(i) = y[i] * sw;
    }
    cv::Mat sol;
    cv::solve(A, b, sol, cv::DECOMP_SVD);
    for (int k = 0; k <= order; k++) c[k] = sol.at<double>(k);
    return c;
}

double eval_polynomial(const std::array<double, 5>& c, double x) {
    double r = 0.0;
    for (int k = 4; k >= 0; k--) r = r * x + c[k];
    return r;
}

double sub_range_centre(int s) { return s * kSubRangeWidth + (kSubRangeWidth - 1) / 2.0; }

}  // namespace

LevelCurve fit_level_curve(const std::vector<BlockSample>& blocks) {
    LevelCurve curve;
    std::array<std::vector<float>, kSubRanges> buckets;
    for (const auto& b : blocks) {
        const int s = std::clamp(int(b.intensity8) / kSubRangeWidth, 0, kSubRanges - 1);
        buckets[s].push_back(b.sigma);
    }
    // Outliers: blocks the mask let through with texture, or with a denoising failure.
    for (int pass = 0; pass < kOutlierPasses; pass++)
        for (auto& v : buckets) {
            if (v.size() < 3) continue;
            const double med = median_of(v);
            std::vector<float> dev(v.size());
            for (std::size_t i = 0; i < v.size(); i++) dev[i] = std::fabs(v[i] - med);
            const double spread = std::max(3.0 * 1.4826 * median_of(dev), 0.05 * med + 1e-6);
            const std::size_t before = v.size();
            v.erase(std::remove_if(v.begin(), v.end(), [&](float s) { return std::fabs(s - med) > spread; }), v.end());
            curve.outliers += before - v.size();
        }
    std::vector<double> px, py, pw;
    for (int s = 0; s < kSubRanges; s++) {
        const auto& v = buckets[s];
        curve.sub_range_count[s] = int(v.size());
        if (v.empty()) continue;
        double ss = 0;
        for (float x : v) ss += double(x) * x;
        curve.sub_range_level[s] = std::sqrt(ss / v.size());  // levels combine as variances
        double sum = 0;
        for (float x : v) sum += x;
        const double mean = sum / double(v.size());
        curve.sub_range_spread[s] = v.size() > 1 ? std::sqrt(std::max(0.0, (ss - sum * mean) / double(v.size() - 1))) : mean;
        curve.observations += v.size();
        px.push_back(sub_range_centre(s) / 255.0);
        py.push_back(curve.sub_range_level[s]);
        pw.push_back(double(v.size()));
    }
    if (px.empty()) return curve;
    // Two passes: the second without the sub-ranges the first fit explains worst.
    curve.polynomial = fit_polynomial(px, py, pw, kPolynomialOrder);
    {
        double rms = 0, wsum = 0;
        for (std::size_t i = 0; i < px.size(); i++) {
            const double r = py[i] - eval_polynomial(curve.polynomial, px[i]);
            rms += pw[i] * r * r;
            wsum += pw[i];
        }
        rms = std::sqrt(rms / wsum);
        std::vector<double> qx, qy, qw;
        for (std::size_t i = 0; i < px.size(); i++)
            if (std::fabs(py[i] - eval_polynomial(curve.polynomial, px[i])) <= 2.5 * rms + 1e-9) {
                qx.push_back(px[i]);
                qy.push_back(py[i]);
                qw.push_back(pw[i]);
            }
        if (qx.size() >= 2) curve.polynomial = fit_polynomial(qx, qy, qw, kPolynomialOrder);
    }
    // Per sub-range level: measured where well supported, the polynomial where sparse.
    int first = -1, last = -1;
    std::array<double, kSubRanges> value{};
    std::array<bool, kSubRanges> has{};
    for (int s = 0; s < kSubRanges; s++)
        if (curve.sub_range_count[s] > 0) {
            if (first < 0) first = s;
            last = s;
        }
    for (int s = first; s <= last; s++) {
        has[s] = true;
        value[s] = curve.sub_range_count[s] >= kMinPerSubRange
                       ? curve.sub_range_level[s]
                       : std::max(0.0, eval_polynomial(curve.polynomial, sub_range_centre(s) / 255.0));
    }
    curve.observed_low = first * kSubRangeWidth;
    curve.observed_high = last * kSubRangeWidth + kSubRangeWidth - 1;
    for (int i = 0; i < 256; i++) {
        const double pos = (i - (kSubRangeWidth - 1) / 2.0) / kSubRangeWidth;
        int s0 = int(std::floor(pos));
        double t = pos - s0;
        if (s0 < first) {
            s0 = first;
            t = 0;
        }
        if (s0 >= last) {
            s0 = last;
            t = 0;
        }
        const double v0 = value[s0], v1 = has[s0 + (t > 0)] ? value[s0 + (t > 0)] : v0;
        curve.level[i] = v0 + (v1 - v0) * t;  // constant extrapolation outside the observations
        const int s = std::clamp(i / kSubRangeWidth, 0, kSubRanges - 1);
        curve.weight[i] = (i >= curve.observed_low && i <= curve.observed_high)
                              ? std::max(1.0, double(curve.sub_range_count[s])) / kSubRangeWidth
                              : 0.0;
    }
    return curve;
}

std::vector<LevelInterval> segment_levels(const LevelCurve& curve, int count) {
    // Extrapolated intensities weigh little, so they join their nearest observed segment.
    double wmean = 0;
    for (double w : curve.weight) wmean += w;
    wmean = std::max(wmean / 256.0, 1e-9);
    std::array<double, 257> W{}, WL{}, WLL{};
    for (int i = 0; i < 256; i++) {
        const double w = curve.weight[i] > 0 ? curve.weight[i] : 1e-3 * wmean;
        W[i + 1] = W[i] + w;
        WL[i + 1] = WL[i] + w * curve.level[i];
        WLL[i + 1] = WLL[i] + w * curve.level[i] * curve.level[i];
    }
    auto cost = [&](int a, int b) {  // [a, b)
        const double w = W[b] - W[a], s = WL[b] - WL[a];
        return (WLL[b] - WLL[a]) - s * s / w;
    };
    count = std::clamp(count, 1, 256);
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::array<double, 257>> dp(count + 1);
    std::vector<std::array<int, 257>> from(count + 1);
    for (auto& r : dp) r.fill(inf);
    dp[0][0] = 0;
    for (int k = 1; k <= count; k++)
        for (int b = k; b <= 256; b++)
            for (int a = k - 1; a < b; a++) {
                if (dp[k - 1][a] == inf) continue;
                const double c = dp[k - 1][a] + cost(a, b);
                if (c < dp[k][b]) {
                    dp[k][b] = c;
                    from[k][b] = a;
                }
            }
    std::vector<LevelInterval> out(count);
    int b = 256;
    for (int k = count; k >= 1; k--) {
        const int a = from[k][b];
        out[k - 1] = {a, b - 1, (WL[b] - WL[a]) / (W[b] - W[a])};
        b = a;
    }
    return out;
}

double relative_error(const LevelCurve& curve, const std::vector<double>& approx) {
    double peak = 0, worst = 0;
    for (int i = 0; i < 256; i++) peak = std::max(peak, curve.level[i]);
    if (peak <= 0) return 0.0;
    for (int i = curve.observed_low; i <= curve.observed_high; i++)
        worst = std::max(worst, std::fabs(approx[i] - curve.level[i]));
    return worst / peak;
}

double rms_relative_error(const LevelCurve& curve, const std::vector<double>& approx) {
    double peak = 0, ss = 0, w = 0;
    for (int i = 0; i < 256; i++) peak = std::max(peak, curve.level[i]);
    if (peak <= 0) return 0.0;
    for (int i = curve.observed_low; i <= curve.observed_high; i++) {
        const double d = approx[i] - curve.level[i];
        ss += curve.weight[i] * d * d;
        w += curve.weight[i];
    }
    return w > 0 ? std::sqrt(ss / w) / peak : 0.0;
}

double worst_band_error(const LevelCurve& curve, const std::vector<double>& approx, int* worst_band_lower) {
    double peak = 0;
    for (int i = curve.observed_low; i <= curve.observed_high && i < 256; i++) peak = std::max(peak, curve.level[i]);
    if (worst_band_lower) *worst_band_lower = -1;
    if (peak <= 0) return 0.0;
    double worst = 0;
    for (int b = 0; b < 256; b += kErrorBandWidth) {
        int blocks = 0;
        double spread2 = 0;  // sum of n s^2: the band's level is a mean of its blocks'
        for (int s = b / kSubRangeWidth; s < (b + kErrorBandWidth) / kSubRangeWidth; s++) {
            blocks += curve.sub_range_count[s];
            spread2 += curve.sub_range_count[s] * curve.sub_range_spread[s] * curve.sub_range_spread[s];
        }
        if (blocks < kMinPerSubRange) continue;
        const double standard_error = std::sqrt(spread2) / blocks;
        double w = 0, level = 0, described = 0;
        for (int i = b; i < b + kErrorBandWidth; i++) {
            if (curve.weight[i] <= 0) continue;
            w += curve.weight[i];
            level += curve.weight[i] * curve.level[i];
            described += curve.weight[i] * approx[i];
        }
        if (w <= 0) continue;
        level /= w;
        described /= w;
        const double e = std::max(0.0, std::fabs(described - level) - 2 * standard_error) / std::max(level, 0.25 * peak);
        if (e > worst) {
            worst = e;
            if (worst_band_lower) *worst_band_lower = b;
        }
    }
    return worst;
}

std::vector<double> evaluate_piecewise_linear(const std::vector<LevelPoint>& points) {
    std::vector<double> f(256, 0.0);
    if (points.empty()) return f;
    for (int i = 0; i < 256; i++) {
        if (i <= points.front().value) {
            f[i] = points.front().level;
        } else if (i >= points.back().value) {
            f[i] = points.back().level;
        } else {
            std::size_t k = 1;
            while (points[k].value < i) k++;
            const auto& p0 = points[k - 1];
            const auto& p1 = points[k];
            f[i] = p0.level + (p1.level - p0.level) * (i - p0.value) / double(p1.value - p0.value);
        }
    }
    return f;
}

namespace {

// Least-squares levels at the given knots (hat functions), with a small second-difference
// penalty that keeps knots without observations on the line of their neighbours.
std::vector<LevelPoint> fit_knots(const LevelCurve& curve, const std::vector<int>& knots, double smoothing) {
    const int k = int(knots.size());
    cv::Mat A = cv::Mat::zeros(k, k, CV_64F), b = cv::Mat::zeros(k, 1, CV_64F);
    double wsum = 0;
    for (int i = 0; i < 256; i++) {
        const double w = curve.weight[i] > 0 ? curve.weight[i] : 1e-4;
        wsum += w;
        int j = 0;
        while (j + 1 < k && knots[j + 1] <= i) j++;
        double phi[2] = {1.0, 0.0};
        int idx[2] = {j, j};
        if (j + 1 < k && i > knots[j]) {
            const double t = (i - knots[j]) / double(knots[j + 1] - knots[j]);
            phi[0] = 1 - t;
            phi[1] = t;
            idx[1] = j + 1;
        }
        for (int u = 0; u < 2; u++) {
            b.at<double>(idx[u]) += w * phi[u] * curve.level[i];
            for (int v = 0; v < 2; v++) A.at<double>(idx[u], idx[v]) += w * phi[u] * phi[v];
        }
    }
    const double lambda = smoothing * wsum / k;
    for (int j = 1; j + 1 < k; j++) {
        const int id[3] = {j - 1, j, j + 1};
        const double c[3] = {1, -2, 1};
        for (int u = 0; u < 3; u++)
            for (int v = 0; v < 3; v++) A.at<double>(id[u], id[v]) += lambda * c[u] * c[v];
    }
    cv::Mat sol;
    cv::solve(A, b, sol, cv::DECOMP_SVD);
    std::vector<LevelPoint> pts(k);
    for (int j = 0; j < k; j++) pts[j] = {knots[j], std::max(0.0, sol.at<double>(j))};
    return pts;
}

}  // namespace

std::vector<LevelPoint> fit_piecewise_linear(const LevelCurve& curve, int max_points, double tolerance) {
    // Knots only where there are observations: both models hold the end points' levels
    // constant beyond them (AV1 7.18.3.5's scaling lookup, the curve's own extrapolation),
    // where knots outside would continue the nearest slope into intensities nobody measured
    // (chroma, observed over a few dozen values near 128, went to 3x its level).
    std::vector<int> knots;
    const int lo = std::clamp(curve.observed_low, 0, 255), hi = std::clamp(curve.observed_high, lo, 255);
    // Every 8 values to start with (the points are then removed least damage first): a
    // lattice of 16 could not follow chroma curves observed over a few dozen values.
    knots.push_back(lo);
    for (int v = (lo / 8 + 1) * 8; v < hi; v += 8)
        if (v - lo >= kSubRangeWidth - 1 && hi - v >= kSubRangeWidth - 1) knots.push_back(v);
    if (hi > lo) knots.push_back(hi);
    constexpr double kSmoothing = 1e-3;
    std::vector<LevelPoint> best = fit_knots(curve, knots, kSmoothing);
    while (knots.size() > 1) {
        double best_err = std::numeric_limits<double>::infinity();
        std::size_t best_drop = 0;
        std::vector<LevelPoint> best_pts;
        for (std::size_t d = 0; d < knots.size(); d++) {
            std::vector<int> trial = knots;
            trial.erase(trial.begin() + d);
            auto pts = fit_knots(curve, trial, kSmoothing);
            const double err = worst_band_error(curve, evaluate_piecewise_linear(pts));
            if (err < best_err) {
                best_err = err;
                best_drop = d;
                best_pts = std::move(pts);
            }
        }
        if (int(knots.size()) <= max_points && best_err > tolerance) break;
        knots.erase(knots.begin() + best_drop);
        best = std::move(best_pts);
    }
    return best;
}

std::string fit_component_curve(const std::vector<BlockSample>& blocks, int bit_depth, LevelCurve& curve, bool chroma) {
    curve = fit_level_curve(blocks);
    if (!curve.valid() || curve.observations < kMinObservations)
        return "too few flat blocks (" + std::to_string(curve.observations) + ") to estimate grain";
    const double floor = kMinGrainLevel8 * double(1 << (bit_depth - 8));
    char text[160];
    if (chroma) {
        std::vector<std::pair<double, int>> levels;
        int total = 0;
        for (int s = 0; s < kSubRanges; s++)
            if (curve.sub_range_count[s] > 0) levels.push_back({curve.sub_range_level[s], curve.sub_range_count[s]}), total += curve.sub_range_count[s];
        std::sort(levels.begin(), levels.end());
        double median = 0;
        for (int seen = 0; const auto& [level, count] : levels)
            if ((seen += count) * 2 >= total) {
                median = level;
                break;
            }
        if (median < floor) {
            std::snprintf(text, sizeof text, "no grain: the typical level %.2f is below %.1f (8-bit units)",
                          median / double(1 << (bit_depth - 8)), kMinGrainLevel8);
            return text;
        }
        return {};
    }
    double peak = 0;
    for (int i = curve.observed_low; i <= curve.observed_high; i++) peak = std::max(peak, curve.level[i]);
    if (peak < floor) {
        std::snprintf(text, sizeof text, "no grain: the largest level %.2f is below %.1f (8-bit units)",
                      peak / double(1 << (bit_depth - 8)), kMinGrainLevel8);
        return text;
    }
    return {};
}

}  // namespace filmgrain::analysis

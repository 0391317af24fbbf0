#include "analysis/block_observations.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace filmgrain::analysis {

const std::array<ArOffset, kMaxArTerms - 1>& ar_offsets_lag3() {
    static const std::array<ArOffset, kMaxArTerms - 1> offsets = [] {
        std::array<ArOffset, kMaxArTerms - 1> o{};
        int i = 0;
        for (int dy = -kMaxArLag; dy <= 0; dy++)
            for (int dx = -kMaxArLag; dx <= kMaxArLag; dx++) {
                if (dy == 0 && dx == 0) return o;
                o[i++] = {dy, dx};
            }
        return o;
    }();
    return offsets;
}

double detrended_sigma(const cv::Mat& block, cv::Mat* residual) {
    // Planar trend a + b x + c y with centred coordinates: the three fits are independent.
    const int w = block.cols, h = block.rows;
    const double cx = (w - 1) / 2.0, cy = (h - 1) / 2.0;
    double s = 0, sx = 0, sy = 0, xx = 0, yy = 0;
    for (int y = 0; y < h; y++) {
        const float* r = block.ptr<float>(y);
        for (int x = 0; x < w; x++) {
            const double dx = x - cx, dy = y - cy;
            s += r[x];
            sx += r[x] * dx;
            sy += r[x] * dy;
            xx += dx * dx;
            yy += dy * dy;
        }
    }
    const double a = s / (w * h), b = sx / xx, c = sy / yy;
    double ss = 0;
    if (residual) residual->create(h, w, CV_32F);
    for (int y = 0; y < h; y++) {
        const float* r = block.ptr<float>(y);
        float* o = residual ? residual->ptr<float>(y) : nullptr;
        for (int x = 0; x < w; x++) {
            const double v = r[x] - a - b * (x - cx) - c * (y - cy);
            ss += v * v;
            if (o) o[x] = float(v);
        }
    }
    return std::sqrt(ss / (w * h - 3));
}

void LagSums::add(const LagSums& o) {
    for (int k = 0; k <= kMaxCorrelationLag; k++) {
        x[k] += o.x[k];
        y[k] += o.y[k];
        x_pairs[k] += o.x_pairs[k];
        y_pairs[k] += o.y_pairs[k];
    }
    for (int d = 0; d < 2; d++) {
        diagonal[d] += o.diagonal[d];
        diagonal_pairs[d] += o.diagonal_pairs[d];
    }
    energy += o.energy;
    samples += o.samples;
}

double LagSums::rx(int k) const {
    return x_pairs[k] > 0 && energy > 0 ? (x[k] / x_pairs[k]) / (energy / samples) : 0.0;
}

double LagSums::ry(int k) const {
    return y_pairs[k] > 0 && energy > 0 ? (y[k] / y_pairs[k]) / (energy / samples) : 0.0;
}

double LagSums::rd(int d) const {
    return diagonal_pairs[d] > 0 && energy > 0 ? (diagonal[d] / diagonal_pairs[d]) / (energy / samples) : 0.0;
}

void accumulate_lags(const cv::Mat& r, LagSums& sums) {
    for (int yy = 0; yy < r.rows; yy++) {
        const float* row = r.ptr<float>(yy);
        for (int xx = 0; xx < r.cols; xx++) {
            const double v = row[xx];
            sums.energy += v * v;
            for (int k = 1; k <= kMaxCorrelationLag; k++) {
                if (xx + k < r.cols) sums.x[k] += v * row[xx + k], sums.x_pairs[k] += 1;
                if (yy + k < r.rows) sums.y[k] += v * r.ptr<float>(yy + k)[xx], sums.y_pairs[k] += 1;
            }
            if (yy + 1 < r.rows) {
                const float* below = r.ptr<float>(yy + 1);
                if (xx + 1 < r.cols) sums.diagonal[0] += v * below[xx + 1], sums.diagonal_pairs[0] += 1;
                if (xx >= 1) sums.diagonal[1] += v * below[xx - 1], sums.diagonal_pairs[1] += 1;
            }
        }
    }
    sums.samples += double(r.total());
}

void accumulate_block_lags(const cv::Mat& grain_block, LagSums& lags) {
    cv::Mat residual;
    detrended_sigma(grain_block, &residual);
    accumulate_lags(residual, lags);
}

cv::Mat block_dct_power(const cv::Mat& grain_block, LagSums* lags) {
    cv::Mat residual, coeffs, sq, sq64;
    detrended_sigma(grain_block, &residual);
    if (lags) accumulate_lags(residual, *lags);
    cv::dct(residual, coeffs);
    cv::multiply(coeffs, coeffs, sq);
    sq.convertTo(sq64, CV_64F);
    return sq64;
}

namespace {

// Non-overlapping size x size blocks lying entirely in the usable area, placed greedily in
// raster order on an 8-sample lattice rather than on a fixed grid, so that flat areas
// between edges yield blocks wherever they fit.
std::vector<cv::Rect> place_flat_blocks(const cv::Mat& integral, int w, int h, int size) {
    constexpr int kLattice = 8;
    std::vector<cv::Rect> out;
    cv::Mat taken = cv::Mat::zeros(h, w, CV_8U);
    for (int y = 0; y + size <= h; y += kLattice)
        for (int x = 0; x + size <= w; x += kLattice) {
            const int n = integral.at<int>(y + size, x + size) - integral.at<int>(y, x + size) -
                          integral.at<int>(y + size, x) + integral.at<int>(y, x);
            if (n != size * size) continue;
            const cv::Rect r(x, y, size, size);
            if (taken.at<uint8_t>(y, x) || taken.at<uint8_t>(y, x + size - 1) || cv::countNonZero(taken(r)) > 0) continue;
            taken(r).setTo(1);
            out.push_back(r);
            x += size - kLattice;
        }
    return out;
}

void accumulate_ar(const cv::Mat& normalized, const cv::Mat& luma_normalized, const cv::Rect& r, ArEquations& eq) {
    const auto& offs = ar_offsets_lag3();
    const bool with_luma = !luma_normalized.empty();
    const int terms = kMaxArTerms - (with_luma ? 0 : 1);
    const int x0 = r.x + kMaxArLag, x1 = r.x + r.width - kMaxArLag;
    const int y0 = r.y + kMaxArLag, y1 = r.y + r.height;
    const int rows = (x1 - x0) * (y1 - y0);
    cv::Mat X(rows, terms, CV_32F), Y(rows, 1, CV_32F);
    int k = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++, k++) {
            float* xr = X.ptr<float>(k);
            for (int i = 0; i < kMaxArTerms - 1; i++) xr[i] = normalized.at<float>(y + offs[i].dy, x + offs[i].dx);
            if (with_luma) xr[kMaxArTerms - 1] = luma_normalized.at<float>(y, x);
            Y.at<float>(k) = normalized.at<float>(y, x);
        }
    cv::Mat xtx, xty;
    cv::mulTransposed(X, xtx, true, cv::noArray(), 1.0, CV_64F);
    cv::Mat X64, Y64;
    X.convertTo(X64, CV_64F);
    Y.convertTo(Y64, CV_64F);
    xty = X64.t() * Y64;
    eq.xtx(cv::Rect(0, 0, terms, terms)) += xtx;
    eq.xty(cv::Rect(0, 0, 1, terms)) += xty;
    eq.yty += Y64.dot(Y64);
    eq.n += rows;
}

}  // namespace

void merge_observations(PlaneObservations& total, const PlaneObservations& part) {
    total.blocks.insert(total.blocks.end(), part.blocks.begin(), part.blocks.end());
    for (int b = 0; b < kPowerBins; b++) {
        if (!part.dct_blocks[b]) continue;
        total.dct_power[b] += part.dct_power[b];
        total.dct_blocks[b] += part.dct_blocks[b];
        total.lags[b].add(part.lags[b]);
    }
    auto add = [](ArEquations& t, const ArEquations& p) {
        t.xtx += p.xtx;
        t.xty += p.xty;
        t.yty += p.yty;
        t.n += p.n;
    };
    add(total.ar_halves[0], part.ar_halves[0]);
    add(total.ar_halves[1], part.ar_halves[1]);
    total.ar.xtx = total.ar_halves[0].xtx + total.ar_halves[1].xtx;
    total.ar.xty = total.ar_halves[0].xty + total.ar_halves[1].xty;
    total.ar.yty = total.ar_halves[0].yty + total.ar_halves[1].yty;
    total.ar.n = total.ar_halves[0].n + total.ar_halves[1].n;
    total.flat_samples += part.flat_samples;
    total.total_samples += part.total_samples;
    total.outside_legal += part.outside_legal;
    total.on_legal_bound += part.on_legal_bound;
}

void count_legal_range(const cv::Mat& source, int bit_depth, int legal_min8, int legal_max8, PlaneObservations& out) {
    const double lo = double(legal_min8 << (bit_depth - 8)), hi = double(legal_max8 << (bit_depth - 8));
    out.outside_legal += cv::countNonZero(source < lo) + cv::countNonZero(source > hi);
    out.on_legal_bound += cv::countNonZero(source == lo) + cv::countNonZero(source == hi);
}

cv::Mat observe_plane(const cv::Mat& source, const cv::Mat& denoised, const cv::Mat& grain, const cv::Mat& usable,
                      int bit_depth, const CoLocatedLuma& luma, const ObservationRequest& request,
                      PlaneObservations& out) {
    const int w = source.cols, h = source.rows;
    const double to8 = 1.0 / double(1 << (bit_depth - 8));
    const double maxv = double((1 << bit_depth) - 1);
    out.flat_samples += cv::countNonZero(usable);
    out.total_samples += (long long)w * h;
    cv::Mat normalized = cv::Mat::zeros(h, w, CV_32F);
    // Normalized grain everywhere (the chroma planes' luma term needs it beyond flat areas).
    cv::Mat residual;
    for (int by = 0; by < h; by += kArBlock)
        for (int bx = 0; bx < w; bx += kArBlock) {
            const cv::Rect r(bx, by, std::min(kArBlock, w - bx), std::min(kArBlock, h - by));
            if (r.width < 4 || r.height < 4) continue;
            const double sigma = detrended_sigma(grain(r), &residual);
            if (sigma > 0) residual.convertTo(normalized(r), CV_32F, 1.0 / sigma);
        }
    cv::Mat usable01, integral;
    cv::threshold(usable, usable01, 0, 1, cv::THRESH_BINARY);
    cv::integral(usable01, integral, CV_32S);
    const auto clipped = [&](const cv::Rect& r) {  // clipped grain: its level is not observable
        double mn, mx;
        cv::minMaxLoc(source(r), &mn, &mx);
        return mn <= 0 || mx >= maxv;
    };
    for (const cv::Rect& r : place_flat_blocks(integral, w, h, request.level_block)) {
        if (clipped(r)) continue;
        const float intensity8 = float(cv::mean(denoised(r))[0] * to8);
        out.blocks.push_back({intensity8, float(detrended_sigma(grain(r), nullptr)),
                              luma.denoised.empty() ? intensity8 : float(cv::mean(luma.denoised(r))[0] * to8)});
    }
    std::vector<cv::Rect> ar_blocks;
    if (request.ar_equations)
        for (const cv::Rect& r : place_flat_blocks(integral, w, h, kArBlock)) {
            if (clipped(r)) continue;
            const double sigma = detrended_sigma(grain(r), &residual);
            if (sigma <= 0) continue;
            cv::Mat nb;
            residual.convertTo(nb, CV_32F, 1.0 / sigma);
            nb.copyTo(normalized(r));
            ar_blocks.push_back(r);
        }
    if (request.ar_equations && !ar_blocks.empty()) {
        // A regular subset keeps the cost bounded on large pictures.
        const std::size_t step = (ar_blocks.size() + request.max_ar_blocks - 1) / request.max_ar_blocks;
        for (std::size_t i = 0; i < ar_blocks.size(); i += step)
            accumulate_ar(normalized, luma.normalized, ar_blocks[i], out.ar_halves[request.half & 1]);
        out.ar = out.ar_halves[0];
        out.ar.xtx = out.ar_halves[0].xtx + out.ar_halves[1].xtx;
        out.ar.xty = out.ar_halves[0].xty + out.ar_halves[1].xty;
        out.ar.yty = out.ar_halves[0].yty + out.ar_halves[1].yty;
        out.ar.n = out.ar_halves[0].n + out.ar_halves[1].n;
    }
    if (request.dct_power) {
        for (const cv::Rect& r : place_flat_blocks(integral, w, h, kDctBlock)) {
            if (clipped(r)) continue;
            const int bin = std::clamp(int(cv::mean(denoised(r))[0] * to8) / (256 / kPowerBins), 0, kPowerBins - 1);
            out.dct_power[bin] += block_dct_power(grain(r), &out.lags[bin]);
            out.dct_blocks[bin]++;
        }
    }
    return normalized;
}

}  // namespace filmgrain::analysis

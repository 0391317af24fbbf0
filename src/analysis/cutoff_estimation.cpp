#include "analysis/cutoff_estimation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace filmgrain::analysis {

int fit_power_step(const std::array<double, kDctBlock>& p) {
    // Frequencies 1..63; DC is removed by the planar detrending and carries no information.
    std::array<double, kDctBlock + 1> s{}, ss{};
    for (int u = 1; u < kDctBlock; u++) {
        s[u + 1] = s[u] + p[u];
        ss[u + 1] = ss[u] + p[u] * p[u];
    }
    auto sse = [&](int a, int b) {  // [a, b)
        if (b <= a) return 0.0;
        const double sum = s[b] - s[a];
        return (ss[b] - ss[a]) - sum * sum / (b - a);
    };
    double best = std::numeric_limits<double>::infinity();
    int best_last = kDctBlock - 1;
    for (int last = 4; last < kDctBlock; last++) {
        const double e = sse(1, last + 1) + sse(last + 1, kDctBlock);
        // A step must go down: a band above the "cut-off" as strong as below is no cut-off.
        const double low = (s[last + 1] - s[1]) / last;
        const double high = last + 1 < kDctBlock ? (s[kDctBlock] - s[last + 1]) / (kDctBlock - 1 - last) : 0.0;
        if (high > 0.5 * low) continue;
        if (e < best) {
            best = e;
            best_last = last;
        }
    }
    return best_last;
}

CutoffEstimate estimate_cutoffs(const cv::Mat& power) {
    CutoffEstimate c;
    for (int v = 1; v < kDctBlock; v++)
        for (int u = 1; u < kDctBlock; u++) {
            const double p = power.at<double>(v, u);
            c.horizontal_power[u] += p;
            c.vertical_power[v] += p;
        }
    // Kept frequencies 0..4(c+1)-1, so the last kept index L gives c = (L + 1) / 4 - 1.
    auto to_cutoff = [](int last) { return std::clamp(int(std::lround((last + 1) / 4.0)) - 1, 2, 14); };
    c.horizontal = to_cutoff(fit_power_step(c.horizontal_power));
    c.vertical = to_cutoff(fit_power_step(c.vertical_power));
    return c;
}

cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper) {
    cv::Mat sum = cv::Mat::zeros(kDctBlock, kDctBlock, CV_64F);
    int n = 0;
    for (int b = 0; b < kPowerBins; b++) {
        const int lo = b * (256 / kPowerBins), hi = lo + 256 / kPowerBins - 1;
        if (hi < lower || lo > upper) continue;
        sum += obs.dct_power[b];
        n += obs.dct_blocks[b];
    }
    if (n > 0) sum /= double(n);
    return sum;
}

}  // namespace filmgrain::analysis

#include "analysis/cutoff_estimation.hpp"

#include <limits>

namespace filmgrain::analysis {

void power_marginals(const cv::Mat& power, PowerMarginal& horizontal, PowerMarginal& vertical) {
    horizontal.fill(0.0);
    vertical.fill(0.0);
    // Frequency 0 along an axis carries the planar trend's leftovers, not grain.
    for (int v = 1; v < kDctBlock; v++)
        for (int u = 1; u < kDctBlock; u++) {
            const double p = power.at<double>(v, u);
            horizontal[u] += p;
            vertical[v] += p;
        }
    double sh = 0, sv = 0;
    for (int i = 0; i < kDctBlock; i++) sh += horizontal[i], sv += vertical[i];
    for (int i = 0; i < kDctBlock; i++) {
        if (sh > 0) horizontal[i] /= sh;
        if (sv > 0) vertical[i] /= sv;
    }
}

namespace {

int nearest_model(const PowerMarginal& observed, const std::array<PowerMarginal, kMaxCutoff + 1>& models, double* mismatch) {
    int best = 8;
    double best_d = std::numeric_limits<double>::infinity();
    for (int c = kMinCutoff; c <= kMaxCutoff; c++) {
        double d = 0;
        for (int i = 1; i < kDctBlock; i++) d += (observed[i] - models[c][i]) * (observed[i] - models[c][i]);
        if (d < best_d) best_d = d, best = c;
    }
    if (mismatch) *mismatch = best_d;
    return best;
}

}  // namespace

CutoffEstimate match_cutoffs(const cv::Mat& power, const CutoffModels& models) {
    CutoffEstimate c;
    power_marginals(power, c.horizontal_power, c.vertical_power);
    c.horizontal = nearest_model(c.horizontal_power, models.horizontal, &c.horizontal_mismatch);
    c.vertical = nearest_model(c.vertical_power, models.vertical, &c.vertical_mismatch);
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

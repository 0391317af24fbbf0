#include "analysis/cutoff_estimation.hpp"

#include <cmath>
#include <limits>

namespace filmgrain::analysis {
namespace {

// The cut-off whose model grain correlates like `observed` along one axis.
int nearest_model(const std::array<double, kMaxCorrelationLag + 1>& observed, const CutoffModels& models, bool horizontal,
                  double* mismatch) {
    const auto r = [horizontal](const LagSums& m, int k) { return horizontal ? m.rx(k) : m.ry(k); };
    int best = 8;
    double best_d = std::numeric_limits<double>::infinity();
    for (int c = kMinCutoff; c <= kMaxCutoff; c++) {
        // Above cut-off 7 the templates ring (negative correlation at lag 2) where smooth
        // grain has none, so no cut-off matches every lag: lag 1, which the grain's apparent
        // size follows, weighs three times lag 2 (squared errors over lags 1-3 let the
        // ringing pull the choice a step or two coarser than lag 1 wants).
        const double d = 3 * std::fabs(r(models.lags[c], 1) - observed[1]) + std::fabs(r(models.lags[c], 2) - observed[2]);
        if (d < best_d) best_d = d, best = c;
    }
    if (mismatch) *mismatch = best_d;
    return best;
}

bool overlaps(int bin, int lower, int upper) {
    const int lo = bin * (256 / kPowerBins), hi = lo + 256 / kPowerBins - 1;
    return hi >= lower && lo <= upper;
}

}  // namespace

CutoffEstimate match_cutoffs(const LagSums& observed, const CutoffModels& models) {
    CutoffEstimate c;
    for (int k = 1; k <= kMaxCorrelationLag; k++) {
        c.observed_x[k] = observed.rx(k);
        c.observed_y[k] = observed.ry(k);
    }
    c.horizontal = nearest_model(c.observed_x, models, true, &c.horizontal_mismatch);
    c.vertical = nearest_model(c.observed_y, models, false, &c.vertical_mismatch);
    return c;
}

LagSums lag_sums_in(const PlaneObservations& obs, int lower, int upper) {
    LagSums s;
    for (int b = 0; b < kPowerBins; b++)
        if (overlaps(b, lower, upper)) s.add(obs.lags[b]);
    return s;
}

int dct_blocks_in(const PlaneObservations& obs, int lower, int upper) {
    int n = 0;
    for (int b = 0; b < kPowerBins; b++)
        if (overlaps(b, lower, upper)) n += obs.dct_blocks[b];
    return n;
}

cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper) {
    cv::Mat sum = cv::Mat::zeros(kDctBlock, kDctBlock, CV_64F);
    int n = 0;
    for (int b = 0; b < kPowerBins; b++) {
        if (!overlaps(b, lower, upper)) continue;
        sum += obs.dct_power[b];
        n += obs.dct_blocks[b];
    }
    if (n > 0) sum /= double(n);
    return sum;
}

}  // namespace filmgrain::analysis

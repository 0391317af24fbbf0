#include "analysis/cutoff_estimation.hpp"

#include <cmath>
#include <limits>

namespace filmgrain::analysis {
namespace {

bool overlaps(int bin, int lower, int upper) {
    const int lo = bin * (256 / kPowerBins), hi = lo + 256 / kPowerBins - 1;
    return hi >= lower && lo <= upper;
}

}  // namespace

std::array<double, kMatchedLags> matched_correlations(const LagSums& s) {
    return {s.rx(1), s.ry(1), s.rd(0), s.rd(1), s.rx(2), s.ry(2)};
}

// One pair for both axes, not one cut-off per axis: the templates ring (negative correlation
// at lag 2 above cut-off 7) where smooth grain has none, so no pair matches every lag, and
// the best compromise shows only when the lags of both axes and the diagonals are weighed
// together (per-axis matching on lags 1 and 2 left the diagonal correlation of blurred
// grain 0.03-0.1 off). Absolute differences, not squared: one lag the model cannot reach
// (lag 2 of a ringing template) does not pull the choice away from the others.
double pair_mismatch(const LagSums& observed, const CutoffModels& models, int h, int v) {
    const auto target = matched_correlations(observed), model = matched_correlations(models.pairs[h][v]);
    double d = 0;
    for (int i = 0; i < kMatchedLags; i++) d += std::fabs(model[i] - target[i]);
    return d / kMatchedLags;
}

double correlation_standard_error(const LagSums& observed) {
    if (observed.samples <= 0) return std::numeric_limits<double>::infinity();
    double sum_sq = 0;
    for (double r : matched_correlations(observed)) sum_sq += r * r;
    return std::sqrt((1 + 2 * sum_sq) / observed.samples);
}

CutoffEstimate match_cutoffs(const LagSums& observed, const CutoffModels& models) {
    CutoffEstimate c;
    for (int k = 1; k <= kMaxCorrelationLag; k++) {
        c.observed_x[k] = observed.rx(k);
        c.observed_y[k] = observed.ry(k);
    }
    c.observed_diagonal = {observed.rd(0), observed.rd(1)};
    double best = std::numeric_limits<double>::infinity();
    for (int h = kMinCutoff; h <= kMaxCutoff; h++)
        for (int v = kMinCutoff; v <= kMaxCutoff; v++)
            if (const double d = pair_mismatch(observed, models, h, v); d < best) best = d, c.horizontal = h, c.vertical = v;
    c.mismatch = best;
    return c;
}

// Where the model cannot reach the observed correlation (mismatch 0.1 on Boolean grain), pairs
// far apart score alike, and the noise of an interval's fewer blocks alone would pick one of
// them per interval.
std::pair<int, int> interval_cutoffs(const LagSums& interval, const CutoffEstimate& pooled, const CutoffModels& models) {
    const CutoffEstimate own = match_cutoffs(interval, models);
    const double gain = pair_mismatch(interval, models, pooled.horizontal, pooled.vertical) - own.mismatch;
    if (gain > 2 * correlation_standard_error(interval)) return {own.horizontal, own.vertical};
    return {pooled.horizontal, pooled.vertical};
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

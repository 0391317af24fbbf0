// Statistics of grain on any clean/grainy pair, whatever synthesized it: the grain is
// grainy - clean (in units of full scale). Each function measures one property a viewer
// or a standard's model cares about.
#pragma once
#include <cmath>
#include <vector>

#include "core/float_plane.hpp"

namespace filmgrain::stats {

// grainy - clean; the planes must have the same size (throws Error otherwise).
FloatPlane grain_of(const FloatPlane& clean, const FloatPlane& grainy);

struct IntensityBin {
    double lo = 0, hi = 0;  // clean intensity range [lo, hi)
    long long count = 0;
    double mean = 0, variance = 0;  // of the grain
};
// Grain variance against the clean intensity (the scaling function an FGC or AV1 model
// signals), in `bins` equal intervals of [0, 1].
std::vector<IntensityBin> variance_vs_intensity(const FloatPlane& clean, const FloatPlane& grain, int bins = 16);

// Autocovariance of the grain (about its mean) at lags |dx|, |dy| <= max_lag:
// at(dx, dy) for the (2 max_lag + 1)^2 table.
struct Autocovariance {
    int max_lag = 0;
    std::vector<double> values;
    double at(int dx, int dy) const { return values[std::size_t(dy + max_lag) * (2 * max_lag + 1) + (dx + max_lag)]; }
};
Autocovariance autocovariance(const FloatPlane& grain, int max_lag);

// Power spectrum by Welch's method: the mean of |DFT|^2 / block^2 over non-overlapping
// block x block tiles (mean removed per tile); `radial` averages it over rings of integer
// frequency radius 0 .. block/2 (cycles per block).
struct PowerSpectrum {
    int block = 0;
    std::vector<double> values;  // block x block, DC at [0]
    std::vector<double> radial;
};
PowerSpectrum power_spectrum(const FloatPlane& grain, int block = 32);

// Grain size from the autocovariance: the lag (pixels, along x and y averaged, linearly
// interpolated) where the autocorrelation falls below 1/e, and the diameter of the disc
// whose area equals the correlation area sum_d C(d) / C(0) over the table.
struct GrainSize {
    double correlation_length = 0;
    double equivalent_diameter = 0;
};
GrainSize grain_size(const Autocovariance& c);

// Variance of the grain on the first and last column (row) of each block of `block`
// pixels against the other columns (rows): blending two overlapping windows, or deblocking
// the seams between templates, lowers it. Ratio < 1 is a loss at the boundaries.
struct BoundaryVariance {
    int block = 0;
    double boundary_columns = 0, interior_columns = 0, boundary_rows = 0, interior_rows = 0;
    double column_ratio() const { return interior_columns > 0 ? boundary_columns / interior_columns : 0; }
    double row_ratio() const { return interior_rows > 0 ? boundary_rows / interior_rows : 0; }
};
BoundaryVariance block_boundary_variance(const FloatPlane& grain, int block);

// Normalized autocorrelation of the grain at shifts (p, 0), (0, p) and (p, p): grain made of
// repeated templates correlates with itself at the template's period.
struct RepetitionPeak {
    int dx = 0, dy = 0;
    double correlation = 0;
};
std::vector<RepetitionPeak> repetition_at_periods(const FloatPlane& grain, const std::vector<int>& periods);
// The strongest correlations at shifts along the axes and the diagonal, min_lag..max_lag.
std::vector<RepetitionPeak> strongest_repetitions(const FloatPlane& grain, int min_lag, int max_lag, int count);

// Pearson correlation of two frames' grain (0 for independent grain, 1 for frozen grain).
double frame_to_frame_correlation(const FloatPlane& grain_a, const FloatPlane& grain_b);

// Relative L2 error of a measured autocovariance table against a reference function
// over the same lags: sqrt(sum (m - r)^2 / sum r^2).
template <typename Reference>
double relative_covariance_error(const Autocovariance& measured, Reference&& reference) {
    double e = 0, n = 0;
    for (int dy = -measured.max_lag; dy <= measured.max_lag; dy++)
        for (int dx = -measured.max_lag; dx <= measured.max_lag; dx++) {
            const double r = reference(dx, dy), d = measured.at(dx, dy) - r;
            e += d * d;
            n += r * r;
        }
    return n > 0 ? std::sqrt(e / n) : 0;
}

}  // namespace filmgrain::stats

// FGC cut-off frequencies (TR 23002-9 clause 8). The templates keep the first 4(c+1) of 64
// DCT frequencies along each axis, but the picture's grain is a mosaic of 16x16 (or 8x8)
// pieces of them, deblocked: its spectrum is no clean step, and an ideal low-pass cannot
// follow a smooth spectrum anyway. So the cut-offs are chosen by matching what the eye
// sees of grain size, its autocorrelation at short lags, against grain the target synthesis
// makes for each cut-off, measured on the same detrended 64x64 blocks. (A step fitted to
// the DCT power read real grain's cut-offs 1-2 steps too low: too coarse; matching whole
// power marginals chose different cut-offs on the two axes of isotropic grain.)
#pragma once
#include <array>
#include <utility>

#include <opencv2/core.hpp>

#include "analysis/block_observations.hpp"

namespace filmgrain::analysis {

inline constexpr int kMinCutoff = 2, kMaxCutoff = 14;  // RDD 5 / HM range of the signalled cut-offs

// The synthesis' grain per signalled cut-off pair, for one component: lag sums of grain made
// with horizontal cut-off h and vertical cut-off v, at [h][v]. Measured per pair, not
// composed from the axes: the deblocking across vertical block edges and the 16x16 mosaic
// make the diagonal correlation no product of the axial ones.
struct CutoffModels {
    std::array<std::array<LagSums, kMaxCutoff + 1>, kMaxCutoff + 1> pairs{};
};

// The short lags the cut-offs are matched on: the 3x3 neighbourhood (both diagonals) and
// lag 2 along each axis.
inline constexpr int kMatchedLags = 6;
std::array<double, kMatchedLags> matched_correlations(const LagSums& s);  // (1,0) (0,1) (1,1) (1,-1) (2,0) (0,2)

struct CutoffEstimate {
    int horizontal = 8, vertical = 8;  // signalled cut-offs, 2..14
    std::array<double, kMaxCorrelationLag + 1> observed_x{}, observed_y{};  // normalized autocorrelation
    std::array<double, 2> observed_diagonal{};                               // at (1,1) and (1,-1)
    double mismatch = 0;  // mean |r_model - r_observed| over the matched lags, at the choice
};

// Mean |r_model - r_observed| over the matched lags for the pair (h, v).
double pair_mismatch(const LagSums& observed, const CutoffModels& models, int h, int v);

// The cut-off pair whose model grain correlates like the observed grain at the matched lags
// (least mean absolute difference).
CutoffEstimate match_cutoffs(const LagSums& observed, const CutoffModels& models);

// The standard error of the observed correlations at the matched lags (Bartlett's formula,
// the matched lags standing for the grain's whole correlation): how far two pairs' mismatches
// may differ by the observation's noise alone.
double correlation_standard_error(const LagSums& observed);

// The pair an intensity interval signals: the component's pooled pair, unless another pair
// matches the interval's own observations better by more than twice their standard error.
std::pair<int, int> interval_cutoffs(const LagSums& interval, const CutoffEstimate& pooled, const CutoffModels& models);

// Lag sums of the observation bins that overlap [lower, upper] (8-bit).
LagSums lag_sums_in(const PlaneObservations& obs, int lower, int upper);

// 64x64 blocks observed in the bins that overlap [lower, upper] (8-bit).
int dct_blocks_in(const PlaneObservations& obs, int lower, int upper);

// Mean DCT power of the observation bins that overlap [lower, upper] (8-bit): the report's
// spectrum.
cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper);

}  // namespace filmgrain::analysis

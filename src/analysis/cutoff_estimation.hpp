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

#include <opencv2/core.hpp>

#include "analysis/block_observations.hpp"

namespace filmgrain::analysis {

inline constexpr int kMinCutoff = 2, kMaxCutoff = 14;  // RDD 5 / HM range of the signalled cut-offs

// The synthesis' grain per signalled cut-off c, for one component: lag sums of grain made
// with both cut-offs c (the template is separable: the horizontal correlation follows the
// horizontal cut-off, the vertical the vertical).
struct CutoffModels {
    std::array<LagSums, kMaxCutoff + 1> lags{};
};

struct CutoffEstimate {
    int horizontal = 8, vertical = 8;  // signalled cut-offs, 2..14
    std::array<double, kMaxCorrelationLag + 1> observed_x{}, observed_y{};  // normalized autocorrelation
    double horizontal_mismatch = 0, vertical_mismatch = 0;  // correlation differences at the choice
};

// Per axis, the cut-off whose model grain correlates like the observed grain at lags 1 and 2.
CutoffEstimate match_cutoffs(const LagSums& observed, const CutoffModels& models);

// Lag sums of the observation bins that overlap [lower, upper] (8-bit).
LagSums lag_sums_in(const PlaneObservations& obs, int lower, int upper);

// 64x64 blocks observed in the bins that overlap [lower, upper] (8-bit).
int dct_blocks_in(const PlaneObservations& obs, int lower, int upper);

// Mean DCT power of the observation bins that overlap [lower, upper] (8-bit): the report's
// spectrum.
cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper);

}  // namespace filmgrain::analysis

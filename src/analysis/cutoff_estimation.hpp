// FGC cut-off frequencies from the averaged 64x64 DCT power of flat grain blocks
// (TR 23002-9 clause 8; HM's analyser averages the squared DCT of the grain the same way).
// The templates keep the first 4(c+1) of 64 frequencies along each axis, but the picture's
// grain is a mosaic of 16x16 (or 8x8) pieces of them, deblocked: its spectrum is no clean
// step. So the cut-offs are chosen by matching, not read off a step: the observed marginal
// spectra against those of grain the target synthesis makes for each cut-off, measured the
// same way (a step fit read real grain's cut-offs 1-2 steps too low: too coarse).
#pragma once
#include <array>

#include <opencv2/core.hpp>

#include "analysis/block_observations.hpp"

namespace filmgrain::analysis {

inline constexpr int kMinCutoff = 2, kMaxCutoff = 14;  // RDD 5 / HM range of the signalled cut-offs

using PowerMarginal = std::array<double, kDctBlock>;  // index = frequency; DC = 0; sums to 1

// What the synthesis' grain looks like per signalled cut-off, for one component: the
// horizontal marginal of grain made with horizontal cut-off c (and vertical, likewise).
struct CutoffModels {
    std::array<PowerMarginal, kMaxCutoff + 1> horizontal{}, vertical{};
};

struct CutoffEstimate {
    int horizontal = 8, vertical = 8;  // signalled cut-offs, 2..14
    PowerMarginal horizontal_power{}, vertical_power{};  // the observed marginals
    double horizontal_mismatch = 0, vertical_mismatch = 0;  // sum of squared differences at the choice
};

// Marginals of a mean power (CV_64F 64x64, rows = vertical frequency), DC excluded, each
// normalized to sum 1 (shape only: the level is the intervals' business).
void power_marginals(const cv::Mat& power, PowerMarginal& horizontal, PowerMarginal& vertical);

// The cut-offs whose model marginals are nearest (least squares) to the observed ones.
CutoffEstimate match_cutoffs(const cv::Mat& power, const CutoffModels& models);

// Mean power of the observation bins that overlap [lower, upper] (8-bit), or of all bins.
cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper);

}  // namespace filmgrain::analysis

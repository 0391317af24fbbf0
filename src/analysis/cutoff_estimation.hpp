// FGC cut-off frequencies from the averaged 64x64 DCT power of flat grain blocks
// (TR 23002-9 clause 8; HM's analyser averages the squared DCT of the grain the same way).
// The templates keep the first 4(c+1) of 64 frequencies along each axis, so a cut-off is a
// step in the marginal power: this fits a two-level step to each marginal and reads c from
// its position, clipped to the RDD 5 range 2..14.
#pragma once
#include <array>

#include <opencv2/core.hpp>

#include "analysis/block_observations.hpp"

namespace filmgrain::analysis {

struct CutoffEstimate {
    int horizontal = 8, vertical = 8;  // plane resolution, 2..14
    std::array<double, kDctBlock> horizontal_power{}, vertical_power{};  // marginals (DC excluded)
};

// power: mean squared DCT coefficients, CV_64F 64x64 (rows = vertical frequency).
CutoffEstimate estimate_cutoffs(const cv::Mat& power);

// Index of the last kept frequency of a step fitted to a marginal (1..63).
int fit_power_step(const std::array<double, kDctBlock>& marginal);

// Mean power of the observation bins that overlap [lower, upper] (8-bit), or of all bins.
cv::Mat mean_power(const PlaneObservations& obs, int lower, int upper);

}  // namespace filmgrain::analysis

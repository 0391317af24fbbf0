// Where grain can be measured: flat regions of the denoised picture (TR 23002-9 clause 8,
// as HM's analyser does it): Canny edges without pre-blur at full, half and quarter
// resolution, each dilated, combined, closed by dilation then erosion; samples too dark or
// too bright for the grain to be unclipped are excluded as well.
#pragma once
#include <opencv2/core.hpp>

namespace filmgrain::analysis {

// CV_8U, 255 = flat. `denoised` is CV_32F in sample units of `bit_depth`.
cv::Mat flat_region_mask(const cv::Mat& denoised, int bit_depth);

// The 8-bit intensity range kept: outside it, additive grain of any useful strength is
// clipped by the sample range and its level cannot be observed.
inline constexpr int kDarkestAnalysedIntensity = 6;
inline constexpr int kBrightestAnalysedIntensity = 249;

}  // namespace filmgrain::analysis

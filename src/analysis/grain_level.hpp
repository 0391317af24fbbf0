// The grain level exactly as the block observations measure it (RMS of the planar-detrended
// block standard deviations), for calibrating the models' parameters against it: whatever
// bias the measurement has, estimation and calibration share it, so it cancels.
#pragma once
#include <opencv2/core.hpp>

#include "filmgrain/frame.hpp"

namespace filmgrain::analysis {

// `block`: the observations' block size (kFgcLevelBlock or kAv1LevelBlock).
double measure_grain_level(const cv::Mat& grain, int block);

// Grain level of plane p of `grainy` - `clean`.
double measure_grain_level(const FrameView& grainy, const FrameView& clean, int p, int block);

// Lowest grain level (8-bit units) reported as grain; below it the analysis signals none.
inline constexpr double kMinGrainLevel8 = 0.5;

}  // namespace filmgrain::analysis

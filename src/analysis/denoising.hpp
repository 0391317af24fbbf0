// The grain image: the grainy picture minus a denoised estimate of the picture underneath
// (TR 23002-9 clause 8: denoising, then the difference as the grain estimate).
#pragma once
#include <vector>

#include <opencv2/core.hpp>

namespace filmgrain::analysis {

struct GrainEstimate {
    cv::Mat denoised;  // CV_32F, sample units
    cv::Mat grain;     // CV_32F, source - denoised (rescaled where temporal, see below)
    cv::Mat reliable;  // CV_8U, 255 where the grain is an unbiased estimate (temporal or supplied)
};

// Motion-adaptive temporal denoising of window[centre]: each neighbour contributes where the
// blurred difference to the centre frame is within the grain's own fluctuation (a robust
// threshold from the whole picture), so moving areas fall back to fewer frames. Averaging n
// frames whose grain is independent leaves (1 - 1/n) of the grain variance in the
// difference, which is undone per sample. Samples no neighbour matched take the spatial
// fallback and are marked unreliable.
GrainEstimate denoise_temporal(const std::vector<const cv::Mat*>& window, int centre, int bit_depth);

// Single-picture fallback: a Gaussian low-pass. The grain it yields misses the grain's own
// low frequencies, so it is marked unreliable.
GrainEstimate denoise_spatial(const cv::Mat& source);

// An externally supplied denoised picture (or the clean original of a synthetic test).
GrainEstimate grain_from_denoised(const cv::Mat& source, const cv::Mat& denoised);

}  // namespace filmgrain::analysis

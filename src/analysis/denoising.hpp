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

// Global motion of a neighbour relative to the centre picture, as a whole-sample
// translation: neighbour(x + dx, y + dy) shows what centre(x, y) shows (up to +-35 samples).
// (0, 0) when no shift matches clearly better than none (static or flat pictures).
cv::Point estimate_global_shift(const cv::Mat& centre, const cv::Mat& neighbour);

// A luma plane made ready for estimate_global_shift once (every picture is the centre of
// one analysis and the neighbour of up to 2 * radius others): low-passed at full resolution
// and at a quarter. Empty for pictures too small to estimate motion on.
struct MotionPicture {
    cv::Mat fine, coarse;
};
MotionPicture prepare_motion_picture(const cv::Mat& luma);
cv::Point estimate_global_shift(const MotionPicture& centre, const MotionPicture& neighbour);

// One neighbour of the temporal window as the denoiser uses it.
struct TemporalNeighbour {
    const cv::Mat* plane = nullptr;
    cv::Point shift;          // global motion (estimate_global_shift, in this plane's samples)
    const cv::Mat* guide = nullptr;  // optional CV_8U: where another plane (luma) accepted this neighbour
};

// Motion-adaptive temporal denoising of the centre picture: each neighbour, moved by its
// global shift, contributes where the blurred difference to the centre is within the
// grain's own fluctuation (a robust threshold from the whole picture) and where the guide
// (luma's decision, for chroma) accepted it, so moving areas fall back to fewer frames.
// Global motion compensation keeps panned pictures temporal (without it a pan sent
// everything to the spatial fallback: twice the luma error); the luma guide keeps chroma,
// whose texture is too faint to trip its own threshold, from taking moving texture for
// grain. Averaging n frames whose grain is independent leaves (1 - 1/n) of the grain
// variance in the difference, which is undone per sample. Samples no neighbour matched take
// the spatial fallback and are marked unreliable. `accepted` (optional) receives, per
// neighbour, where it contributed (CV_8U 255), for guiding the chroma planes.
GrainEstimate denoise_temporal(const cv::Mat& centre, const std::vector<TemporalNeighbour>& neighbours, int bit_depth,
                               std::vector<cv::Mat>* accepted = nullptr);

// Single-picture fallback: a Gaussian low-pass. The grain it yields misses the grain's own
// low frequencies, so it is marked unreliable.
GrainEstimate denoise_spatial(const cv::Mat& source);

// An externally supplied denoised picture (or the clean original of a synthetic test).
GrainEstimate grain_from_denoised(const cv::Mat& source, const cv::Mat& denoised);

}  // namespace filmgrain::analysis

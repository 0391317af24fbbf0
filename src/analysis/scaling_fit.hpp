// The grain level as a function of intensity (the "scaling function" both models signal),
// fitted to the block observations: sub-range averaging, outlier passes, a two-pass
// polynomial fit that fills sparse sub-ranges, constant extrapolation beyond the observed
// range (TR 23002-9 clause 8; HM's analyser fits, then quantizes).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "analysis/block_observations.hpp"

namespace filmgrain::analysis {

inline constexpr int kSubRangeWidth = 4;  // 8-bit levels per sub-range
inline constexpr int kSubRanges = 256 / kSubRangeWidth;

struct LevelCurve {
    std::array<double, 256> level{};   // grain standard deviation per 8-bit intensity, sample units
    std::array<double, 256> weight{};  // observations supporting each intensity (0 = extrapolated)
    std::array<double, kSubRanges> sub_range_level{};
    std::array<int, kSubRanges> sub_range_count{};
    std::array<double, kSubRanges> sub_range_spread{};  // standard deviation of the blocks' levels
    int observed_low = 255, observed_high = 0;  // intensity range with observations
    std::size_t observations = 0;               // after outlier removal
    std::size_t outliers = 0;
    std::array<double, 5> polynomial{};  // in x = intensity / 255
    bool valid() const { return observations > 0 && observed_low <= observed_high; }
};

LevelCurve fit_level_curve(const std::vector<BlockSample>& blocks);

// The level curve of one component for either model, and why it carries no grain: too few
// flat blocks to trust the fit, or no level above kMinGrainLevel8 (8-bit units, scaled to
// `bit_depth`). For luma the level is the largest over intensity bands; for chroma, the
// typical one (the block-count-weighted median of the sub-ranges): chroma without grain
// leaves only the denoiser's floor and a few leaked texture blocks, which lifted single
// sub-ranges over the threshold and gave luma-only grain chroma grain of its own.
// Returns the reason, empty when the component has grain.
std::string fit_component_curve(const std::vector<BlockSample>& blocks, int bit_depth, LevelCurve& curve,
                                bool chroma = false);

// Contiguous intensity intervals, each with one level: the segmentation with the least
// weighted squared error (the Lloyd-Max criterion restricted to intervals; solved exactly by
// dynamic programming over the 256 intensities).
struct LevelInterval {
    int lower = 0, upper = 255;
    double level = 0.0;
};
std::vector<LevelInterval> segment_levels(const LevelCurve& curve, int count);

// Worst relative error of a piecewise description against the curve over observed
// intensities (relative to the curve's largest level, so that near-zero levels do not
// dominate).
double relative_error(const LevelCurve& curve, const std::vector<double>& approx);
// The same, as an observation-weighted RMS (robust to a few noisy sub-ranges).
double rms_relative_error(const LevelCurve& curve, const std::vector<double>& approx);

// The accuracy every fit is held to: per band of kErrorBandWidth intensities with
// observations, |mean description - mean level| beyond twice the standard error of the
// band's measured level, relative to the band's own level (floored at a quarter of the
// peak, so that near-zero levels do not dominate); the worst band. Bands count alike
// whatever their number of blocks: a dark band seen in a few blocks needs its own interval
// as much as the well-observed midtones (a count-weighted criterion let one interval cover
// both, 17-32 % low in the darks). The standard error keeps fits from chasing, and the
// accuracy check from refusing, what the measurement itself cannot tell apart.
inline constexpr int kErrorBandWidth = 16;
double worst_band_error(const LevelCurve& curve, const std::vector<double>& approx, int* worst_band_lower = nullptr);

// Piecewise-linear points (value, level): a regularized least-squares fit on fixed knots,
// then points removed one at a time, least damage first, while at most `max_points` remain
// and the error stays within `tolerance` (relative, as relative_error).
struct LevelPoint {
    int value;
    double level;
};
std::vector<LevelPoint> fit_piecewise_linear(const LevelCurve& curve, int max_points, double tolerance);
std::vector<double> evaluate_piecewise_linear(const std::vector<LevelPoint>& points);

}  // namespace filmgrain::analysis

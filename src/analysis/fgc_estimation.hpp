// FGC SEI parameters (frequency-filtering model, additive blending) from observations:
// intervals from the level curve, cut-offs from the DCT power, and comp_model_value[0]
// with log2_scale_factor calibrated by synthesizing a flat picture through the chosen
// flavour and measuring it as the observations were measured.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "analysis/block_observations.hpp"
#include "analysis/cutoff_estimation.hpp"
#include "analysis/scaling_fit.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::analysis {

struct FgcTarget {
    FgcFlavour flavour = FgcFlavour::kRdd5;  // rdd5 or vtm: whose templates calibrate the scale
    ChromaFormat chroma = ChromaFormat::k420;
    int bit_depth = 8;
    double accuracy = 0.05;  // largest tolerated RMS relative error of the interval levels
    int max_intervals = 8;
};

// One component as the model describes it: intervals (levels in sample units) with their
// signalled cut-offs (chroma's as the SEI carries them: the synthesis scales them to the
// chroma plane).
struct FgcComponentLevels {
    std::vector<LevelInterval> intervals;
    std::vector<std::pair<int, int>> cutoffs;  // (horizontal, vertical) per interval
};

struct FgcComponentReport {
    bool present = false;
    LevelCurve curve;
    std::vector<LevelInterval> intervals;
    std::vector<double> error_by_order;  // worst band error (worst_band_error) with 1, 2, ... intervals
    int chosen_order = 0;
    double error = 0.0;
    int worst_band = -1;   // lower end of the band of that error (8-bit)
    bool accurate = true;  // error within the target's accuracy
    CutoffEstimate pooled;
    std::vector<std::pair<int, int>> cutoffs;  // signalled, per interval
    int cutoff_pairs = 0;
    std::string note;
};

struct FgcEstimate {
    FgcParams params;
    std::array<FgcComponentReport, 3> components;
};

FgcEstimate estimate_fgc(const std::array<PlaneObservations, 3>& obs, const FgcTarget& target);

// The fewest intervals (up to target.max_intervals) whose worst band error meets
// target.accuracy; fills intervals, error_by_order, chosen_order, error and accurate.
void choose_intervals(const LevelCurve& curve, const FgcTarget& target, FgcComponentReport& report);

// The SEI for given component levels (empty intervals = no grain for that component):
// chooses log2_scale_factor for precision and converts levels to comp_model_value.
FgcParams fgc_params_from_levels(const std::array<FgcComponentLevels, 3>& levels, const FgcTarget& target);

// A parameter set that disables synthesis (cancel flag set).
FgcParams fgc_no_grain();

}  // namespace filmgrain::analysis

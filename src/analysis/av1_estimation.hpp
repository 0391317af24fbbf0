// AV1 film grain parameters (the model AFGS1 carries) from observations: the AR filter by
// least squares over flat blocks (libaom's noise model fits the same causal neighbourhood),
// with the lag chosen by measured residual; the piecewise-linear scaling functions fitted
// to the level curves and reduced to at most 14 / 10 points; ar_coeff_shift and
// scaling_shift chosen for precision; the scaling calibrated by synthesizing flat pictures
// with the estimated filter and measuring them as the observations were measured.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "analysis/block_observations.hpp"
#include "analysis/scaling_fit.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::analysis {

struct Av1Target {
    ChromaFormat chroma = ChromaFormat::k420;
    int bit_depth = 8;
    // Largest tolerated relative error of the scaling function. Tighter than FGC's: the
    // syntax always has room for 14 luma points, and at 5 % the fit stopped at 3-6 of them,
    // cutting corners at the ends of the curve (median band error 4.8 % -> 2.6 %).
    double accuracy = 0.02;
    double lag_spectrum_tolerance = 0.08;  // least tolerated mean spectrum deviation from the longest lag's model
    int max_lag = 3;
    int grain_seed = 7391;
};

struct Av1ComponentReport {
    bool present = false;
    LevelCurve curve;
    std::vector<LevelPoint> points;  // levels in sample units
    double error = 0.0;    // worst band error of the points (worst_band_error)
    int worst_band = -1;   // lower end of that band (8-bit)
    bool accurate = true;  // error within the target's accuracy
    std::vector<double> residual_by_lag;  // normalized residual variance for lags 0..3
    std::vector<double> spectrum_error_by_lag;  // spectrum deviation from the longest lag's model
    double lag_tolerance = 0.0;                 // the deviation accepted (at least the split-half noise)
    int own_lag = 0;                            // the lag this plane alone would choose
    // Chroma: the scaling index's share of the luma average, in quarters (0: the chroma
    // sample alone; 4: the luma average alone), and for each share the spread of the blocks'
    // levels around the curve it indexes (pooled within-sub-range standard deviation).
    int luma_quarters = 0;
    std::vector<double> spread_by_luma_quarters;
    std::vector<double> coefficients;     // real-valued AR coefficients at the chosen lag
    std::string note;
};

struct Av1Estimate {
    Av1FilmGrainParams params;
    int chosen_lag = 0;
    std::array<Av1ComponentReport, 3> components;
    // The grainy samples never leave the studio range and some sit on its bounds: the grain
    // was clipped there, and clip_to_restricted_range makes the synthesis clip it alike.
    bool clipped_to_legal_range = false;
    double on_legal_bound = 0.0;  // fraction of the samples on the bounds
};

Av1Estimate estimate_av1(const std::array<PlaneObservations, 3>& obs, const Av1Target& target);

// Parameters for given level points (sample units) and real AR coefficients per plane
// (chroma: the luma term last, when luma has grain). Empty points = no grain there.
// `luma_quarters` per chroma plane: the scaling index's luma share (Av1ComponentReport).
Av1FilmGrainParams av1_params_from_levels(const std::array<std::vector<LevelPoint>, 3>& points, int lag,
                                          const std::array<std::vector<double>, 3>& coefficients,
                                          const Av1Target& target, const std::array<int, 3>& luma_quarters = {});

// The blocks with intensity8 replaced by the chroma scaling index that gives the luma
// average `luma_quarters` / 4 of its weight: ((4 - q) * chroma + q * luma) / 4, AV1
// 7.18.3.5 with cb_mult - 128 = 16 (4 - q), cb_luma_mult - 128 = 16 q, cb_offset 256.
std::vector<BlockSample> blocks_by_chroma_index(const std::vector<BlockSample>& blocks, int luma_quarters);

// Solves the AR model of one lag from the lag-3 normal equations. Returns the coefficients
// (AV1 order; the luma term last when `with_luma`) and the residual variance per equation.
std::vector<double> solve_ar(const ArEquations& eq, int lag, bool with_luma, double* residual);

// Normalized power spectrum (mean 1) of an AR filter with Gaussian innovation on an n x n
// frequency grid, for comparing models (luma filters only).
std::vector<double> ar_power_spectrum(const std::vector<double>& coefficients, int lag, int n);

}  // namespace filmgrain::analysis

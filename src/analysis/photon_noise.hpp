// Photon-noise presets: grain parameters for content that never had grain, from a
// camera-like model. A sensor of the given size behind the picture's pixel grid collects,
// at diffuse white and ISO 100, kElectronsPerUm2AtIso100 electrons per square micrometre;
// higher ISO means proportionally fewer. Shot noise (Poisson, sqrt of the electron count)
// plus read noise, taken through the transfer function's slope into code values, gives the
// grain level at every intensity. Photon noise is white and luma-only here (a neutral
// sensor response), so FGC uses the widest cut-offs and AV1 an AR lag of 0.
#pragma once
#include <string>

#include "analysis/av1_estimation.hpp"
#include "analysis/fgc_estimation.hpp"
#include "analysis/scaling_fit.hpp"

namespace filmgrain::analysis {

enum class TransferFunction { kSdr, kPq, kHlg };
TransferFunction parse_transfer_function(const std::string& name);  // sdr|bt709|gamma, pq, hlg

struct CameraModel {
    double iso = 800;
    double sensor_width_mm = 36.0, sensor_height_mm = 24.0;
    int width = 1920, height = 1080;  // picture size the sensor is resampled to
    TransferFunction transfer = TransferFunction::kSdr;
    int bit_depth = 8;
    bool full_range = false;
    double read_noise_electrons = 3.0;
};

inline constexpr double kElectronsPerUm2AtIso100 = 1500.0;

// Grain level (sample units) per 8-bit intensity.
LevelCurve photon_noise_levels(const CameraModel& camera);

FgcParams photon_noise_fgc(const CameraModel& camera, ChromaFormat chroma, FgcFlavour flavour, double accuracy,
                           FgcComponentReport* report = nullptr);
Av1FilmGrainParams photon_noise_av1(const CameraModel& camera, ChromaFormat chroma, double accuracy,
                                    Av1ComponentReport* report = nullptr);

}  // namespace filmgrain::analysis

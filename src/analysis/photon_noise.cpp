#include "analysis/photon_noise.hpp"

#include <algorithm>
#include <cmath>

#include "filmgrain/error.hpp"

namespace filmgrain::analysis {
namespace {

// Diffuse white: 203 cd/m2 in PQ (ITU-R BT.2408), scene light 0.2647 in HLG (75% signal).
constexpr double kPqDiffuseWhite = 203.0;
constexpr double kHlgDiffuseWhite = 0.2647;

// Signal 0..1 for linear light L (1 = diffuse white).
double oetf(TransferFunction tf, double L) {
    switch (tf) {
        case TransferFunction::kSdr:  // BT.709
            L = std::clamp(L, 0.0, 1.0);
            return L < 0.018 ? 4.5 * L : 1.099 * std::pow(L, 0.45) - 0.099;
        case TransferFunction::kPq: {  // SMPTE ST 2084 inverse EOTF
            const double y = std::clamp(L * kPqDiffuseWhite / 10000.0, 0.0, 1.0);
            const double m1 = 2610.0 / 16384, m2 = 2523.0 / 4096 * 128, c1 = 3424.0 / 4096, c2 = 2413.0 / 4096 * 32,
                         c3 = 2392.0 / 4096 * 32;
            const double p = std::pow(y, m1);
            return std::pow((c1 + c2 * p) / (1 + c3 * p), m2);
        }
        case TransferFunction::kHlg: {  // BT.2100 HLG OETF
            const double e = std::clamp(L * kHlgDiffuseWhite, 0.0, 1.0);
            const double a = 0.17883277, b = 1 - 4 * a, c = 0.5 - a * std::log(4 * a);
            return e <= 1.0 / 12 ? std::sqrt(3 * e) : a * std::log(12 * e - b) + c;
        }
    }
    return 0.0;
}

double max_light(TransferFunction tf) {
    return tf == TransferFunction::kSdr ? 1.0 : tf == TransferFunction::kPq ? 10000.0 / kPqDiffuseWhite : 1.0 / kHlgDiffuseWhite;
}

// Linear light for a signal value, by bisection (the OETFs are increasing).
double inverse_oetf(TransferFunction tf, double v) {
    double lo = 0, hi = max_light(tf);
    for (int i = 0; i < 80; i++) {
        const double mid = 0.5 * (lo + hi);
        (oetf(tf, mid) < v ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

TransferFunction parse_transfer_function(const std::string& name) {
    if (name == "sdr" || name == "bt709" || name == "gamma") return TransferFunction::kSdr;
    if (name == "pq" || name == "st2084") return TransferFunction::kPq;
    if (name == "hlg") return TransferFunction::kHlg;
    throw Error(ErrorCode::kInvalidArgument, "--transfer '" + name + "' is not known (allowed sdr, pq, hlg)");
}

LevelCurve photon_noise_levels(const CameraModel& cam) {
    if (!(cam.iso >= 1 && cam.iso <= 1e7))
        throw Error(ErrorCode::kInvalidArgument, "ISO " + std::to_string(cam.iso) + " is out of range (allowed 1..10000000)");
    if (!(cam.sensor_width_mm > 0 && cam.sensor_height_mm > 0 && cam.sensor_width_mm < 1000 && cam.sensor_height_mm < 1000))
        throw Error(ErrorCode::kInvalidArgument, "sensor size must be positive and below 1000 mm");
    const double pixel_um2 = (cam.sensor_width_mm * 1000.0 / cam.width) * (cam.sensor_height_mm * 1000.0 / cam.height);
    const double white_electrons = kElectronsPerUm2AtIso100 * pixel_um2 * 100.0 / cam.iso;
    const double code_scale = (cam.full_range ? 255.0 : 219.0) * double(1 << (cam.bit_depth - 8));
    const int lo = cam.full_range ? 0 : 16, hi = cam.full_range ? 255 : 235;
    LevelCurve c;
    for (int i = 0; i < 256; i++) {
        const double v = std::clamp((i - lo) / double(hi - lo), 0.0, 1.0);
        const double L = inverse_oetf(cam.transfer, v);
        const double electrons = L * white_electrons;
        const double sigma_l = std::sqrt(electrons + cam.read_noise_electrons * cam.read_noise_electrons) / white_electrons;
        // The slope of the transfer function over +-1 sigma (a secant: near black the
        // power-law slopes are unbounded, the noise is not).
        const double l0 = std::max(0.0, L - sigma_l), l1 = std::min(max_light(cam.transfer), L + sigma_l);
        const double slope = l1 > l0 ? (oetf(cam.transfer, l1) - oetf(cam.transfer, l0)) / (l1 - l0) : 0.0;
        c.level[i] = slope * sigma_l * code_scale;
        c.weight[i] = (i >= lo && i <= hi) ? 1.0 : 0.0;
    }
    c.observed_low = lo;
    c.observed_high = hi;
    c.observations = std::size_t(hi - lo + 1);
    for (int s = 0; s < kSubRanges; s++) {
        c.sub_range_level[s] = c.level[s * kSubRangeWidth + 1];
        c.sub_range_count[s] = 1;
    }
    return c;
}

FgcParams photon_noise_fgc(const CameraModel& cam, ChromaFormat chroma, FgcFlavour flavour, double accuracy,
                           FgcComponentReport* report) {
    FgcTarget t;
    t.flavour = flavour;
    t.chroma = chroma;
    t.bit_depth = cam.bit_depth;
    t.accuracy = accuracy;
    FgcComponentReport rep;
    rep.curve = photon_noise_levels(cam);
    choose_intervals(rep.curve, t, rep);
    // White noise: the widest band the model has.
    rep.cutoffs.assign(rep.intervals.size(), {14, 14});
    rep.cutoff_pairs = 1;
    rep.present = true;
    std::array<FgcComponentLevels, 3> levels;
    levels[0].intervals = rep.intervals;
    levels[0].cutoffs = rep.cutoffs;
    const FgcParams p = fgc_params_from_levels(levels, t);
    if (report) *report = rep;
    return p;
}

Av1FilmGrainParams photon_noise_av1(const CameraModel& cam, ChromaFormat chroma, double accuracy,
                                    Av1ComponentReport* report) {
    Av1Target t;
    t.chroma = chroma;
    t.bit_depth = cam.bit_depth;
    Av1ComponentReport rep;
    rep.curve = photon_noise_levels(cam);
    rep.points = fit_piecewise_linear(rep.curve, 14, accuracy);
    rep.error = worst_band_error(rep.curve, evaluate_piecewise_linear(rep.points));
    rep.present = true;
    std::array<std::vector<LevelPoint>, 3> points;
    points[0] = rep.points;
    const Av1FilmGrainParams p = av1_params_from_levels(points, 0, {}, t);
    if (report) *report = rep;
    return p;
}

}  // namespace filmgrain::analysis

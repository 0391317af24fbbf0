#include "tradeoff_methods.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "filmgrain/session.hpp"

namespace filmgrain::cli {

FgcParams fgc_params(int scale, int log2_scale_factor, int cutoff_h, int cutoff_v) {
    FgcParams p;
    p.log2_scale_factor = log2_scale_factor;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    FgcIntensityInterval iv;
    iv.intensity_interval_lower_bound = 0;
    iv.intensity_interval_upper_bound = 255;
    iv.comp_model_value = {scale, cutoff_h, cutoff_v, 0, 0, 0};
    p.comp[0].intervals = {iv};
    return p;
}

namespace {
// Solves A x = b (Gaussian elimination with partial pivoting); A is n x n row-major.
std::vector<double> solve(std::vector<double> a, std::vector<double> b) {
    const int n = int(b.size());
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (std::abs(a[r * n + c]) > std::abs(a[piv * n + c])) piv = r;
        for (int k = 0; k < n; k++) std::swap(a[c * n + k], a[piv * n + k]);
        std::swap(b[c], b[piv]);
        if (std::abs(a[c * n + c]) < 1e-300) continue;
        for (int r = c + 1; r < n; r++) {
            const double f = a[r * n + c] / a[c * n + c];
            for (int k = c; k < n; k++) a[r * n + k] -= f * a[c * n + k];
            b[r] -= f * b[c];
        }
    }
    std::vector<double> x(n, 0);
    for (int r = n - 1; r >= 0; r--) {
        double s = b[r];
        for (int k = r + 1; k < n; k++) s -= a[r * n + k] * x[k];
        x[r] = std::abs(a[r * n + r]) < 1e-300 ? 0 : s / a[r * n + r];
    }
    return x;
}
}  // namespace

Av1FilmGrainParams av1_params(const TargetCovariance& target, int scaling, int scaling_shift_minus_8, int seed) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = seed & 0xffff;
    p.num_y_points = 2;
    p.point_y_value[0] = 0;
    p.point_y_value[1] = 255;
    p.point_y_scaling[0] = p.point_y_scaling[1] = scaling;
    p.grain_scaling_minus_8 = scaling_shift_minus_8;
    p.ar_coeff_lag = 3;
    p.ar_coeff_shift_minus_6 = 0;  // coefficients in units of 1/64: the fit needs magnitudes above 1
    // The causal neighbours in the order of AV1 7.18.3.3: rows -lag..0, columns -lag..lag,
    // stopping before the current sample.
    std::vector<std::pair<int, int>> pos;
    for (int dy = -3; dy <= 0; dy++)
        for (int dx = -3; dx <= 3; dx++) {
            if (dy == 0 && dx == 0) break;
            pos.push_back({dx, dy});
        }
    const int n = int(pos.size());
    std::vector<double> a(std::size_t(n) * n), b(n);
    for (int i = 0; i < n; i++) {
        b[i] = target(pos[i].first, pos[i].second);
        for (int j = 0; j < n; j++) a[std::size_t(i) * n + j] = target(pos[i].first - pos[j].first, pos[i].second - pos[j].second);
    }
    const std::vector<double> coeff = solve(a, b);
    for (int i = 0; i < n; i++)
        p.ar_coeffs_y_plus_128[i] = 128 + int(std::clamp(std::lround(coeff[i] * 64), -128L, 127L));
    return p;
}

FrameSynthesizer fgc_synthesizer(const FgcParams& params, FgcFlavour flavour) {
    SessionOptions so;
    so.flavour = flavour;
    auto s = std::make_shared<Session>(so);
    // vfgs keeps a set in force (its reference has no persistence rules) and its random
    // state runs on across pictures: the set is given once. The other flavours get it with
    // every picture, as a stream that repeats its SEI.
    const bool once = flavour == FgcFlavour::kVfgs;
    if (once) s->receive_fgc_params(params, FgcCodec::kHevc);
    return [s, params, once](const FrameBuffer& src, FrameBuffer& dst, int frame) {
        if (!once) s->receive_fgc_params(params, FgcCodec::kHevc);
        FrameInfo fi;
        fi.ids = FgcPictureIds{frame, 0};
        s->apply(const_cast<FrameBuffer&>(src).view(), dst.view(), &fi);
    };
}

FrameSynthesizer av1_synthesizer(const Av1FilmGrainParams& params) {
    SessionOptions so;
    so.threads = 1;  // as the single-threaded synthesis these timings were first taken with
    auto s = std::make_shared<Session>(so);
    return [s, params](const FrameBuffer& src, FrameBuffer& dst, int frame) {
        Av1FilmGrainParams p = params;
        p.grain_seed = (params.grain_seed + frame * 7391) & 0xffff;
        p.update_grain = 1;
        s->receive_av1_params(p, 0, 1);
        s->apply(const_cast<FrameBuffer&>(src).view(), dst.view());
    };
}

std::string fixed_decimals(double v, int decimals) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return b;
}

}  // namespace filmgrain::cli

// A random AV1 film grain parameter set with every field in its syntax range, for the
// randomized harnesses that prove two paths equal (SIMD twins, verify's mistake synthesis).
#pragma once
#include <random>

#include "filmgrain/av1_params.hpp"

namespace filmgrain::test_support {

// mono: no chroma points. Chroma point counts are drawn independently (one may be 0 and the
// other not), which 4:2:0 streams cannot signal; callers that validate fix that up.
inline Av1FilmGrainParams random_av1_params(std::mt19937& rng, bool mono) {
    auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = u(0, 65535);
    auto points = [&](int max_n, auto& values, auto& scalings) {
        const int n = u(0, max_n);
        int v = -1, k = 0;
        for (; k < n; k++) {
            v += u(1, 30);
            if (v > 255) break;
            values[std::size_t(k)] = v;
            scalings[std::size_t(k)] = u(0, 255);
        }
        return k;
    };
    p.num_y_points = points(14, p.point_y_value, p.point_y_scaling);
    if (!mono) {
        p.chroma_scaling_from_luma = u(0, 3) == 0;
        if (!p.chroma_scaling_from_luma) {
            p.num_cb_points = points(10, p.point_cb_value, p.point_cb_scaling);
            p.num_cr_points = points(10, p.point_cr_value, p.point_cr_scaling);
        }
    }
    p.grain_scaling_minus_8 = u(0, 3);
    p.ar_coeff_lag = u(0, 3);
    for (auto& c : p.ar_coeffs_y_plus_128) c = u(100, 156);
    for (auto& c : p.ar_coeffs_cb_plus_128) c = u(100, 156);
    for (auto& c : p.ar_coeffs_cr_plus_128) c = u(100, 156);
    p.ar_coeff_shift_minus_6 = u(0, 3);
    p.grain_scale_shift = u(0, 3);
    p.cb_mult = u(0, 255), p.cb_luma_mult = u(0, 255), p.cb_offset = u(0, 511);
    p.cr_mult = u(0, 255), p.cr_luma_mult = u(0, 255), p.cr_offset = u(0, 511);
    p.overlap_flag = u(0, 1);
    p.clip_to_restricted_range = u(0, 1);
    return p;
}

}  // namespace filmgrain::test_support

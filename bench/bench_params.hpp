// The AV1 parameter set every benchmark in bench/ uses: three luma points, two per chroma
// component with their own multipliers, lag 3 (the most filter work), overlap on.
#pragma once
#include <cstddef>

#include "filmgrain/av1_params.hpp"

namespace filmgrain::bench {

inline Av1FilmGrainParams av1_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 1234;
    p.num_y_points = 3;
    p.point_y_value = {0, 128, 255};
    p.point_y_scaling = {40, 70, 50};
    p.num_cb_points = 2;
    p.point_cb_value = {0, 255};
    p.point_cb_scaling = {30, 40};
    p.num_cr_points = 2;
    p.point_cr_value = {0, 255};
    p.point_cr_scaling = {35, 45};
    p.grain_scaling_minus_8 = 3;
    p.ar_coeff_lag = 3;
    for (int i = 0; i < 24; i++) p.ar_coeffs_y_plus_128[std::size_t(i)] = 128 + (i % 7) - 3;
    for (int i = 0; i < 25; i++) p.ar_coeffs_cb_plus_128[std::size_t(i)] = 128 + (i % 5) - 2;
    for (int i = 0; i < 25; i++) p.ar_coeffs_cr_plus_128[std::size_t(i)] = 128 - (i % 5) + 2;
    p.ar_coeff_shift_minus_6 = 1;
    p.cb_mult = 128 + 10, p.cb_luma_mult = 192, p.cb_offset = 256;
    p.cr_mult = 128 - 10, p.cr_luma_mult = 180, p.cr_offset = 250;
    p.overlap_flag = 1;
    return p;
}

}  // namespace filmgrain::bench

// Per-component access to the AV1 parameter struct, shared by the AFGS1 reader
// and writer, whose syntax repeats the same pattern for y, cb and cr.
#pragma once
#include <array>

#include "filmgrain/av1_params.hpp"

namespace filmgrain::afgs1_fields {

inline const char* const kComponentName[3] = {"y", "cb", "cr"};

struct Scaling {
    int* count;
    int* values;
    int* scalings;
    int max_points;
};

inline Scaling scaling_of(Av1FilmGrainParams& p, int c) {
    if (c == 0) return {&p.num_y_points, p.point_y_value.data(), p.point_y_scaling.data(), 14};
    if (c == 1) return {&p.num_cb_points, p.point_cb_value.data(), p.point_cb_scaling.data(), 10};
    return {&p.num_cr_points, p.point_cr_value.data(), p.point_cr_scaling.data(), 10};
}

// {mult, luma_mult, offset} of cb (c = 1) or cr (c = 2).
inline std::array<int*, 3> mults_of(Av1FilmGrainParams& p, int c) {
    if (c == 1) return {&p.cb_mult, &p.cb_luma_mult, &p.cb_offset};
    return {&p.cr_mult, &p.cr_luma_mult, &p.cr_offset};
}

inline int* ar_coeffs_of(Av1FilmGrainParams& p, int c) {
    return c == 0 ? p.ar_coeffs_y_plus_128.data()
                  : c == 1 ? p.ar_coeffs_cb_plus_128.data() : p.ar_coeffs_cr_plus_128.data();
}

}  // namespace filmgrain::afgs1_fields

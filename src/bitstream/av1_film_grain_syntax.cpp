#include "bitstream/av1_film_grain_syntax.hpp"

#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::bitstream {
namespace {

[[noreturn]] void malformed(const std::string& what) {
    throw Error(ErrorCode::kMalformedPayload, "AV1 frame header: " + what);
}

}  // namespace

void read_av1_film_grain_values(BitReader& r, const Av1SequenceHeader& seq, Av1FilmGrainParams& p) {
    p.num_y_points = int(r.u(4, "num_y_points"));
    if (p.num_y_points > 14) malformed(out_of_range_message("num_y_points", p.num_y_points, 0, 14));
    for (int i = 0; i < p.num_y_points; i++) {
        p.point_y_value[std::size_t(i)] = int(r.u(8, "point_y_value"));
        p.point_y_scaling[std::size_t(i)] = int(r.u(8, "point_y_scaling"));
    }
    p.chroma_scaling_from_luma = seq.mono_chrome ? 0 : int(r.u(1, "chroma_scaling_from_luma"));
    if (seq.mono_chrome || p.chroma_scaling_from_luma ||
        (seq.subsampling_x == 1 && seq.subsampling_y == 1 && p.num_y_points == 0)) {
        p.num_cb_points = p.num_cr_points = 0;
    } else {
        p.num_cb_points = int(r.u(4, "num_cb_points"));
        if (p.num_cb_points > 10) malformed(out_of_range_message("num_cb_points", p.num_cb_points, 0, 10));
        for (int i = 0; i < p.num_cb_points; i++) {
            p.point_cb_value[std::size_t(i)] = int(r.u(8, "point_cb_value"));
            p.point_cb_scaling[std::size_t(i)] = int(r.u(8, "point_cb_scaling"));
        }
        p.num_cr_points = int(r.u(4, "num_cr_points"));
        if (p.num_cr_points > 10) malformed(out_of_range_message("num_cr_points", p.num_cr_points, 0, 10));
        for (int i = 0; i < p.num_cr_points; i++) {
            p.point_cr_value[std::size_t(i)] = int(r.u(8, "point_cr_value"));
            p.point_cr_scaling[std::size_t(i)] = int(r.u(8, "point_cr_scaling"));
        }
    }
    p.grain_scaling_minus_8 = int(r.u(2, "grain_scaling_minus_8"));
    p.ar_coeff_lag = int(r.u(2, "ar_coeff_lag"));
    const int num_pos_luma = p.num_pos_luma(), num_pos_chroma = p.num_pos_chroma();
    if (p.num_y_points)
        for (int i = 0; i < num_pos_luma; i++) p.ar_coeffs_y_plus_128[std::size_t(i)] = int(r.u(8, "ar_coeffs_y_plus_128"));
    if (p.chroma_scaling_from_luma || p.num_cb_points)
        for (int i = 0; i < num_pos_chroma; i++)
            p.ar_coeffs_cb_plus_128[std::size_t(i)] = int(r.u(8, "ar_coeffs_cb_plus_128"));
    if (p.chroma_scaling_from_luma || p.num_cr_points)
        for (int i = 0; i < num_pos_chroma; i++)
            p.ar_coeffs_cr_plus_128[std::size_t(i)] = int(r.u(8, "ar_coeffs_cr_plus_128"));
    p.ar_coeff_shift_minus_6 = int(r.u(2, "ar_coeff_shift_minus_6"));
    p.grain_scale_shift = int(r.u(2, "grain_scale_shift"));
    if (p.num_cb_points) {
        p.cb_mult = int(r.u(8, "cb_mult"));
        p.cb_luma_mult = int(r.u(8, "cb_luma_mult"));
        p.cb_offset = int(r.u(9, "cb_offset"));
    }
    if (p.num_cr_points) {
        p.cr_mult = int(r.u(8, "cr_mult"));
        p.cr_luma_mult = int(r.u(8, "cr_luma_mult"));
        p.cr_offset = int(r.u(9, "cr_offset"));
    }
    p.overlap_flag = int(r.u(1, "overlap_flag"));
    p.clip_to_restricted_range = int(r.u(1, "clip_to_restricted_range"));
}

}  // namespace filmgrain::bitstream

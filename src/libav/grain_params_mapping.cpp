#include "libav/grain_params_mapping.hpp"

extern "C" {
#include <libavutil/film_grain_params.h>
}

namespace filmgrain::libav {

Av1FilmGrainParams av1_params_from_libav(const AVFilmGrainParams& fgp) {
    const AVFilmGrainAOMParams& a = fgp.codec.aom;
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = int(fgp.seed & 0xFFFF);
    p.update_grain = 1;
    p.num_y_points = a.num_y_points;
    for (int i = 0; i < a.num_y_points && i < 14; i++) {
        p.point_y_value[i] = a.y_points[i][0];
        p.point_y_scaling[i] = a.y_points[i][1];
    }
    p.chroma_scaling_from_luma = a.chroma_scaling_from_luma;
    p.num_cb_points = a.num_uv_points[0];
    p.num_cr_points = a.num_uv_points[1];
    for (int i = 0; i < 10; i++) {
        if (i < a.num_uv_points[0]) {
            p.point_cb_value[i] = a.uv_points[0][i][0];
            p.point_cb_scaling[i] = a.uv_points[0][i][1];
        }
        if (i < a.num_uv_points[1]) {
            p.point_cr_value[i] = a.uv_points[1][i][0];
            p.point_cr_scaling[i] = a.uv_points[1][i][1];
        }
    }
    p.grain_scaling_minus_8 = a.scaling_shift - 8;
    p.ar_coeff_lag = a.ar_coeff_lag;
    for (int i = 0; i < 24; i++) p.ar_coeffs_y_plus_128[i] = a.ar_coeffs_y[i] + 128;
    for (int i = 0; i < 25; i++) {
        p.ar_coeffs_cb_plus_128[i] = a.ar_coeffs_uv[0][i] + 128;
        p.ar_coeffs_cr_plus_128[i] = a.ar_coeffs_uv[1][i] + 128;
    }
    p.ar_coeff_shift_minus_6 = a.ar_coeff_shift - 6;
    p.grain_scale_shift = a.grain_scale_shift;
    p.cb_mult = a.uv_mult[0] + 128;
    p.cb_luma_mult = a.uv_mult_luma[0] + 128;
    p.cb_offset = a.uv_offset[0] + 256;
    p.cr_mult = a.uv_mult[1] + 128;
    p.cr_luma_mult = a.uv_mult_luma[1] + 128;
    p.cr_offset = a.uv_offset[1] + 256;
    p.overlap_flag = a.overlap_flag;
    p.clip_to_restricted_range = a.limit_output_range;
    return p;
}

FgcParams fgc_params_from_libav(const AVFilmGrainParams& fgp) {
    const AVFilmGrainH274Params& h = fgp.codec.h274;
    FgcParams p;
    p.film_grain_model_id = h.model_id;
    p.blending_mode_id = h.blending_mode_id;
    p.log2_scale_factor = h.log2_scale_factor;
    for (int c = 0; c < 3; c++) {
        FgcComponentModel& m = p.comp[c];
        m.comp_model_present_flag = h.component_model_present[c] != 0;
        if (!m.comp_model_present_flag) continue;
        m.num_model_values_minus1 = h.num_model_values[c] - 1;
        for (int i = 0; i < h.num_intensity_intervals[c] && i < 256; i++) {
            FgcIntensityInterval iv;
            iv.intensity_interval_lower_bound = h.intensity_interval_lower_bound[c][i];
            iv.intensity_interval_upper_bound = h.intensity_interval_upper_bound[c][i];
            for (int v = 0; v < 6; v++) iv.comp_model_value[v] = v < h.num_model_values[c] ? h.comp_model_value[c][i][v] : 0;
            m.intervals.push_back(iv);
        }
    }
    p.film_grain_characteristics_persistence_flag = true;
    return p;
}

}  // namespace filmgrain::libav

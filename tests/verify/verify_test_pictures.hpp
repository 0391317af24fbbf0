// Pictures and parameter sets the verify tests re-synthesize mistakes on: content that
// exercises every stage (a ramp over the whole intensity range with texture, odd sizes).
#pragma once
#include <random>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::verify::test_pictures {

// Luma ramps left to right over the full range, chroma top to bottom, with a little noise.
inline FrameBuffer textured_picture(int width, int height, PixelFormat fmt, unsigned seed) {
    FrameBuffer f(width, height, fmt);
    FrameView v = f.view();
    std::mt19937 rng(seed);
    const int max = (1 << fmt.bit_depth) - 1;
    for (int p = 0; p < v.plane_count(); p++)
        for (int y = 0; y < v.planes[p].height; y++)
            for (int x = 0; x < v.planes[p].width; x++) {
                const double t = p == 0 ? double(x) / std::max(1, v.planes[p].width - 1)
                                        : double(y) / std::max(1, v.planes[p].height - 1);
                const int s = std::clamp(int(t * max) + int(rng() % 9) - 4, 0, max);
                if (fmt.bit_depth > 8)
                    v.planes[p].row<uint16_t>(y)[x] = uint16_t(s);
                else
                    v.planes[p].row<uint8_t>(y)[x] = uint8_t(s);
            }
    return f;
}

// A step inside the partial blocks at the right edge (dark, then bright): averages over the
// samples inside the picture and over edge-replicated padding then fall into different
// intensity intervals of full_fgc_params(), as they can on real content.
inline void add_edge_step(FrameBuffer& f) {
    FrameView v = f.view();
    const int up = v.bit_depth - 8;
    for (int p = 0; p < v.plane_count(); p++) {
        const int w = v.planes[p].width, partial = w % 8;
        if (partial < 2) continue;
        for (int y = 0; y < v.planes[p].height; y++)
            for (int x = w - partial; x < w; x++) {
                const int s = (x < w - (partial >= 6 ? 2 : 1) ? 60 : 200) << up;
                if (v.bit_depth > 8)
                    v.planes[p].row<uint16_t>(y)[x] = uint16_t(s);
                else
                    v.planes[p].row<uint8_t>(y)[x] = uint8_t(s);
            }
    }
}

// Every AV1 stage in use: luma and chroma points, lag-2 AR with a luma term, overlap,
// restricted clipping, chroma mixing with luma.
inline Av1FilmGrainParams full_av1_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 4321;
    p.num_y_points = 3;
    p.point_y_value = {0, 128, 255};
    p.point_y_scaling = {70, 120, 50};
    p.num_cb_points = 2;
    p.point_cb_value = {0, 255};
    p.point_cb_scaling = {80, 60};
    p.num_cr_points = 2;
    p.point_cr_value = {16, 220};
    p.point_cr_scaling = {40, 90};
    p.grain_scaling_minus_8 = 2;
    p.ar_coeff_lag = 2;
    for (int i = 0; i < 24; ++i) p.ar_coeffs_y_plus_128[std::size_t(i)] = 128 + (i % 5) * 3 - 6;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cb_plus_128[std::size_t(i)] = 128 + (i % 7) - 3;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cr_plus_128[std::size_t(i)] = 128 - (i % 6) + 2;
    p.ar_coeff_shift_minus_6 = 1;
    p.grain_scale_shift = 0;
    p.cb_mult = 100, p.cb_luma_mult = 180, p.cb_offset = 240;
    p.cr_mult = 150, p.cr_luma_mult = 210, p.cr_offset = 270;
    p.overlap_flag = 1;
    p.clip_to_restricted_range = 1;
    return p;
}

// An FGC SEI with grain on all three components, intervals that leave the darkest and the
// brightest blocks without grain, and per-component cut-offs.
inline FgcParams full_fgc_params() {
    FgcParams p;
    p.log2_scale_factor = 4;
    for (int c = 0; c < 3; c++) {
        FgcComponentModel& m = p.comp[std::size_t(c)];
        m.comp_model_present_flag = true;
        m.num_model_values_minus1 = 2;
        FgcIntensityInterval low, high;
        low.intensity_interval_lower_bound = 40;
        low.intensity_interval_upper_bound = 129;
        low.comp_model_value = {90 - 20 * c, 8, 8 + c, 0, 0, 0};
        high.intensity_interval_lower_bound = 130;
        high.intensity_interval_upper_bound = 215;
        high.comp_model_value = {140 - 30 * c, 5, 12, 0, 0, 0};
        m.intervals = {low, high};
    }
    return p;
}

}  // namespace filmgrain::verify::test_pictures

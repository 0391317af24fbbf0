// FFmpeg's exported film grain side data (AVFilmGrainParams, libavutil/film_grain_params.h)
// as this project's parameter types.
#pragma once
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"

struct AVFilmGrainParams;

namespace filmgrain::libav {

// AV_FILM_GRAIN_PARAMS_AV1: FFmpeg stores the unbiased values (ar_coeffs as signed,
// uv_mult / uv_mult_luma minus 128, uv_offset minus 256, scaling_shift = grain_scaling_minus_8
// + 8, ar_coeff_shift = ar_coeff_shift_minus_6 + 6); the bitstream biases are put back.
// grain_seed is AVFilmGrainParams::seed.
Av1FilmGrainParams av1_params_from_libav(const AVFilmGrainParams& p);

// AV_FILM_GRAIN_PARAMS_H274: the syntax elements of the FGC SEI FFmpeg decided applies to
// the frame (it handles persistence and cancellation itself). The colour description is
// not carried over (separate_colour_description_present_flag = 0): FFmpeg only exports it,
// the picture's own format is what synthesis follows.
FgcParams fgc_params_from_libav(const AVFilmGrainParams& p);

}  // namespace filmgrain::libav

#include "av1/params_validation.hpp"

#include <string>
#include <utility>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::av1 {
namespace {

// The field name is built only for the message: validation runs for every frame, and a
// valid frame must not allocate (steady-state synthesis is allocation-free).
inline std::string field_name(const char* name) { return name; }
template <typename F, typename = decltype(std::declval<F>()())>
std::string field_name(const F& make) {
    return make();
}

template <typename Name>
void check_range(const Name& field, long long value, long long lo, long long hi) {
    if (value < lo || value > hi)
        throw Error(ErrorCode::kInvalidParams, out_of_range_message(field_name(field), value, lo, hi));
}

// Points of one scaling function: values 8 bits and strictly increasing (the
// spec requires it so that the interpolation divides by a positive run).
void check_points(const char* value_name, const char* scaling_name, const int* values, const int* scalings,
                  int count) {
    for (int i = 0; i < count; ++i) {
        const long long lo = i == 0 ? 0 : values[i - 1] + 1;
        if (values[i] < lo || values[i] > 255) {
            std::string msg = out_of_range_message(indexed(value_name, i), values[i], lo, 255);
            if (i > 0) msg += " (point values must be strictly increasing)";
            throw Error(ErrorCode::kInvalidParams, msg);
        }
        check_range([&] { return indexed(scaling_name, i); }, scalings[i], 0, 255);
    }
}

}  // namespace

void validate_params(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth) {
    if (bit_depth != 8 && bit_depth != 10 && bit_depth != 12)
        throw Error(ErrorCode::kInvalidParams,
                    "bit_depth = " + std::to_string(bit_depth) + " is not supported by AV1 (allowed 8, 10, 12)");
    check_range("apply_grain", p.apply_grain, 0, 1);
    if (!p.apply_grain) return;
    check_range("grain_seed", p.grain_seed, 0, 65535);
    check_range("update_grain", p.update_grain, 0, 1);
    check_range("film_grain_params_ref_idx", p.film_grain_params_ref_idx, 0, 7);

    const bool mono = format == ChromaFormat::k400;
    const bool is420 = format == ChromaFormat::k420;

    check_range("num_y_points", p.num_y_points, 0, 14);
    check_points("point_y_value", "point_y_scaling", p.point_y_value.data(), p.point_y_scaling.data(),
                 p.num_y_points);

    // Monochrome streams do not signal chroma_scaling_from_luma (inferred 0).
    check_range(mono ? "chroma_scaling_from_luma (monochrome frame)" : "chroma_scaling_from_luma",
                p.chroma_scaling_from_luma, 0, mono ? 0 : 1);

    // num_cb_points / num_cr_points are not signalled (inferred 0) for
    // monochrome, with chroma_scaling_from_luma, and for 4:2:0 without luma points.
    const char* why = "";
    if (mono) why = " (monochrome frame)";
    else if (p.chroma_scaling_from_luma) why = " (chroma_scaling_from_luma = 1)";
    else if (is420 && p.num_y_points == 0 && !p.chroma_point_counts_signalled)
        why = " (4:2:0 with num_y_points = 0)";  // AV1 infers them 0 there; AFGS1 signals them
    const int max_chroma_points = *why ? 0 : 10;
    check_range([&] { return std::string("num_cb_points") + why; }, p.num_cb_points, 0, max_chroma_points);
    check_range([&] { return std::string("num_cr_points") + why; }, p.num_cr_points, 0, max_chroma_points);
    check_points("point_cb_value", "point_cb_scaling", p.point_cb_value.data(), p.point_cb_scaling.data(),
                 p.num_cb_points);
    check_points("point_cr_value", "point_cr_scaling", p.point_cr_value.data(), p.point_cr_scaling.data(),
                 p.num_cr_points);
    // 6.8.20: in 4:2:0 either both chroma planes have points or neither.
    if (is420 && (p.num_cb_points == 0) != (p.num_cr_points == 0))
        throw Error(ErrorCode::kInvalidParams,
                    "num_cb_points = " + std::to_string(p.num_cb_points) + " and num_cr_points = " +
                        std::to_string(p.num_cr_points) +
                        " are inconsistent: for 4:2:0 both must be 0 or both must be non-zero");

    check_range("grain_scaling_minus_8", p.grain_scaling_minus_8, 0, 3);
    check_range("ar_coeff_lag", p.ar_coeff_lag, 0, 3);
    if (p.num_y_points > 0)
        for (int i = 0; i < p.num_pos_luma(); ++i)
            check_range([&] { return indexed("ar_coeffs_y_plus_128", i); }, p.ar_coeffs_y_plus_128[static_cast<std::size_t>(i)], 0,
                        255);
    if (p.chroma_scaling_from_luma || p.num_cb_points > 0)
        for (int i = 0; i < p.num_pos_chroma(); ++i)
            check_range([&] { return indexed("ar_coeffs_cb_plus_128", i); }, p.ar_coeffs_cb_plus_128[static_cast<std::size_t>(i)], 0,
                        255);
    if (p.chroma_scaling_from_luma || p.num_cr_points > 0)
        for (int i = 0; i < p.num_pos_chroma(); ++i)
            check_range([&] { return indexed("ar_coeffs_cr_plus_128", i); }, p.ar_coeffs_cr_plus_128[static_cast<std::size_t>(i)], 0,
                        255);
    check_range("ar_coeff_shift_minus_6", p.ar_coeff_shift_minus_6, 0, 3);
    check_range("grain_scale_shift", p.grain_scale_shift, 0, 3);
    if (p.num_cb_points > 0) {
        check_range("cb_mult", p.cb_mult, 0, 255);
        check_range("cb_luma_mult", p.cb_luma_mult, 0, 255);
        check_range("cb_offset", p.cb_offset, 0, 511);
    }
    if (p.num_cr_points > 0) {
        check_range("cr_mult", p.cr_mult, 0, 255);
        check_range("cr_luma_mult", p.cr_luma_mult, 0, 255);
        check_range("cr_offset", p.cr_offset, 0, 511);
    }
    check_range("overlap_flag", p.overlap_flag, 0, 1);
    check_range("clip_to_restricted_range", p.clip_to_restricted_range, 0, 1);
}

}  // namespace filmgrain::av1

// The C API (include/filmgrain/filmgrain.h) over filmgrain::Session: argument checks that C
// needs (NULL pointers, struct sizes, enum ranges), conversion of the C structs to the
// C++ value types, and every exception turned into a status plus a message.
#include "filmgrain/filmgrain.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <new>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <iterator>
#include <vector>

#include "bitstream/afgs1_in_stream.hpp"
#include "bitstream/sei_messages.hpp"
#include "bitstream/stream_scan.hpp"
#include "core/field_names.hpp"
#include "core/thread_pool.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/filmgrain.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_sei.hpp"

struct fg_context {
    filmgrain::Session grain;
    std::string last_error;

    explicit fg_context(const filmgrain::SessionOptions& o) : grain(o) {}
};

namespace {

using filmgrain::Error;
using filmgrain::ErrorCode;

fg_status to_status(ErrorCode code) {
    switch (code) {
    case ErrorCode::kOk: return FG_OK;
    case ErrorCode::kInvalidArgument: return FG_ERROR_INVALID_ARGUMENT;
    case ErrorCode::kInvalidParams: return FG_ERROR_INVALID_PARAMS;
    case ErrorCode::kMalformedPayload: return FG_ERROR_MALFORMED_PAYLOAD;
    case ErrorCode::kUnsupported: return FG_ERROR_UNSUPPORTED;
    case ErrorCode::kIo: return FG_ERROR_IO;
    case ErrorCode::kOutOfMemory: return FG_ERROR_OUT_OF_MEMORY;
    case ErrorCode::kInternal: return FG_ERROR_INTERNAL;
    }
    return FG_ERROR_INTERNAL;
}

// Runs `body`, mapping whatever it throws to a status and `message`.
template <typename Body>
fg_status guarded(std::string& message, Body&& body) noexcept {
    try {
        message.clear();
        body();
        return FG_OK;
    } catch (const Error& e) {
        message = e.what();
        return to_status(e.code());
    } catch (const std::bad_alloc&) {
        message = "out of memory";
        return FG_ERROR_OUT_OF_MEMORY;
    } catch (const std::exception& e) {
        message = std::string("internal error: ") + e.what();
        return FG_ERROR_INTERNAL;
    } catch (...) {
        message = "internal error: unknown exception";
        return FG_ERROR_INTERNAL;
    }
}

[[noreturn]] void invalid(const std::string& message) { throw Error(ErrorCode::kInvalidArgument, message); }

// Older callers may pass a smaller struct: fields past their struct_size keep defaults.
template <typename T>
T sized_copy(const T* in, std::size_t min_size, const T& defaults, const char* name) {
    T out = defaults;
    const std::size_t size = in->struct_size;
    if (size < min_size || size > (std::size_t(1) << 16))
        invalid(std::string(name) + ".struct_size = " + std::to_string(size) + " is not the size of a known version " +
                "(expected " + std::to_string(sizeof(T)) + "; call the matching _init function)");
    std::memcpy(&out, in, std::min(size, sizeof(T)));
    out.struct_size = sizeof(T);
    return out;
}

filmgrain::SessionOptions to_options(const fg_options& o) {
    filmgrain::SessionOptions c;
    if (o.flavour < FG_FLAVOUR_RDD5 || o.flavour > FG_FLAVOUR_FFMPEG)
        invalid(filmgrain::out_of_range_message("options.flavour", o.flavour, 0, 4));
    if (o.pattern_interpolation != 0 && o.pattern_interpolation != 1)
        invalid(filmgrain::out_of_range_message("options.pattern_interpolation", o.pattern_interpolation, 0, 1));
    if (o.persistence < FG_PERSISTENCE_REFERENCE || o.persistence > FG_PERSISTENCE_SEMANTIC)
        invalid(filmgrain::out_of_range_message("options.persistence", o.persistence, 0, 1));
    if (o.passthrough_invalid != 0 && o.passthrough_invalid != 1)
        invalid(filmgrain::out_of_range_message("options.passthrough_invalid", o.passthrough_invalid, 0, 1));
    if (o.threads < 0 || o.threads > filmgrain::kMaxThreads)
        invalid(filmgrain::out_of_range_message("options.threads", o.threads, 0, filmgrain::kMaxThreads));
    if (o.coded_width < 0) invalid(filmgrain::out_of_range_message("options.coded_width", o.coded_width, 0, INT32_MAX));
    if (o.coded_height < 0)
        invalid(filmgrain::out_of_range_message("options.coded_height", o.coded_height, 0, INT32_MAX));
    if (o.vfgs_gain_percent < 0)
        invalid(filmgrain::out_of_range_message("options.vfgs_gain_percent", o.vfgs_gain_percent, 0, INT32_MAX));
    c.flavour = static_cast<filmgrain::FgcFlavour>(o.flavour);
    c.persistence = static_cast<filmgrain::FgcPersistence>(o.persistence);
    c.passthrough_invalid = o.passthrough_invalid != 0;
    c.threads = o.threads;
    c.coded_width = o.coded_width;
    c.coded_height = o.coded_height;
    if (o.vfgs_has_seed) c.vfgs_seed = o.vfgs_seed;
    c.vfgs_gain_percent = o.vfgs_gain_percent;
    c.block_size = o.block_size;
    c.single_line_blocks = o.single_line_blocks;
    c.pattern_interpolation = o.pattern_interpolation != 0;
    c.vfgs_output_bit_depth = o.vfgs_output_bit_depth;
    c.clip_to_restricted_range = o.clip_to_restricted_range;
    return c;  // the rest (ranges, combinations) is checked by the Session, naming the field
}

filmgrain::FgcCodec to_codec(int codec) {
    if (codec < FG_CODEC_AVC || codec > FG_CODEC_VVC) invalid(filmgrain::out_of_range_message("codec", codec, 0, 2));
    return static_cast<filmgrain::FgcCodec>(codec);
}

std::optional<filmgrain::FgcPictureIds> to_ids(const fg_picture_ids* p) {
    if (!p) return std::nullopt;
    filmgrain::FgcPictureIds ids;
    ids.poc = p->poc;
    ids.idr_pic_id = p->idr_pic_id;
    return ids;
}

// Every field of fg_av1_params and its Av1FilmGrainParams namesake, for either direction:
// `f(x, y)` is called with the two members (arrays as arrays).
template <typename A, typename B, typename F>
void for_each_av1_field(A& a, B& b, F&& f) {
    f(a.apply_grain, b.apply_grain);
    f(a.grain_seed, b.grain_seed);
    f(a.update_grain, b.update_grain);
    f(a.film_grain_params_ref_idx, b.film_grain_params_ref_idx);
    f(a.num_y_points, b.num_y_points);
    f(a.point_y_value, b.point_y_value);
    f(a.point_y_scaling, b.point_y_scaling);
    f(a.chroma_scaling_from_luma, b.chroma_scaling_from_luma);
    f(a.num_cb_points, b.num_cb_points);
    f(a.point_cb_value, b.point_cb_value);
    f(a.point_cb_scaling, b.point_cb_scaling);
    f(a.num_cr_points, b.num_cr_points);
    f(a.point_cr_value, b.point_cr_value);
    f(a.point_cr_scaling, b.point_cr_scaling);
    f(a.grain_scaling_minus_8, b.grain_scaling_minus_8);
    f(a.ar_coeff_lag, b.ar_coeff_lag);
    f(a.ar_coeffs_y_plus_128, b.ar_coeffs_y_plus_128);
    f(a.ar_coeffs_cb_plus_128, b.ar_coeffs_cb_plus_128);
    f(a.ar_coeffs_cr_plus_128, b.ar_coeffs_cr_plus_128);
    f(a.ar_coeff_shift_minus_6, b.ar_coeff_shift_minus_6);
    f(a.grain_scale_shift, b.grain_scale_shift);
    f(a.cb_mult, b.cb_mult);
    f(a.cb_luma_mult, b.cb_luma_mult);
    f(a.cb_offset, b.cb_offset);
    f(a.cr_mult, b.cr_mult);
    f(a.cr_luma_mult, b.cr_luma_mult);
    f(a.cr_offset, b.cr_offset);
    f(a.overlap_flag, b.overlap_flag);
    f(a.clip_to_restricted_range, b.clip_to_restricted_range);
}

// Assigns `from` to `to`, element by element for arrays (C arrays and std::array alike).
struct AssignField {
    template <typename To, typename From>
    void operator()(To& to, const From& from) const {
        if constexpr (std::is_arithmetic_v<To>) {
            to = from;
        } else {
            for (std::size_t i = 0; i < std::size(from); i++) to[i] = from[i];
        }
    }
};

filmgrain::Av1FilmGrainParams to_av1(const fg_av1_params& c) {
    filmgrain::Av1FilmGrainParams p;
    for_each_av1_field(p, c, AssignField{});
    return p;
}

filmgrain::FrameView to_view(const fg_frame* f, const char* name) {
    using filmgrain::ChromaFormat;
    const std::string n(name);
    if (!f) invalid(n + " is NULL");
    if (f->chroma_format < FG_CHROMA_400 || f->chroma_format > FG_CHROMA_444)
        invalid(filmgrain::out_of_range_message(n + ".chroma_format", f->chroma_format, 0, 3));
    if (f->width <= 0 || f->height <= 0)
        invalid(n + ".width x height = " + std::to_string(f->width) + "x" + std::to_string(f->height) +
                " must be positive");
    if (f->bit_depth < 8 || f->bit_depth > 16)
        invalid(filmgrain::out_of_range_message(n + ".bit_depth", f->bit_depth, 8, 16));
    filmgrain::FrameView v;
    v.format = static_cast<ChromaFormat>(f->chroma_format);
    v.bit_depth = f->bit_depth;
    v.width = f->width;
    v.height = f->height;
    for (int p = 0; p < v.plane_count(); p++) {
        const std::string pn = n + ".planes[" + std::to_string(p) + "]";
        if (!f->planes[p]) invalid(pn + " is NULL");
        v.planes[p].data = static_cast<uint8_t*>(f->planes[p]);
        v.planes[p].stride = f->strides[p];
        v.planes[p].width = filmgrain::plane_width(v.format, p, v.width);
        v.planes[p].height = filmgrain::plane_height(v.format, p, v.height);
    }
    // strides and alignment: the session checks them (check_plane_layout), naming `n`
    return v;
}

// A caller-filled struct of this library's version: every field 0, struct_size set.
template <typename T>
T zeroed_struct() {
    T t;
    std::memset(&t, 0, sizeof t);
    t.struct_size = sizeof t;
    return t;
}

fg_options default_options() {
    fg_options o = zeroed_struct<fg_options>();
    o.flavour = FG_FLAVOUR_RDD5;
    o.persistence = FG_PERSISTENCE_REFERENCE;
    o.vfgs_gain_percent = 100;
    o.clip_to_restricted_range = -1;
    return o;
}

fg_frame_info default_frame_info() {
    fg_frame_info i = zeroed_struct<fg_frame_info>();
    return i;
}

fg_av1_params default_av1_params() {
    fg_av1_params c = zeroed_struct<fg_av1_params>();
    const filmgrain::Av1FilmGrainParams d;
    c.update_grain = d.update_grain;
    for (int& v : c.ar_coeffs_y_plus_128) v = 128;
    for (int& v : c.ar_coeffs_cb_plus_128) v = 128;
    for (int& v : c.ar_coeffs_cr_plus_128) v = 128;
    c.cb_mult = d.cb_mult;
    c.cb_luma_mult = d.cb_luma_mult;
    c.cb_offset = d.cb_offset;
    c.cr_mult = d.cr_mult;
    c.cr_luma_mult = d.cr_luma_mult;
    c.cr_offset = d.cr_offset;
    c.matrix_coefficients = 2;
    return c;
}

// Version 1.0 sizes: the oldest layouts the library still reads.
// 1.0 ended at vfgs_gain_percent; 2.0 added the fields from block_size on.
constexpr std::size_t kOptionsV1Size = offsetof(fg_options, block_size);
constexpr std::size_t kFrameInfoV1Size = sizeof(fg_frame_info);
constexpr std::size_t kAv1ParamsV1Size = sizeof(fg_av1_params);

const char* const kNullContext = "fg_context is NULL";

// A failure's message into a caller's buffer (NUL-terminated, truncated), for the functions
// that have no context to keep it in.
void copy_message(const std::string& error, char* message, size_t message_size) {
    if (!message || !message_size) return;
    const std::size_t n = std::min(error.size(), message_size - 1);
    std::memcpy(message, error.data(), n);
    message[n] = '\0';
}

[[noreturn]] void invalid_params(const std::string& message) { throw Error(ErrorCode::kInvalidParams, message); }

void check_in(const char* field, long long v, long long lo, long long hi) {
    if (v < lo || v > hi) invalid_params(filmgrain::out_of_range_message(field, v, lo, hi));
}

// fg_fgc_params -> FgcParams: the counts are checked before the arrays are read, then every
// value against its syntax range (the same check every other path to synthesis makes).
filmgrain::FgcParams to_fgc(const fg_fgc_params& c) {
    filmgrain::FgcParams p;
    p.film_grain_characteristics_cancel_flag = c.cancel_flag != 0;
    p.film_grain_model_id = c.model_id;
    p.separate_colour_description_present_flag = c.separate_colour_description_present_flag != 0;
    p.film_grain_bit_depth_luma_minus8 = c.bit_depth_luma_minus8;
    p.film_grain_bit_depth_chroma_minus8 = c.bit_depth_chroma_minus8;
    p.film_grain_full_range_flag = c.full_range_flag != 0;
    p.film_grain_colour_primaries = c.colour_primaries;
    p.film_grain_transfer_characteristics = c.transfer_characteristics;
    p.film_grain_matrix_coeffs = c.matrix_coeffs;
    p.blending_mode_id = c.blending_mode_id;
    p.log2_scale_factor = c.log2_scale_factor;
    p.film_grain_characteristics_persistence_flag = c.persistence_flag != 0;
    p.film_grain_characteristics_repetition_period = c.repetition_period;
    for (int k = 0; k < 3; k++) {
        if (!c.comp_model_present_flag[k]) continue;
        const std::string idx = filmgrain::indexed("", k);
        check_in(("num_intensity_intervals_minus1" + idx).c_str(), c.num_intensity_intervals_minus1[k], 0, 255);
        check_in(("num_model_values_minus1" + idx).c_str(), c.num_model_values_minus1[k], 0, 5);
        filmgrain::FgcComponentModel& m = p.comp[std::size_t(k)];
        m.comp_model_present_flag = true;
        m.num_model_values_minus1 = c.num_model_values_minus1[k];
        m.intervals.resize(std::size_t(c.num_intensity_intervals_minus1[k]) + 1);
        for (std::size_t i = 0; i < m.intervals.size(); i++) {
            m.intervals[i].intensity_interval_lower_bound = c.intensity_interval_lower_bound[k][i];
            m.intervals[i].intensity_interval_upper_bound = c.intensity_interval_upper_bound[k][i];
            for (int j = 0; j <= m.num_model_values_minus1; j++)
                m.intervals[i].comp_model_value[std::size_t(j)] = c.comp_model_value[k][i][j];
        }
    }
    filmgrain::fgc::check_fgc_syntax_ranges(p);
    return p;
}

fg_fgc_params default_fgc_params() {
    fg_fgc_params c = zeroed_struct<fg_fgc_params>();
    const filmgrain::FgcParams d;
    c.colour_primaries = d.film_grain_colour_primaries;
    c.transfer_characteristics = d.film_grain_transfer_characteristics;
    c.matrix_coeffs = d.film_grain_matrix_coeffs;
    c.persistence_flag = d.film_grain_characteristics_persistence_flag;
    c.repetition_period = d.film_grain_characteristics_repetition_period;
    return c;
}

fg_fgc_params from_fgc(const filmgrain::FgcParams& p) {
    fg_fgc_params c = default_fgc_params();
    c.cancel_flag = p.film_grain_characteristics_cancel_flag;
    c.model_id = p.film_grain_model_id;
    c.separate_colour_description_present_flag = p.separate_colour_description_present_flag;
    c.bit_depth_luma_minus8 = p.film_grain_bit_depth_luma_minus8;
    c.bit_depth_chroma_minus8 = p.film_grain_bit_depth_chroma_minus8;
    c.full_range_flag = p.film_grain_full_range_flag;
    c.colour_primaries = p.film_grain_colour_primaries;
    c.transfer_characteristics = p.film_grain_transfer_characteristics;
    c.matrix_coeffs = p.film_grain_matrix_coeffs;
    c.blending_mode_id = p.blending_mode_id;
    c.log2_scale_factor = p.log2_scale_factor;
    c.persistence_flag = p.film_grain_characteristics_persistence_flag;
    c.repetition_period = p.film_grain_characteristics_repetition_period;
    for (int k = 0; k < 3; k++) {
        const filmgrain::FgcComponentModel& m = p.comp[std::size_t(k)];
        c.comp_model_present_flag[k] = m.comp_model_present_flag;
        if (!m.comp_model_present_flag) continue;
        c.num_intensity_intervals_minus1[k] = int(m.intervals.size()) - 1;  // a parsed set has 1..256
        c.num_model_values_minus1[k] = m.num_model_values_minus1;
        for (std::size_t i = 0; i < m.intervals.size() && i < 256; i++) {
            c.intensity_interval_lower_bound[k][i] = uint8_t(m.intervals[i].intensity_interval_lower_bound);
            c.intensity_interval_upper_bound[k][i] = uint8_t(m.intervals[i].intensity_interval_upper_bound);
            for (int j = 0; j < 6; j++) c.comp_model_value[k][i][j] = m.intervals[i].comp_model_value[std::size_t(j)];
        }
    }
    return c;
}

fg_av1_grain default_av1_grain() {
    fg_av1_grain g = zeroed_struct<fg_av1_grain>();
    g.scaling_shift = 8;
    g.ar_coeff_shift = 6;
    g.matrix_coefficients = 2;
    return g;
}

// The de-biased form (dav1d's) -> the bitstream form; each value against what its field carries.
filmgrain::Av1FilmGrainParams from_av1_grain(const fg_av1_grain& g) {
    filmgrain::Av1FilmGrainParams p;
    check_in("apply_grain", g.apply_grain, 0, 1);
    check_in("seed", g.seed, 0, 65535);
    check_in("num_y_points", g.num_y_points, 0, 14);
    check_in("num_uv_points[0]", g.num_uv_points[0], 0, 10);
    check_in("num_uv_points[1]", g.num_uv_points[1], 0, 10);
    check_in("chroma_scaling_from_luma", g.chroma_scaling_from_luma, 0, 1);
    check_in("scaling_shift", g.scaling_shift, 8, 11);
    check_in("ar_coeff_lag", g.ar_coeff_lag, 0, 3);
    check_in("ar_coeff_shift", g.ar_coeff_shift, 6, 9);
    check_in("grain_scale_shift", g.grain_scale_shift, 0, 3);
    check_in("overlap_flag", g.overlap_flag, 0, 1);
    check_in("clip_to_restricted_range", g.clip_to_restricted_range, 0, 1);
    p.apply_grain = g.apply_grain;
    p.update_grain = 1;
    p.grain_seed = int(g.seed);
    p.num_y_points = g.num_y_points;
    for (int i = 0; i < 14; i++) {
        p.point_y_value[std::size_t(i)] = g.y_points[i][0];
        p.point_y_scaling[std::size_t(i)] = g.y_points[i][1];
    }
    p.chroma_scaling_from_luma = g.chroma_scaling_from_luma;
    p.num_cb_points = g.num_uv_points[0];
    p.num_cr_points = g.num_uv_points[1];
    for (int i = 0; i < 10; i++) {
        p.point_cb_value[std::size_t(i)] = g.uv_points[0][i][0];
        p.point_cb_scaling[std::size_t(i)] = g.uv_points[0][i][1];
        p.point_cr_value[std::size_t(i)] = g.uv_points[1][i][0];
        p.point_cr_scaling[std::size_t(i)] = g.uv_points[1][i][1];
    }
    p.grain_scaling_minus_8 = g.scaling_shift - 8;
    p.ar_coeff_lag = g.ar_coeff_lag;
    for (int i = 0; i < 24; i++) {
        check_in(("ar_coeffs_y[" + std::to_string(i) + "]").c_str(), g.ar_coeffs_y[i], -128, 127);
        p.ar_coeffs_y_plus_128[std::size_t(i)] = g.ar_coeffs_y[i] + 128;
    }
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 25; i++) {
            check_in(("ar_coeffs_uv[" + std::to_string(k) + "][" + std::to_string(i) + "]").c_str(), g.ar_coeffs_uv[k][i],
                     -128, 127);
            (k ? p.ar_coeffs_cr_plus_128 : p.ar_coeffs_cb_plus_128)[std::size_t(i)] = g.ar_coeffs_uv[k][i] + 128;
        }
    p.ar_coeff_shift_minus_6 = g.ar_coeff_shift - 6;
    p.grain_scale_shift = g.grain_scale_shift;
    for (int k = 0; k < 2; k++) {
        const std::string idx = filmgrain::indexed("", k);
        check_in(("uv_mult" + idx).c_str(), g.uv_mult[k], -128, 127);
        check_in(("uv_luma_mult" + idx).c_str(), g.uv_luma_mult[k], -128, 127);
        check_in(("uv_offset" + idx).c_str(), g.uv_offset[k], -256, 255);
    }
    p.cb_mult = g.uv_mult[0] + 128;
    p.cb_luma_mult = g.uv_luma_mult[0] + 128;
    p.cb_offset = g.uv_offset[0] + 256;
    p.cr_mult = g.uv_mult[1] + 128;
    p.cr_luma_mult = g.uv_luma_mult[1] + 128;
    p.cr_offset = g.uv_offset[1] + 256;
    p.overlap_flag = g.overlap_flag;
    p.clip_to_restricted_range = g.clip_to_restricted_range;
    return p;
}

fg_av1_grain to_av1_grain(const filmgrain::Av1FilmGrainParams& p, int matrix_coefficients) {
    fg_av1_grain g = default_av1_grain();
    g.apply_grain = p.apply_grain;
    g.seed = unsigned(p.grain_seed);
    g.num_y_points = p.num_y_points;
    for (int i = 0; i < 14; i++) {
        g.y_points[i][0] = uint8_t(p.point_y_value[std::size_t(i)]);
        g.y_points[i][1] = uint8_t(p.point_y_scaling[std::size_t(i)]);
    }
    g.chroma_scaling_from_luma = p.chroma_scaling_from_luma;
    g.num_uv_points[0] = p.num_cb_points;
    g.num_uv_points[1] = p.num_cr_points;
    for (int i = 0; i < 10; i++) {
        g.uv_points[0][i][0] = uint8_t(p.point_cb_value[std::size_t(i)]);
        g.uv_points[0][i][1] = uint8_t(p.point_cb_scaling[std::size_t(i)]);
        g.uv_points[1][i][0] = uint8_t(p.point_cr_value[std::size_t(i)]);
        g.uv_points[1][i][1] = uint8_t(p.point_cr_scaling[std::size_t(i)]);
    }
    g.scaling_shift = p.grain_scaling_minus_8 + 8;
    g.ar_coeff_lag = p.ar_coeff_lag;
    for (int i = 0; i < 24; i++) g.ar_coeffs_y[i] = p.ar_coeffs_y_plus_128[std::size_t(i)] - 128;
    for (int i = 0; i < 25; i++) {
        g.ar_coeffs_uv[0][i] = p.ar_coeffs_cb_plus_128[std::size_t(i)] - 128;
        g.ar_coeffs_uv[1][i] = p.ar_coeffs_cr_plus_128[std::size_t(i)] - 128;
    }
    g.ar_coeff_shift = p.ar_coeff_shift_minus_6 + 6;
    g.grain_scale_shift = p.grain_scale_shift;
    g.uv_mult[0] = p.cb_mult - 128;
    g.uv_luma_mult[0] = p.cb_luma_mult - 128;
    g.uv_offset[0] = p.cb_offset - 256;
    g.uv_mult[1] = p.cr_mult - 128;
    g.uv_luma_mult[1] = p.cr_luma_mult - 128;
    g.uv_offset[1] = p.cr_offset - 256;
    g.overlap_flag = p.overlap_flag;
    g.clip_to_restricted_range = p.clip_to_restricted_range;
    g.matrix_coefficients = matrix_coefficients;
    return g;
}

}  // namespace

extern "C" {

unsigned fg_version(void) { return FG_VERSION; }

const char* fg_version_string(void) { return "2.0.0"; }

const char* fg_status_name(int status) {
    switch (status) {
    case FG_OK: return "FG_OK";
    case FG_ERROR_INVALID_ARGUMENT: return "FG_ERROR_INVALID_ARGUMENT";
    case FG_ERROR_INVALID_PARAMS: return "FG_ERROR_INVALID_PARAMS";
    case FG_ERROR_MALFORMED_PAYLOAD: return "FG_ERROR_MALFORMED_PAYLOAD";
    case FG_ERROR_UNSUPPORTED: return "FG_ERROR_UNSUPPORTED";
    case FG_ERROR_IO: return "FG_ERROR_IO";
    case FG_ERROR_OUT_OF_MEMORY: return "FG_ERROR_OUT_OF_MEMORY";
    case FG_ERROR_INTERNAL: return "FG_ERROR_INTERNAL";
    }
    return "unknown fg_status";
}

void fg_options_init(fg_options* options) {
    if (options) *options = default_options();
}

void fg_frame_info_init(fg_frame_info* info) {
    if (info) *info = default_frame_info();
}

void fg_av1_params_init(fg_av1_params* params) {
    if (params) *params = default_av1_params();
}

fg_status fg_context_create(const fg_options* options, fg_context** out, char* message, size_t message_size) {
    std::string error;
    fg_context* created = nullptr;
    const fg_status st = guarded(error, [&] {
        if (!out) invalid("fg_context_create: out is NULL");
        *out = nullptr;
        const fg_options o = options ? sized_copy(options, kOptionsV1Size, default_options(), "options")
                                     : default_options();
        created = new fg_context(to_options(o));
    });
    if (st == FG_OK) *out = created;
    if (message && message_size) {
        const std::size_t n = std::min(error.size(), message_size - 1);
        std::memcpy(message, error.data(), n);
        message[n] = '\0';
    }
    return st;
}

void fg_context_destroy(fg_context* ctx) { delete ctx; }

const char* fg_last_error(const fg_context* ctx) { return ctx ? ctx->last_error.c_str() : kNullContext; }

fg_status fg_context_push_fgc_sei(fg_context* ctx, const uint8_t* payload, size_t size, int codec,
                                  const fg_picture_ids* picture) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!payload) invalid("payload is NULL");
        ctx->grain.receive_fgc_sei_payload(payload, size, to_codec(codec), to_ids(picture));
    });
}

fg_status fg_context_push_av1_params(fg_context* ctx, const fg_av1_params* params, unsigned refresh_frame_flags) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!params) invalid("params is NULL");
        const fg_av1_params c = sized_copy(params, kAv1ParamsV1Size, default_av1_params(), "params");
        ctx->grain.receive_av1_params(to_av1(c), refresh_frame_flags, c.matrix_coefficients);
    });
}

fg_status fg_context_show_existing_av1_frame(fg_context* ctx, int frame_to_show_map_idx) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] { ctx->grain.show_existing_av1_frame(frame_to_show_map_idx); });
}

fg_status fg_context_push_afgs1_t35(fg_context* ctx, const uint8_t* payload, size_t size) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!payload) invalid("payload is NULL");
        ctx->grain.receive_afgs1_t35(payload, size);
    });
}

fg_status fg_context_reset(fg_context* ctx) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] { ctx->grain.reset(); });
}

fg_status fg_context_apply(fg_context* ctx, const fg_frame* src, const fg_frame* dst, fg_frame_info* info) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        const filmgrain::FrameView in = to_view(src, "src");
        const filmgrain::FrameView out = dst ? to_view(dst, "dst") : in;
        filmgrain::FrameInfo fi;
        if (info) {
            const fg_frame_info i = sized_copy(info, kFrameInfoV1Size, default_frame_info(), "info");
            fi.ids.poc = i.ids.poc;
            fi.ids.idr_pic_id = i.ids.idr_pic_id;
            if (i.has_seed) fi.seed = i.seed;
            info->grain_applied = 0;
        }
        const filmgrain::ApplyResult r = ctx->grain.apply(in, out, info ? &fi : nullptr);
        if (info) info->grain_applied = r.grain_applied ? 1 : 0;
        ctx->last_error = r.message;
    });
}

}  // extern "C"

void fg_fgc_params_init(fg_fgc_params* params) {
    if (params) *params = default_fgc_params();
}

fg_status fg_fgc_params_from_sei(const uint8_t* payload, size_t size, int codec, fg_fgc_params* out, char* message,
                                 size_t message_size) {
    std::string error;
    const fg_status st = guarded(error, [&] {
        if (!out) invalid("out is NULL");
        if (!payload && size) invalid("payload is NULL with size " + std::to_string(size));
        *out = from_fgc(filmgrain::parse_fgc_sei_payload(payload, size, to_codec(codec)));
    });
    copy_message(error, message, message_size);
    return st;
}

fg_status fg_fgc_params_to_sei(const fg_fgc_params* params, int codec, uint8_t* out, size_t capacity, size_t* size,
                               char* message, size_t message_size) {
    std::string error;
    const fg_status st = guarded(error, [&] {
        if (!params || !size) invalid(!params ? "params is NULL" : "size is NULL");
        const fg_fgc_params c = sized_copy(params, sizeof(fg_fgc_params), default_fgc_params(), "params");
        const std::vector<uint8_t> bytes = filmgrain::write_fgc_sei_payload(to_fgc(c), to_codec(codec));
        *size = bytes.size();
        if (capacity < bytes.size() || (!out && !bytes.empty()))
            invalid("capacity = " + std::to_string(capacity) + " is smaller than the payload (" +
                    std::to_string(bytes.size()) + " bytes)");
        std::memcpy(out, bytes.data(), bytes.size());
    });
    copy_message(error, message, message_size);
    return st;
}

fg_status fg_context_push_fgc_params(fg_context* ctx, const fg_fgc_params* params, int codec,
                                     const fg_picture_ids* picture) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!params) invalid("params is NULL");
        const fg_fgc_params c = sized_copy(params, sizeof(fg_fgc_params), default_fgc_params(), "params");
        ctx->grain.receive_fgc_params(to_fgc(c), to_codec(codec), to_ids(picture));
    });
}

void fg_av1_grain_init(fg_av1_grain* grain) {
    if (grain) *grain = default_av1_grain();
}

fg_status fg_av1_grain_from_params(const fg_av1_params* params, fg_av1_grain* out, char* message, size_t message_size) {
    std::string error;
    const fg_status st = guarded(error, [&] {
        if (!params || !out) invalid(!params ? "params is NULL" : "out is NULL");
        const fg_av1_params c = sized_copy(params, kAv1ParamsV1Size, default_av1_params(), "params");
        const filmgrain::Av1FilmGrainParams p = to_av1(c);
        if (p.apply_grain && !p.update_grain)
            invalid_params("update_grain = 0: the set is in reference slot film_grain_params_ref_idx = " +
                           std::to_string(p.film_grain_params_ref_idx) + ", not in these values (allowed: 1)");
        // every value through the de-biased form's checks
        const fg_av1_grain g = to_av1_grain(p, c.matrix_coefficients);
        (void)from_av1_grain(g);
        *out = g;
    });
    copy_message(error, message, message_size);
    return st;
}

fg_status fg_av1_grain_to_params(const fg_av1_grain* grain, fg_av1_params* out, char* message, size_t message_size) {
    std::string error;
    const fg_status st = guarded(error, [&] {
        if (!grain || !out) invalid(!grain ? "grain is NULL" : "out is NULL");
        const fg_av1_grain g = sized_copy(grain, sizeof(fg_av1_grain), default_av1_grain(), "grain");
        const filmgrain::Av1FilmGrainParams p = from_av1_grain(g);
        fg_av1_params c = default_av1_params();
        for_each_av1_field(c, p, AssignField{});
        c.matrix_coefficients = g.matrix_coefficients;
        *out = c;
    });
    copy_message(error, message, message_size);
    return st;
}

fg_status fg_context_push_av1_grain(fg_context* ctx, const fg_av1_grain* grain) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!grain) invalid("grain is NULL");
        const fg_av1_grain g = sized_copy(grain, sizeof(fg_av1_grain), default_av1_grain(), "grain");
        ctx->grain.receive_av1_params(from_av1_grain(g), 0, g.matrix_coefficients);
    });
}

// ---- stream scanning ------------------------------------------------------------------

struct fg_stream_scan {
    struct Unit {
        fg_stream_unit info{};
        std::vector<std::vector<uint8_t>> fgc;
        std::vector<std::vector<uint8_t>> t35;
        std::vector<uint8_t> afgs1;  // resolved in decode order; empty: none
        fg_av1_grain av1_grain{};
        std::vector<std::string> warnings;
    };
    std::vector<Unit> units;  // output order
    std::vector<std::string> warnings;
    // Why the last call on this scan failed: the scan is read-only to its callers, its
    // error is not.
    mutable std::string last_error;
};

namespace {

const char* const kNullScan = "fg_stream_scan is NULL";

filmgrain::bitstream::StreamCodec to_stream_codec(int codec) {
    switch (codec) {
    case FG_STREAM_H264: return filmgrain::bitstream::StreamCodec::kH264;
    case FG_STREAM_H265: return filmgrain::bitstream::StreamCodec::kH265;
    case FG_STREAM_H266: return filmgrain::bitstream::StreamCodec::kH266;
    case FG_STREAM_AV1: return filmgrain::bitstream::StreamCodec::kAv1;
    }
    invalid(filmgrain::out_of_range_message("codec", codec, FG_STREAM_H264, FG_STREAM_AV1) +
            " (fg_stream_codec: 0 H.264, 1 H.265, 2 H.266, 3 AV1)");
}

const fg_stream_scan::Unit& scan_unit(const fg_stream_scan* scan, int unit) {
    if (!scan) invalid(kNullScan);
    if (scan->units.empty()) invalid("unit = " + std::to_string(unit) + ": the stream has no units");
    if (unit < 0 || std::size_t(unit) >= scan->units.size())
        invalid(filmgrain::out_of_range_message("unit", unit, 0, (long long)scan->units.size() - 1));
    return scan->units[std::size_t(unit)];
}

// Runs `body` for a call on `scan`, its failure's message kept in the scan (if there is one).
template <typename Body>
fg_status guarded_scan(const fg_stream_scan* scan, Body&& body) noexcept {
    std::string none;
    return guarded(scan ? scan->last_error : none, std::forward<Body>(body));
}

void payload_out(const std::vector<std::vector<uint8_t>>& list, int j, const char* what, const uint8_t** data,
                 size_t* size) {
    if (!data || !size) invalid(!data ? "data is NULL" : "size is NULL");
    if (list.empty()) invalid(std::string(what) + " = " + std::to_string(j) + ": the unit has none");
    if (j < 0 || std::size_t(j) >= list.size())
        invalid(filmgrain::out_of_range_message(what, j, 0, (long long)list.size() - 1));
    *data = list[std::size_t(j)].data();
    *size = list[std::size_t(j)].size();
}

}  // namespace

fg_status fg_stream_scan_create(const uint8_t* data, size_t size, int codec, fg_stream_scan** out, char* message,
                                size_t message_size) {
    std::string error;
    if (out) *out = nullptr;
    const fg_status st = guarded(error, [&] {
        if (!out) invalid("out is NULL");
        if (!data && size) invalid("data is NULL with size " + std::to_string(size));
        namespace bs = filmgrain::bitstream;
        const bs::StreamScan found = bs::scan_stream(data, size, to_stream_codec(codec));
        auto scan = std::make_unique<fg_stream_scan>();
        scan->warnings = found.warnings;
        // The AV1 colour description a unit's grain is synthesized with: the sequence
        // header in force at that unit (decode order).
        std::vector<int> matrix(found.units.size(), 2);
        int current_matrix = 2;
        // AFGS1 payloads resolved in decode order, written with every set explicit.
        const auto reads = bs::read_afgs1_in_decode_order(found);
        std::vector<std::vector<uint8_t>> afgs1(found.units.size());
        std::vector<std::vector<std::string>> afgs1_warnings(found.units.size());
        for (std::size_t k = 0; k < found.units.size(); k++) {
            if (found.units[k].av1_sequence_header)
                current_matrix = found.units[k].av1_sequence_header->matrix_coefficients;
            matrix[k] = current_matrix;
            for (const bs::Afgs1Read& read : reads[k]) {
                if (const auto* p = std::get_if<filmgrain::Afgs1Payload>(&read))
                    afgs1[k] = filmgrain::write_afgs1_resolved(*p);
                if (const auto* why = std::get_if<std::string>(&read))
                    afgs1_warnings[k].push_back("AFGS1 payload skipped: " + *why);
            }
        }
        for (const bs::AccessUnit* au : bs::units_in_output_order(found)) {
            fg_stream_scan::Unit u;
            u.info.decode_index = au->index;
            u.info.offset = au->offset;
            u.info.has_poc = au->poc.has_value();
            u.info.poc = au->poc.value_or(0);
            u.info.idr_pic_id = au->idr_pic_id.value_or(0);
            u.info.sequence = au->sequence;
            u.info.output = au->output;
            for (const bs::FoundFgc& f : au->fgc) u.fgc.push_back(f.payload);
            for (const bs::FoundT35& t : au->t35) u.t35.push_back(bs::t35_bytes(t.t35));
            u.afgs1 = afgs1[std::size_t(au->index)];
            if (au->av1_frame_grain) {
                u.info.has_av1_grain = 1;
                u.av1_grain = to_av1_grain(*au->av1_frame_grain, matrix[std::size_t(au->index)]);
            } else {
                u.av1_grain = default_av1_grain();
            }
            u.warnings = au->warnings;
            const auto& skipped = afgs1_warnings[std::size_t(au->index)];
            u.warnings.insert(u.warnings.end(), skipped.begin(), skipped.end());
            u.info.fgc_count = int(u.fgc.size());
            u.info.t35_count = int(u.t35.size());
            u.info.warning_count = int(u.warnings.size());
            scan->units.push_back(std::move(u));
        }
        *out = scan.release();
    });
    copy_message(error, message, message_size);
    return st;
}

void fg_stream_scan_destroy(fg_stream_scan* scan) { delete scan; }

int fg_stream_scan_unit_count(const fg_stream_scan* scan) { return scan ? int(scan->units.size()) : 0; }

int fg_stream_scan_stream_warning_count(const fg_stream_scan* scan) { return scan ? int(scan->warnings.size()) : 0; }

const char* fg_stream_scan_last_error(const fg_stream_scan* scan) {
    return scan ? scan->last_error.c_str() : kNullScan;
}

fg_status fg_stream_scan_unit(const fg_stream_scan* scan, int unit, fg_stream_unit* out) {
    return guarded_scan(scan, [&] {
        const fg_stream_scan::Unit& u = scan_unit(scan, unit);
        if (!out) invalid("out is NULL");
        *out = u.info;
    });
}

fg_status fg_stream_scan_fgc_payload(const fg_stream_scan* scan, int unit, int j, const uint8_t** data, size_t* size) {
    return guarded_scan(scan, [&] { payload_out(scan_unit(scan, unit).fgc, j, "j (FGC SEI payload)", data, size); });
}

fg_status fg_stream_scan_t35_payload(const fg_stream_scan* scan, int unit, int j, const uint8_t** data, size_t* size) {
    return guarded_scan(scan, [&] { payload_out(scan_unit(scan, unit).t35, j, "j (T.35 payload)", data, size); });
}

fg_status fg_stream_scan_afgs1_payload(const fg_stream_scan* scan, int unit, const uint8_t** data, size_t* size) {
    return guarded_scan(scan, [&] {
        const fg_stream_scan::Unit& u = scan_unit(scan, unit);
        if (!data || !size) invalid(!data ? "data is NULL" : "size is NULL");
        *data = u.afgs1.empty() ? nullptr : u.afgs1.data();
        *size = u.afgs1.size();
    });
}

fg_status fg_stream_scan_av1_grain(const fg_stream_scan* scan, int unit, fg_av1_grain* out) {
    return guarded_scan(scan, [&] {
        const fg_stream_scan::Unit& u = scan_unit(scan, unit);
        if (!out) invalid("out is NULL");
        if (!u.info.has_av1_grain) invalid("unit " + std::to_string(unit) + " has no AV1 frame-header film grain");
        *out = u.av1_grain;
    });
}

const char* fg_stream_scan_warning(const fg_stream_scan* scan, int unit, int j) {
    if (!scan || j < 0) return nullptr;
    const std::vector<std::string>* list = &scan->warnings;
    if (unit >= 0) {
        if (std::size_t(unit) >= scan->units.size()) return nullptr;
        list = &scan->units[std::size_t(unit)].warnings;
    } else if (unit != -1) {
        return nullptr;
    }
    return std::size_t(j) < list->size() ? (*list)[std::size_t(j)].c_str() : nullptr;
}

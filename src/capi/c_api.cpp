// The C API (include/filmgrain/filmgrain.h) over GrainContext: argument checks that C
// needs (NULL pointers, struct sizes, enum ranges), conversion of the C structs to the
// C++ value types, and every exception turned into a status plus a message.
#include "filmgrain/filmgrain.h"

#include <cstring>
#include <new>
#include <string>

#include "core/thread_pool.hpp"
#include "fgc/plane_layout.hpp"
#include "filmgrain/filmgrain.hpp"

struct fg_context {
    filmgrain::GrainContext grain;
    std::string last_error;

    explicit fg_context(const filmgrain::ContextOptions& o) : grain(o) {}
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

filmgrain::ContextOptions to_options(const fg_options& o) {
    filmgrain::ContextOptions c;
    if (o.flavour < FG_FLAVOUR_RDD5 || o.flavour > FG_FLAVOUR_VFGS)
        invalid(filmgrain::out_of_range_message("options.flavour", o.flavour, 0, 2));
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
    return c;
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

template <std::size_t N>
void copy_points(std::array<int, N>& to, const int (&from)[N]) {
    for (std::size_t i = 0; i < N; i++) to[i] = from[i];
}

filmgrain::Av1FilmGrainParams to_av1(const fg_av1_params& c) {
    filmgrain::Av1FilmGrainParams p;
    p.apply_grain = c.apply_grain;
    p.grain_seed = c.grain_seed;
    p.update_grain = c.update_grain;
    p.film_grain_params_ref_idx = c.film_grain_params_ref_idx;
    p.num_y_points = c.num_y_points;
    copy_points(p.point_y_value, c.point_y_value);
    copy_points(p.point_y_scaling, c.point_y_scaling);
    p.chroma_scaling_from_luma = c.chroma_scaling_from_luma;
    p.num_cb_points = c.num_cb_points;
    copy_points(p.point_cb_value, c.point_cb_value);
    copy_points(p.point_cb_scaling, c.point_cb_scaling);
    p.num_cr_points = c.num_cr_points;
    copy_points(p.point_cr_value, c.point_cr_value);
    copy_points(p.point_cr_scaling, c.point_cr_scaling);
    p.grain_scaling_minus_8 = c.grain_scaling_minus_8;
    p.ar_coeff_lag = c.ar_coeff_lag;
    copy_points(p.ar_coeffs_y_plus_128, c.ar_coeffs_y_plus_128);
    copy_points(p.ar_coeffs_cb_plus_128, c.ar_coeffs_cb_plus_128);
    copy_points(p.ar_coeffs_cr_plus_128, c.ar_coeffs_cr_plus_128);
    p.ar_coeff_shift_minus_6 = c.ar_coeff_shift_minus_6;
    p.grain_scale_shift = c.grain_scale_shift;
    p.cb_mult = c.cb_mult;
    p.cb_luma_mult = c.cb_luma_mult;
    p.cb_offset = c.cb_offset;
    p.cr_mult = c.cr_mult;
    p.cr_luma_mult = c.cr_luma_mult;
    p.cr_offset = c.cr_offset;
    p.overlap_flag = c.overlap_flag;
    p.clip_to_restricted_range = c.clip_to_restricted_range;
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
    // strides[p]: at least a row, the plane within PTRDIFF_MAX bytes (computed without
    // negating PTRDIFF_MIN); bit_depth > 8: even planes[p] and strides[p].
    filmgrain::fgc::check_plane_layout(v, n);
    return v;
}

fg_options default_options() {
    fg_options o;
    std::memset(&o, 0, sizeof o);
    o.struct_size = sizeof o;
    o.flavour = FG_FLAVOUR_RDD5;
    o.persistence = FG_PERSISTENCE_REFERENCE;
    o.vfgs_gain_percent = 100;
    return o;
}

fg_frame_info default_frame_info() {
    fg_frame_info i;
    std::memset(&i, 0, sizeof i);
    i.struct_size = sizeof i;
    return i;
}

fg_av1_params default_av1_params() {
    fg_av1_params c;
    std::memset(&c, 0, sizeof c);
    const filmgrain::Av1FilmGrainParams d;
    c.struct_size = sizeof c;
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
constexpr std::size_t kOptionsV1Size = sizeof(fg_options);
constexpr std::size_t kFrameInfoV1Size = sizeof(fg_frame_info);
constexpr std::size_t kAv1ParamsV1Size = sizeof(fg_av1_params);

const char* const kNullContext = "fg_context is NULL";

}  // namespace

extern "C" {

unsigned fg_version(void) { return FG_VERSION; }

const char* fg_version_string(void) { return "1.0.0"; }

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

fg_status fg_context_push_json(fg_context* ctx, const char* json, size_t length, int codec,
                               const fg_picture_ids* picture) {
    if (!ctx) return FG_ERROR_INVALID_ARGUMENT;
    return guarded(ctx->last_error, [&] {
        if (!json) invalid("json is NULL");
        ctx->grain.receive_json(std::string_view(json, length), to_codec(codec), to_ids(picture));
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

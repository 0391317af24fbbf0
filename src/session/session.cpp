// Session: the per-stream state behind every entry point (include/filmgrain/session.hpp).
// It routes metadata to the model it belongs to (FgcStreamSynthesis for rdd5/vtm/tr,
// vfgs::Synthesizer, AV1 synthesis) and keeps what a decoder would otherwise have to: SEIs
// waiting for their output picture, AV1 reference slots, the AFGS1 stored parameter sets,
// the picture count for callers that pass no ids.
#include "filmgrain/session.hpp"


#include "av1/av1_picture_synthesis.hpp"
#include "session/av1_reference_slots.hpp"
#include "session/pending_sei_queue.hpp"
#include "core/thread_pool.hpp"
#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/vfgs.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_sei.hpp"

namespace filmgrain {

namespace {

void check_options(const SessionOptions& o) {
    const int flavour = static_cast<int>(o.flavour), persistence = static_cast<int>(o.persistence);
    if (flavour < 0 || flavour > 4) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("flavour", flavour, 0, 4));
    if (persistence < 0 || persistence > 1)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("persistence", persistence, 0, 1));
    if (o.threads < 0 || o.threads > kMaxThreads)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("threads", o.threads, 0, kMaxThreads));
    if (o.coded_width < 0 || o.coded_height < 0)
        throw Error(ErrorCode::kInvalidArgument,
                    out_of_range_message(o.coded_width < 0 ? "coded_width" : "coded_height",
                                         o.coded_width < 0 ? o.coded_width : o.coded_height, 0, INT32_MAX));
    if (o.vfgs_gain_percent < 0)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("vfgs_gain_percent", o.vfgs_gain_percent, 0, INT32_MAX));
    if (o.block_size != 0 && o.block_size != 8 && o.block_size != 16 && o.block_size != 32)
        throw Error(ErrorCode::kInvalidArgument,
                    "block_size = " + std::to_string(o.block_size) + " is not a block size (allowed 0, 8, 16, 32)");
    if (o.single_line_blocks != 0 && o.single_line_blocks != 8 && o.single_line_blocks != 16 &&
        o.single_line_blocks != 32)
        throw Error(ErrorCode::kInvalidArgument, "single_line_blocks = " + std::to_string(o.single_line_blocks) +
                                                     " is not a segment length (allowed 0, 8, 16, 32)");
    if (o.clip_to_restricted_range < -1 || o.clip_to_restricted_range > 1)
        throw Error(ErrorCode::kInvalidArgument,
                    out_of_range_message("clip_to_restricted_range", o.clip_to_restricted_range, -1, 1));
    const bool vfgs = o.flavour == FgcFlavour::kVfgs;
    if (vfgs && o.single_line_blocks)
        throw Error(ErrorCode::kInvalidArgument,
                    "single_line_blocks is an option of the vtm and tr flavours (VFGS adapts per sample)");
    if (!vfgs && (o.vfgs_seed || o.vfgs_gain_percent != 100 || o.vfgs_output_bit_depth || o.pattern_interpolation))
        throw Error(ErrorCode::kInvalidArgument,
                    "vfgs_seed, vfgs_gain_percent, vfgs_output_bit_depth and pattern_interpolation belong to the "
                    "vfgs flavour");
    if (o.vfgs_output_bit_depth != 0 && (o.vfgs_output_bit_depth < 8 || o.vfgs_output_bit_depth > 16))
        throw Error(ErrorCode::kInvalidArgument,
                    "vfgs_output_bit_depth = " + std::to_string(o.vfgs_output_bit_depth) +
                        " is out of range (allowed 0, the input's depth, or 8..16)");
}

void check_codec(FgcCodec codec) {
    const int c = static_cast<int>(codec);
    if (c < 0 || c > 2) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("codec", c, 0, 2));
}

// copy_plane leaves a plane alone when dst is src (in place).
void copy_frame(const FrameView& src, const FrameView& dst) {
    for (int c = 0; c < src.plane_count(); c++) fgc::copy_plane(src.planes[c], dst.planes[c], src.bytes_per_sample());
}

void check_views(const FrameView& src, const FrameView& dst, int dst_bit_depth) {
    // sizes, planes, strides and 16-bit alignment (check_plane_layout), for every model
    av1::check_frame_view(src, "src");
    av1::check_frame_view(dst, "dst");
    if (src.format != dst.format || src.width != dst.width || src.height != dst.height)
        throw Error(ErrorCode::kInvalidArgument, "dst differs from src in size or chroma format");
    if (dst.bit_depth != dst_bit_depth)
        throw Error(ErrorCode::kInvalidArgument,
                    "dst.bit_depth = " + std::to_string(dst.bit_depth) + ", expected " + std::to_string(dst_bit_depth) +
                        (dst_bit_depth == src.bit_depth ? " (the source's)" : " (vfgs_output_bit_depth)"));
}

// Only parameter-set problems pass through; caller errors (views, sizes) always fail.
bool is_parameter_problem(ErrorCode code) {
    return code == ErrorCode::kInvalidParams || code == ErrorCode::kUnsupported;
}

}  // namespace

struct Session::Impl {
    enum class Model { kNone, kFgc, kAv1, kAfgs1 };

    SessionOptions options;
    Model model = Model::kNone;
    int pictures_applied = 0;

    // FGC SEI: rdd5 / vtm through FgcStreamSynthesis, vfgs through its own synthesizer.
    session::PendingSeiQueue pending;
    std::unique_ptr<FgcStreamSynthesis> fgc;
    std::unique_ptr<vfgs::Synthesizer> vfgs;
    std::string vfgs_invalid;  // why the vfgs parameter set in force cannot be used

    // AV1
    session::Av1ReferenceSlots slots;
    std::optional<Av1FilmGrainParams> av1;
    int av1_matrix_coefficients = 2;
    // Made on first use: an FGC-only context starts no AV1 worker threads.
    std::unique_ptr<av1::Av1PictureSynthesis> av1_synthesizer;

    // AFGS1: the stored sets persist across payloads; a payload is for the next picture
    // applied only (as `filmgrain apply --afgs1`: the metadata travels with its frame).
    Afgs1Reader afgs1_reader;
    std::optional<Afgs1Payload> afgs1_pending;

    explicit Impl(const SessionOptions& o) : options(o) { make_synthesizers(); }

    void make_synthesizers() {
        if (options.flavour == FgcFlavour::kVfgs) {
            vfgs::Options vo;
            vo.seed = options.vfgs_seed;
            vo.gain_percent = options.vfgs_gain_percent;
            vo.output_bit_depth = options.vfgs_output_bit_depth;
            vo.pattern_interpolation = options.pattern_interpolation;
            vo.block_size = options.block_size;
            vo.threads = options.threads;
            vo.reference_kernels = options.reference_kernels;
            vfgs = std::make_unique<vfgs::Synthesizer>(vo);
        } else {
            FgcOptions fo;
            fo.flavour = options.flavour;
            fo.persistence = options.persistence;
            fo.coded_width = options.coded_width;
            fo.coded_height = options.coded_height;
            fo.passthrough_invalid = options.passthrough_invalid;
            fo.threads = options.threads;
            fo.block_size = options.block_size;
            fo.single_line_blocks = options.single_line_blocks;
            fo.reference_kernels = options.reference_kernels;
            fgc = std::make_unique<FgcStreamSynthesis>(fo);
        }
        vfgs_invalid.clear();
    }

    ApplyResult apply_fgc(const FrameView& src, const FrameView& dst, const FrameInfo& info) {
        std::optional<session::PendingSei> sei = pending.take_for(info.ids);
        ApplyResult r;
        if (fgc) {
            if (sei) fgc->receive_sei(sei->params, sei->codec);
            FgcPictureIds ids = info.ids;
            if (info.seed) {
                // Both flavours derive the seed from pic_offset = POC + (idr_pic_id << 5).
                ids.poc = static_cast<int32_t>(*info.seed);
                ids.idr_pic_id = 0;
            }
            FgcFrameResult fr = fgc->apply(src, dst, ids);
            if (options.report_applied_parameters) {
                FgcCodec codec = FgcCodec::kHevc;
                if (const FgcParams* in_force = fgc->params_in_force(&codec)) {
                    AppliedGrain a;
                    a.model = AppliedGrain::Model::kFgc;
                    a.fgc = *in_force;
                    a.fgc_codec = codec;
                    a.fgc_ids = ids;
                    a.fgc_own_sei = sei.has_value();
                    r.applied = std::move(a);
                }
            }
            r.grain_applied = fr.grain_applied;
            r.message = fr.message;
            r.parameters_refused = fr.parameters_refused;
            return r;
        }
        if (info.seed) refuse_vfgs_seed();
        if (sei) receive_vfgs_sei(*sei);
        if (!vfgs_has_params) {
            vfgs->pass_through(src, dst);
            return r;
        }
        if (!vfgs_invalid.empty()) {
            vfgs->pass_through(src, dst);
            r.message = "film grain not applied: " + vfgs_invalid;
            r.parameters_refused = true;
            return r;
        }
        try {
            vfgs->apply(src, dst);
        } catch (const Error& e) {
            if (!options.passthrough_invalid || !is_parameter_problem(e.code())) throw;
            vfgs->pass_through(src, dst);
            r.message = std::string("film grain not applied: ") + e.what();
            r.parameters_refused = true;
            return r;
        }
        r.grain_applied = !vfgs_cancelled;
        if (vfgs_cancelled) r.message = "film grain cancelled (film_grain_characteristics_cancel_flag = 1)";
        return r;
    }

    [[noreturn]] static void refuse_vfgs_seed() {
        throw Error(ErrorCode::kUnsupported,
                    "seed: the vfgs flavour never reseeds per picture (VersatileFilmGrain); set vfgs_seed at creation");
    }

    // vfgs keeps the last parameter set in force (the reference has no persistence rules); a
    // cancel or an invalid set stays in force until the next SEI.
    void receive_vfgs_sei(const session::PendingSei& sei) {
        vfgs_has_params = true;
        vfgs_cancelled = sei.params.film_grain_characteristics_cancel_flag;
        vfgs_invalid.clear();
        try {
            vfgs->set_params(sei.params);
        } catch (const Error& e) {
            if (!options.passthrough_invalid || !is_parameter_problem(e.code())) throw;
            vfgs_invalid = e.what();
        }
    }

    bool vfgs_has_params = false;
    bool vfgs_cancelled = false;

    ApplyResult apply_av1(const FrameView& src, const FrameView& dst, const FrameInfo& info) {
        return apply_av1_params(*av1, av1_matrix_coefficients, src, dst, info);
    }

    ApplyResult apply_av1_params(Av1FilmGrainParams p, int matrix_coefficients, const FrameView& src,
                                 const FrameView& dst, const FrameInfo& info) {
        ApplyResult r;
        if (info.seed) p.grain_seed = static_cast<int>(*info.seed & 0xFFFF);
        if (options.clip_to_restricted_range >= 0) p.clip_to_restricted_range = options.clip_to_restricted_range;
        if (info.matrix_coefficients) matrix_coefficients = *info.matrix_coefficients;
        if (!av1_synthesizer)
            av1_synthesizer = std::make_unique<av1::Av1PictureSynthesis>(
                options.threads, options.reference_kernels ? av1::Kernels::kReference : av1::Kernels::kOptimized);
        if (options.report_applied_parameters) {
            AppliedGrain a;
            a.model = AppliedGrain::Model::kAv1;
            a.av1 = p;
            a.matrix_coefficients = matrix_coefficients;
            r.applied = a;
        }
        try {
            av1_synthesizer->apply(p, src, dst, matrix_coefficients);
        } catch (const Error& e) {
            if (!options.passthrough_invalid || !is_parameter_problem(e.code())) throw;
            copy_frame(src, dst);
            r.message = std::string("film grain not applied: ") + e.what();
            r.parameters_refused = true;
            return r;
        }
        r.grain_applied = p.apply_grain != 0 && (p.num_y_points > 0 || p.chroma_scaling_from_luma ||
                                                 p.num_cb_points > 0 || p.num_cr_points > 0);
        return r;
    }

    // AFGS1 7.3: the picture takes the set signalled for its size, subsampling and bit
    // depth. The context knows nothing of the picture's colour description, so sets match
    // whatever CICP values they signal (Afgs1Picture's "unknown").
    ApplyResult apply_afgs1(const FrameView& src, const FrameView& dst, const FrameInfo& info) {
        ApplyResult r;
        if (!afgs1_pending) {
            copy_frame(src, dst);
            r.message = "film grain not applied: no AFGS1 payload arrived for this picture";
            return r;
        }
        const Afgs1Payload payload = std::move(*afgs1_pending);
        afgs1_pending.reset();
        Afgs1Picture pic;
        pic.width = src.width;
        pic.height = src.height;
        pic.format = src.format;
        pic.bit_depth = src.bit_depth;
        if (info.matrix_coefficients) pic.matrix_coefficients = *info.matrix_coefficients;
        const std::optional<Afgs1Selection> sel = select_afgs1_set(payload, pic);
        if (!sel) {
            copy_frame(src, dst);
            r.message = payload.afgs1_enable_flag
                            ? "film grain not applied: no parameter set of the AFGS1 payload fits a " +
                                  std::to_string(src.width) + "x" + std::to_string(src.height) + " " +
                                  std::to_string(src.bit_depth) + "-bit " + chroma_format_label(src.format) + " picture"
                            : "film grain not applied: afgs1_enable_flag = 0";
            return r;
        }
        // the selection already weighed the picture's matrix_coefficients against the set's
        FrameInfo selected = info;
        selected.matrix_coefficients.reset();
        ApplyResult applied = apply_av1_params(sel->params, sel->matrix_coefficients, src, dst, selected);
        if (!sel->params.apply_grain && applied.message.empty())
            applied.message = "film grain not applied: the selected AFGS1 set (film_grain_param_set_idx " +
                              std::to_string(payload.sets[sel->set_index].film_grain_param_set_idx) +
                              ") has apply_grain_flag = 0";
        return applied;
    }

    // Callers that pass no ids count pictures from 0 (POC k, idr_pic_id 0).
    FrameInfo info_or_next(const FrameInfo* info) const {
        if (info) return *info;
        FrameInfo fi;
        fi.ids.poc = pictures_applied;
        return fi;
    }

    static std::string chroma_format_label(ChromaFormat f) {
        switch (f) {
        case ChromaFormat::k400: return "4:0:0";
        case ChromaFormat::k420: return "4:2:0";
        case ChromaFormat::k422: return "4:2:2";
        case ChromaFormat::k444: return "4:4:4";
        }
        return "?";
    }
};

Session::Session(const SessionOptions& options) {
    check_options(options);
    impl_ = std::make_unique<Impl>(options);
}
Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

const SessionOptions& Session::options() const { return impl_->options; }

void Session::receive_fgc_params(const FgcParams& params, FgcCodec codec, std::optional<FgcPictureIds> picture) {
    check_codec(codec);
    impl_->pending.push({params, codec, picture});
    impl_->model = Impl::Model::kFgc;
}

void Session::receive_fgc_sei_payload(const uint8_t* payload, std::size_t size, FgcCodec codec,
                                           std::optional<FgcPictureIds> picture) {
    check_codec(codec);
    if (!payload && size) throw Error(ErrorCode::kInvalidArgument, "payload is NULL with size " + std::to_string(size));
    receive_fgc_params(parse_fgc_sei_payload(payload, size, codec), codec, picture);
}

void Session::receive_av1_params(const Av1FilmGrainParams& params, unsigned refresh_frame_flags,
                                      int matrix_coefficients) {
    if (refresh_frame_flags > 0xFF)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("refresh_frame_flags", refresh_frame_flags, 0, 255));
    if (matrix_coefficients < 0 || matrix_coefficients > 255)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("matrix_coefficients", matrix_coefficients, 0, 255));
    const Av1FilmGrainParams resolved = impl_->slots.resolve(params);
    impl_->slots.store(resolved, refresh_frame_flags);
    impl_->av1 = resolved;
    impl_->av1_matrix_coefficients = matrix_coefficients;
    impl_->model = Impl::Model::kAv1;
}

void Session::show_existing_av1_frame(int frame_to_show_map_idx) {
    impl_->av1 = impl_->slots.at(frame_to_show_map_idx);
    impl_->model = Impl::Model::kAv1;
}

void Session::receive_afgs1_t35(const uint8_t* payload, std::size_t size) {
    if (!payload && size) throw Error(ErrorCode::kInvalidArgument, "payload is NULL with size " + std::to_string(size));
    if (!payload || size == 0)
        throw Error(ErrorCode::kMalformedPayload, "AFGS1 payload: empty (0 bytes; at least 1 is needed)");
    // A bare av1_film_grain_param_sets() cannot start with the country code 0xB5 (its
    // reserved bits are 0), so both forms decoders hand over are told apart by the first byte.
    // The reader leaves its stored sets untouched when it throws: a damaged payload is as
    // if it never arrived.
    Afgs1Payload parsed = impl_->afgs1_reader.receive(payload, size, afgs1_has_t35_header(payload, size));
    impl_->afgs1_pending = std::move(parsed);
    impl_->model = Impl::Model::kAfgs1;
}


void Session::reset() {
    Impl& s = *impl_;
    s.pending.clear();
    s.slots.clear();
    s.av1.reset();
    s.afgs1_reader = Afgs1Reader{};
    s.afgs1_pending.reset();
    s.model = Impl::Model::kNone;
    s.pictures_applied = 0;
    s.vfgs_cancelled = false;
    s.vfgs_has_params = false;
    s.make_synthesizers();
}

void Session::skip_picture(const FrameInfo* info) { skip_picture(0, 0, info); }

void Session::skip_picture(int luma_width, int luma_height, const FrameInfo* info) {
    Impl& s = *impl_;
    if (s.model == Impl::Model::kFgc && !s.fgc && (luma_width < 1 || luma_height < 1)) {
        std::string msg = "the vfgs flavour follows a stream only with the picture size (skip_picture(width, height)): "
                          "VersatileFilmGrain's random state steps once per 16x16 block of every picture; got ";
        msg += std::to_string(luma_width);
        msg += 'x';
        msg += std::to_string(luma_height);
        throw Error(ErrorCode::kUnsupported, msg);
    }
    const FrameInfo fi = s.info_or_next(info);
    switch (s.model) {
    case Impl::Model::kNone:
    case Impl::Model::kAv1: break;
    case Impl::Model::kFgc: {
        std::optional<session::PendingSei> sei = s.pending.take_for(fi.ids);
        if (!s.fgc) {
            if (fi.seed) Impl::refuse_vfgs_seed();
            if (sei) s.receive_vfgs_sei(*sei);
            // apply() passes such pictures through without moving the random state, and so it
            // does a picture it refuses under passthrough_invalid
            if (s.vfgs_has_params && s.vfgs_invalid.empty()) {
                try {
                    s.vfgs->skip(luma_width, luma_height);
                } catch (const Error& e) {
                    if (!s.options.passthrough_invalid || !is_parameter_problem(e.code())) throw;
                }
            }
            break;
        }
        if (sei) s.fgc->receive_sei(sei->params, sei->codec);
        s.fgc->skip_picture();
        break;
    }
    case Impl::Model::kAfgs1: s.afgs1_pending.reset(); break;
    }
    s.pictures_applied = static_cast<int>(static_cast<unsigned>(s.pictures_applied) + 1u);
}

ApplyResult Session::apply(const FrameView& src, const FrameView& dst, const FrameInfo* info) {
    Impl& s = *impl_;
    const FrameInfo fi = s.info_or_next(info);
    const int dst_bit_depth = s.options.flavour == FgcFlavour::kVfgs && s.options.vfgs_output_bit_depth
                                  ? s.options.vfgs_output_bit_depth
                                  : src.bit_depth;
    check_views(src, dst, dst_bit_depth);
    ApplyResult r;
    switch (s.model) {
    case Impl::Model::kNone: copy_frame(src, dst); break;
    case Impl::Model::kFgc: r = s.apply_fgc(src, dst, fi); break;
    case Impl::Model::kAv1: r = s.apply_av1(src, dst, fi); break;
    case Impl::Model::kAfgs1: r = s.apply_afgs1(src, dst, fi); break;
    }
    s.pictures_applied = static_cast<int>(static_cast<unsigned>(s.pictures_applied) + 1u);  // wraps, as POC may
    return r;
}

}  // namespace filmgrain

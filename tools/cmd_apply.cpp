// `filmgrain apply`: add grain to a raw YUV or Y4M file from parameters (JSON, SEI payloads).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "core/thread_pool.hpp"
#include "frame_pipeline.hpp"
#include "option_parsing.hpp"
#include "filmgrain/session.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/aom_grain_table.hpp"
#include "payload_files.hpp"
#include "metadata/av1_params_json.hpp"
#include "filmgrain/error.hpp"
#include "io/xz_file.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/json_access.hpp"
#include "metadata/params_file.hpp"

namespace filmgrain::cli {
namespace {

struct ApplyOptions {
    std::string input, output, params;
    std::vector<std::string> sei;
    std::vector<std::string> afgs1;
    std::string sei_codec = "hevc";
    std::string flavour = "rdd5";
    std::string on_invalid = "error";
    std::string persistence = "reference";
    int block_size = 0;
    int single_line_blocks = 0;
    std::string coded_size;
    int threads = 0;
    bool quiet = false;
    // vfgs flavour: the reference tool's own options
    std::optional<uint32_t> seed;
    int gain = 100;
    std::string output_pix_fmt;
    bool pattern_interpolation = false;
    // AV1
    int matrix_coefficients = -1;
    int clip_to_restricted_range = -1;
    RawVideoOptions raw;
};

// Where each picture's FGC SEI comes from.
class FgcSource {
public:
    virtual ~FgcSource() = default;
    // The SEI that arrives with picture k (if any) and its ids.
    virtual std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) = 0;
};

class ParamsFileSource : public FgcSource {
public:
    explicit ParamsFileSource(ParamsFile f) : f_(std::move(f)) {}
    std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) override {
        ids = FgcPictureIds{k, 0};
        if (!f_.per_frame) return f_.frames[0].fgc;  // one object: every picture
        if (std::size_t(k) >= f_.frames.size()) return std::nullopt;
        const FrameParams& fr = f_.frames[k];
        if (fr.poc) ids.poc = *fr.poc;
        if (fr.idr_pic_id) ids.idr_pic_id = *fr.idr_pic_id;
        if (fr.pic_offset) ids = FgcPictureIds{*fr.pic_offset, 0};
        return fr.fgc;
    }

private:
    ParamsFile f_;
};

class SeiFileSource : public FgcSource {
public:
    SeiFileSource(std::vector<std::string> files, FgcCodec codec) : files_(std::move(files)), codec_(codec) {}
    std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) override {
        ids = FgcPictureIds{k, 0};
        const auto bytes = files_.for_picture(k);
        if (!bytes) return std::nullopt;
        try {
            return parse_fgc_sei_payload(*bytes, codec_);
        } catch (const Error& e) {
            throw Error(e.code(), "'" + files_.name_for(k) + "': " + e.what());
        }
    }

private:
    PayloadFiles files_;
    FgcCodec codec_;
};

bool ends_with(const std::string& s, const char* suffix) {
    const std::size_t n = std::strlen(suffix);
    return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// The per-frame loop shared by every model: read, synthesize, write, pipelined so that
// the three overlap (frame_pipeline.hpp); the output file appears only when every frame
// succeeded.
template <typename Synthesize>
int process_video(const ApplyOptions& o, const VideoInfo& out_override, bool override_format, Synthesize&& synth,
                  const char* model) {
    VideoReader reader(o.input, o.raw.to_info());
    VideoInfo out_info = reader.info();
    if (override_format) out_info.format = out_override.format;
    const bool y4m_out = o.output != "-" ? has_y4m_extension(o.output) : reader.info().y4m;
    VideoWriter writer(o.output, out_info, y4m_out);
    const int k = run_frame_pipeline(
        [&](FrameBuffer& in) { return reader.read(in); },
        [&](int k, FrameSlot& slot) {
            FrameBuffer &in = slot.in, &out = slot.out;
            if (out.width() != in.width() || out.height() != in.height() ||
                out.format().chroma != out_info.format.chroma || out.format().bit_depth != out_info.format.bit_depth)
                out = FrameBuffer(in.width(), in.height(), out_info.format);
            synth(k, reader.info(), in, out);
        },
        [&](const FrameBuffer& out) { writer.write(out); });
    if (k == 0) throw Error(ErrorCode::kIo, "input '" + o.input + "' holds no frame");
    writer.commit();
    if (!o.quiet && o.output != "-")
        std::fprintf(stderr, "filmgrain: %d frame(s) written to %s (%s)\n", k, o.output.c_str(), model);
    return 0;
}

// Stream state and synthesis are the session's (include/filmgrain/session.hpp): the tool
// reads files and hands each picture's metadata over as a decoder would.
SessionOptions session_options(const ApplyOptions& o) {
    SessionOptions so;
    so.threads = o.threads;
    so.clip_to_restricted_range = o.clip_to_restricted_range;
    return so;
}

// A message of the session about picture k (passthrough, cancel, no AFGS1 payload...).
void report(const ApplyOptions& o, int k, const ApplyResult& r) {
    if (!r.message.empty() && !o.quiet) std::fprintf(stderr, "filmgrain: frame %d: %s\n", k, r.message.c_str());
}

int run_av1(const ApplyOptions& o) {
    std::vector<Av1FrameParams> frames;
    std::optional<AomGrainTable> table;
    if (ends_with(o.params, ".tbl")) {
        table = read_aom_grain_table(o.params);
    } else {
        frames = av1_frame_params_from_json(read_json_file(o.params));
        if (frames.empty()) throw Error(ErrorCode::kInvalidParams, "parameter file '" + o.params + "' has no AV1 frame");
    }
    const bool single = frames.size() == 1;
    Session session(session_options(o));
    return process_video(
        o, {}, false,
        [&](int k, const VideoInfo& info, FrameBuffer& in, FrameBuffer& out) {
            Av1FilmGrainParams p;
            int mc = o.matrix_coefficients;
            if (table) {
                // libaom tables are indexed by time in 10 MHz ticks
                const int64_t ts = int64_t(k) * 10000000 * info.fps_den / info.fps_num;
                const auto idx = table->find_index(ts);
                if (!idx)
                    throw Error(ErrorCode::kInvalidParams, "grain table '" + o.params + "' has no entry for frame " +
                                                               std::to_string(k) + " (timestamp " + std::to_string(ts) +
                                                               ")");
                p = table->resolved_params(*idx);
            } else {
                const Av1FrameParams& fp = single ? frames[0] : frames.at(std::min<std::size_t>(k, frames.size() - 1));
                if (!single && std::size_t(k) >= frames.size())
                    throw Error(ErrorCode::kInvalidParams, "parameter file '" + o.params + "' lists " +
                                                               std::to_string(frames.size()) +
                                                               " frames but the input has more");
                p = fp.grain;
                if (mc < 0 && fp.color) mc = fp.color->matrix_coefficients;
            }
            if (mc < 0) mc = 2;  // unspecified
            // a file's set is complete: nothing to load from a reference slot
            p.update_grain = 1;
            session.receive_av1_params(p, 0, mc);
            FrameInfo fi;
            fi.ids.poc = k;
            report(o, k, session.apply(in.view(), out.view(), &fi));
        },
        "AV1 film grain");
}

// AFGS1 T.35 payloads: the stored sets persist across pictures; each picture's
// payload selects the set for the picture's size, format and bit depth. A picture
// without a payload gets no grain (the metadata applies to its own picture).
int run_afgs1(const ApplyOptions& o) {
    const PayloadFiles files(o.afgs1);
    Session session(session_options(o));
    return process_video(
        o, {}, false,
        [&](int k, const VideoInfo&, FrameBuffer& in, FrameBuffer& out) {
            if (const auto bytes = files.for_picture(k)) {
                try {
                    session.receive_afgs1_t35(bytes->data(), bytes->size());
                } catch (const Error& e) {
                    throw Error(e.code(), "'" + files.name_for(k) + "': " + e.what());
                }
            }
            FrameInfo fi;
            fi.ids.poc = k;
            if (o.matrix_coefficients >= 0) fi.matrix_coefficients = o.matrix_coefficients;
            report(o, k, session.apply(in.view(), out.view(), &fi));
        },
        "AFGS1 film grain");
}

// FGC SEI in every flavour: the source gives each picture's SEI (if any), the session
// keeps persistence, cancel and the invalid-set policy.
int run_fgc(const ApplyOptions& o, FgcFlavour flavour, FgcCodec codec, std::unique_ptr<FgcSource> source) {
    SessionOptions so = session_options(o);
    so.flavour = flavour;
    so.persistence = o.persistence == "semantic" ? FgcPersistence::kSemantic : FgcPersistence::kReference;
    so.block_size = o.block_size;
    so.single_line_blocks = o.single_line_blocks;
    so.passthrough_invalid = o.on_invalid == "passthrough";
    VideoInfo out_override;
    bool override_format = false;
    if (flavour == FgcFlavour::kVfgs) {
        so.vfgs_seed = o.seed;
        so.vfgs_gain_percent = o.gain;
        so.pattern_interpolation = o.pattern_interpolation;
        if (!o.output_pix_fmt.empty()) {
            out_override.format = parse_pix_fmt(o.output_pix_fmt);
            override_format = true;
            so.vfgs_output_bit_depth = out_override.format.bit_depth;
        }
    }
    if (!o.coded_size.empty()) {
        const PictureSize cs = parse_picture_size(o.coded_size, "--coded-size");
        so.coded_width = cs.width;
        so.coded_height = cs.height;
    }
    Session session(so);
    const std::string model = std::string("flavour ") + fgc_flavour_name(flavour);
    return process_video(
        o, out_override, override_format,
        [&](int k, const VideoInfo& info, FrameBuffer& in, FrameBuffer& out) {
            if (override_format && out_override.format.chroma != info.format.chroma)
                throw Error(ErrorCode::kInvalidArgument, "--output-pix-fmt " + o.output_pix_fmt +
                                                             " must keep the input's chroma format (" +
                                                             pix_fmt_name(info.format) + ")");
            FrameInfo fi;
            if (auto sei = source->sei_for(k, fi.ids)) session.receive_fgc_params(*sei, codec);
            report(o, k, session.apply(in.view(), out.view(), &fi));
        },
        model.c_str());
}

int run_apply(const ApplyOptions& o) {
    const FgcFlavour flavour = parse_flavour(o.flavour);
    if (o.on_invalid != "error" && o.on_invalid != "passthrough")
        throw Error(ErrorCode::kInvalidArgument, "--on-invalid '" + o.on_invalid + "' is not known (allowed error, passthrough)");
    if (o.persistence != "reference" && o.persistence != "semantic")
        throw Error(ErrorCode::kInvalidArgument,
                    "--persistence '" + o.persistence + "' is not known (allowed reference, semantic)");
    if (int(!o.params.empty()) + int(!o.sei.empty()) + int(!o.afgs1.empty()) != 1)
        throw Error(ErrorCode::kInvalidArgument, "give exactly one of --params FILE, --sei FILE or --afgs1 FILE");
    if (!o.afgs1.empty()) return run_afgs1(o);
    const FgcCodec codec = parse_fgc_codec(o.sei_codec);

    std::unique_ptr<FgcSource> source;
    if (!o.params.empty()) {
        if (ends_with(o.params, ".tbl")) return run_av1(o);
        ParamsFile pf = load_params_file(o.params);
        if (!pf.has_fgc() && pf.has_av1()) return run_av1(o);
        source = std::make_unique<ParamsFileSource>(std::move(pf));
    } else {
        source = std::make_unique<SeiFileSource>(o.sei, codec);
    }
    if (flavour == FgcFlavour::kVfgs && o.single_line_blocks)
        throw Error(ErrorCode::kInvalidArgument,
                    "--single-line-blocks is an option of --flavour vtm and tr (VFGS adapts per sample)");
    if (flavour != FgcFlavour::kVfgs && (o.gain != 100 || o.seed || !o.output_pix_fmt.empty() || o.pattern_interpolation))
        throw Error(ErrorCode::kInvalidArgument,
                    "--seed, --gain, --output-pix-fmt and --pattern-interpolation belong to --flavour vfgs");
    return run_fgc(o, flavour, codec, std::move(source));
}

}  // namespace

void register_apply(CLI::App& app) {
    auto o = std::make_shared<ApplyOptions>();
    CLI::App* sub = app.add_subcommand("apply", "add film grain to a raw YUV or Y4M file");
    sub->add_option("--input,-i", o->input, "input file (raw planar YUV or Y4M), - for stdin")->required();
    sub->add_option("--output,-o", o->output, "output file (.y4m writes Y4M), - for stdout")->required();
    sub->add_option("--params,-p", o->params, "parameter file: JSON (FGC SEI syntax elements, AV1 film_grain_params, or a per-frame list) or a libaom grain table (.tbl)");
    sub->add_option("--sei", o->sei,
                    "raw FGC SEI payload(s) (payloadType 19 body); one file for every picture, several for "
                    "pictures 0,1,..., or a printf pattern such as frame%d.fgc.bin (missing = no SEI)");
    sub->add_option("--afgs1", o->afgs1,
                    "AFGS1 ITU-T T.35 payload(s) (with or without the B5 5890 01 header); one file for every "
                    "picture, several for pictures 0,1,..., or a printf pattern (missing = no grain)");
    sub->add_option("--sei-codec", o->sei_codec, "SEI syntax variant: avc, hevc or vvc")->capture_default_str();
    sub->add_option("--flavour", o->flavour,
                    "rdd5 (SMPTE RDD 5 / FFmpeg), vtm (HM/VTM reference), vfgs (VersatileFilmGrain) or tr (rdd5 "
                    "plus what TR 23002-9 allows beyond the references: auto-regressive model, multiplicative "
                    "blending, film grain bit depth)")
        ->capture_default_str();
    sub->add_option("--on-invalid", o->on_invalid,
                    "invalid parameter set: error (exit non-zero) or passthrough (picture unchanged, as the references)")
        ->capture_default_str();
    sub->add_option("--persistence", o->persistence,
                    "pictures without an SEI: reference (HM: reuse the last SEI) or semantic (persistence_flag)")
        ->capture_default_str();
    sub->add_option("--block-size", o->block_size,
                    "force the block size 8, 16 or 32 (0: flavour default; vfgs has 16 only)");
    sub->add_option("--single-line-blocks", o->single_line_blocks,
                    "vtm, tr: TR 23002-9 7.3.2.3 single-line blocks, intensity averaged over 8x1, 16x1 or 32x1 "
                    "segments, one template per component and picture (0: square blocks)");
    sub->add_option("--coded-size", o->coded_size,
                    "vtm: the stream's coded picture size WxH (SPS), which picks HM's block size "
                    "(default: the picture size rounded up to a multiple of 16)");
    sub->add_option("--threads", o->threads,
                    "synthesis threads per frame, rdd5/vtm/AV1 (0: all cores; the output is the same for any count)")
        ->check(CLI::Range(0, kMaxThreads));
    sub->add_option("--seed", o->seed, "vfgs: the reference's -r seed (absent: its default state 0xDEADBEEF)");
    sub->add_option("--gain", o->gain, "vfgs: the reference's --gain in percent")->capture_default_str();
    sub->add_option("--output-pix-fmt", o->output_pix_fmt, "vfgs: output format, e.g. yuv420p for 8-bit output of 10-bit input");
    sub->add_flag("--pattern-interpolation", o->pattern_interpolation,
                  "vfgs: TR 23002-9 7.2.4.2 pattern interpolation, blending the templates of neighbouring intensity "
                  "intervals near their boundary (compiled out of the reference: not bit-exact with it)");
    sub->add_option("--matrix-coefficients", o->matrix_coefficients,
                    "AV1: the stream's matrix_coefficients (0 = identity changes the chroma clip); default from the "
                    "parameter file, else 2")
        ->check(CLI::Range(0, 255));
    sub->add_option("--clip-to-restricted-range", o->clip_to_restricted_range,
                    "AV1: override clip_to_restricted_range (0/1); libaom grain tables cannot carry it")
        ->check(CLI::Range(0, 1));
    sub->add_flag("--quiet,-q", o->quiet, "no messages on stderr except errors");
    o->raw.add_to(sub);
    sub->callback([o]() {
        int rc = run_apply(*o);
        if (rc) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli

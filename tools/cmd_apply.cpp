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
#include "session/parameter_file_feed.hpp"
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

// Stream state and synthesis are the session's (include/filmgrain/session.hpp); what each
// picture receives is the parameter-file feed's (session/parameter_file_feed.hpp), which
// the GStreamer element's properties share.
SessionOptions session_options(const ApplyOptions& o, FgcFlavour flavour, session::FeedModel model) {
    SessionOptions so;
    so.threads = o.threads;
    so.clip_to_restricted_range = o.clip_to_restricted_range;
    if (model != session::FeedModel::kFgc) return so;
    so.flavour = flavour;
    so.persistence = o.persistence == "semantic" ? FgcPersistence::kSemantic : FgcPersistence::kReference;
    so.block_size = o.block_size;
    so.single_line_blocks = o.single_line_blocks;
    so.passthrough_invalid = o.on_invalid == "passthrough";
    if (flavour == FgcFlavour::kVfgs) {
        so.vfgs_seed = o.seed;
        so.vfgs_gain_percent = o.gain;
        so.pattern_interpolation = o.pattern_interpolation;
        if (!o.output_pix_fmt.empty()) so.vfgs_output_bit_depth = parse_pix_fmt(o.output_pix_fmt).bit_depth;
    }
    if (!o.coded_size.empty()) {
        const PictureSize cs = parse_picture_size(o.coded_size, "--coded-size");
        so.coded_width = cs.width;
        so.coded_height = cs.height;
    }
    return so;
}

// A message of the session about picture k (passthrough, cancel, no AFGS1 payload...).
void report(const ApplyOptions& o, int k, const ApplyResult& r) {
    if (!r.message.empty() && !o.quiet) std::fprintf(stderr, "filmgrain: frame %d: %s\n", k, r.message.c_str());
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
    session::ParameterFiles files;
    files.params = o.params;
    files.sei = o.sei;
    files.afgs1 = o.afgs1;
    files.sei_codec = parse_fgc_codec(o.sei_codec);
    files.matrix_coefficients = o.matrix_coefficients;
    session::ParameterFileFeed feed(files);
    const session::FeedModel model = feed.model();
    if (model == session::FeedModel::kFgc) {
        if (flavour == FgcFlavour::kVfgs && o.single_line_blocks)
            throw Error(ErrorCode::kInvalidArgument,
                        "--single-line-blocks is an option of --flavour vtm and tr (VFGS adapts per sample)");
        if (flavour != FgcFlavour::kVfgs &&
            (o.gain != 100 || o.seed || !o.output_pix_fmt.empty() || o.pattern_interpolation))
            throw Error(ErrorCode::kInvalidArgument,
                        "--seed, --gain, --output-pix-fmt and --pattern-interpolation belong to --flavour vfgs");
    }
    Session session(session_options(o, flavour, model));
    VideoInfo out_override;
    const bool override_format = model == session::FeedModel::kFgc && flavour == FgcFlavour::kVfgs &&
                                 !o.output_pix_fmt.empty();
    if (override_format) out_override.format = parse_pix_fmt(o.output_pix_fmt);
    const std::string name = model == session::FeedModel::kAv1     ? std::string("AV1 film grain")
                             : model == session::FeedModel::kAfgs1 ? std::string("AFGS1 film grain")
                                                                   : std::string("flavour ") + fgc_flavour_name(flavour);
    return process_video(
        o, out_override, override_format,
        [&](int k, const VideoInfo& info, FrameBuffer& in, FrameBuffer& out) {
            if (override_format && out_override.format.chroma != info.format.chroma)
                throw Error(ErrorCode::kInvalidArgument, "--output-pix-fmt " + o.output_pix_fmt +
                                                             " must keep the input's chroma format (" +
                                                             pix_fmt_name(info.format) + ")");
            const FrameInfo fi = feed.feed(session, k, info.fps_num, info.fps_den);
            report(o, k, session.apply(in.view(), out.view(), &fi));
        },
        name.c_str());
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

// `filmgrain apply`: add grain to a raw YUV or Y4M file from parameters (JSON, SEI payloads).
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "apply_job.hpp"
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

void check_apply_options(const ApplyOptions& o) {
    parse_flavour(o.flavour);
    if (o.on_invalid != "error" && o.on_invalid != "passthrough")
        throw Error(ErrorCode::kInvalidArgument, "--on-invalid '" + o.on_invalid + "' is not known (allowed error, passthrough)");
    if (o.persistence != "reference" && o.persistence != "semantic")
        throw Error(ErrorCode::kInvalidArgument,
                    "--persistence '" + o.persistence + "' is not known (allowed reference, semantic)");
    if (int(!o.params.empty()) + int(!o.sei.empty()) + int(!o.afgs1.empty()) != 1)
        throw Error(ErrorCode::kInvalidArgument, "give exactly one of --params FILE, --sei FILE or --afgs1 FILE");
}

session::ParameterFiles parameter_files_of(const ApplyOptions& o) {
    session::ParameterFiles files;
    files.params = o.params;
    files.sei = o.sei;
    files.afgs1 = o.afgs1;
    files.sei_codec = parse_fgc_codec(o.sei_codec);
    files.matrix_coefficients = o.matrix_coefficients;
    return files;
}

}  // namespace

ApplyJob::ApplyJob(const ApplyOptions& options) : o_(options) {
    const ApplyOptions& o = o_;
    check_apply_options(o);
    flavour_ = parse_flavour(o.flavour);
    feed_ = std::make_unique<session::ParameterFileFeed>(parameter_files_of(o));
    model_ = feed_->model();
    if (model_ == session::FeedModel::kFgc) {
        if (flavour_ == FgcFlavour::kVfgs && o.single_line_blocks)
            throw Error(ErrorCode::kInvalidArgument,
                        "--single-line-blocks is an option of --flavour vtm and tr (VFGS adapts per sample)");
        if (flavour_ != FgcFlavour::kVfgs &&
            (o.gain != 100 || o.seed || !o.output_pix_fmt.empty() || o.pattern_interpolation))
            throw Error(ErrorCode::kInvalidArgument,
                        "--seed, --gain, --output-pix-fmt and --pattern-interpolation belong to --flavour vfgs");
    }
    session_options_ = session_options(o, flavour_, model_);
    Session check(session_options_);  // the options' own checks, before any frame is read
    override_format_ = model_ == session::FeedModel::kFgc && flavour_ == FgcFlavour::kVfgs && !o.output_pix_fmt.empty();
    if (override_format_) out_override_.format = parse_pix_fmt(o.output_pix_fmt);
}

ApplyJob::~ApplyJob() = default;

std::string ApplyJob::model_name() const {
    return model_ == session::FeedModel::kAv1     ? std::string("AV1 film grain")
           : model_ == session::FeedModel::kAfgs1 ? std::string("AFGS1 film grain")
                                                  : std::string("flavour ") + fgc_flavour_name(flavour_);
}

const VideoInfo& ApplyJob::input_info() const {
    if (!input_info_) input_info_ = VideoReader(o_.input, o_.raw.to_info()).info();
    return *input_info_;
}

VideoInfo ApplyJob::output_info() const {
    VideoInfo out = input_info();
    if (override_format_) out.format = out_override_.format;
    return out;
}

bool ApplyJob::output_y4m() const { return o_.output != "-" ? has_y4m_extension(o_.output) : input_info().y4m; }

long long ApplyJob::frame_count() const { return frame_count_from_size(o_.input, input_info()); }

// The feed read by the constructor serves the first run; a later one reads the files again
// (a feed moves through the pictures once).
std::unique_ptr<session::ParameterFileFeed> ApplyJob::take_feed() {
    if (feed_) return std::move(feed_);
    return std::make_unique<session::ParameterFileFeed>(parameter_files_of(o_));
}

void ApplyJob::synthesize(session::ParameterFileFeed& feed, Session& session, int k, const VideoInfo& info,
                          FrameBuffer& in, FrameBuffer& out) const {
    if (override_format_ && out_override_.format.chroma != info.format.chroma)
        throw Error(ErrorCode::kInvalidArgument, "--output-pix-fmt " + o_.output_pix_fmt +
                                                     " must keep the input's chroma format (" + pix_fmt_name(info.format) +
                                                     ")");
    const FrameInfo fi = feed.feed(session, k, info.fps_num, info.fps_den);
    report(o_, k, session.apply(in.view(), out.view(), &fi));
}

int ApplyJob::run_all() {
    const std::unique_ptr<session::ParameterFileFeed> owned = take_feed();
    session::ParameterFileFeed& feed = *owned;
    Session session(session_options_);
    const std::string name = model_name();
    return process_video(
        o_, out_override_, override_format_,
        [&](int k, const VideoInfo& info, FrameBuffer& in, FrameBuffer& out) { synthesize(feed, session, k, info, in, out); },
        name.c_str());
}

int ApplyJob::run_range(int from, int to, const std::string& part) {
    if (from < 0 || to < from)
        throw Error(ErrorCode::kInvalidArgument, "picture range [" + std::to_string(from) + ", " + std::to_string(to) +
                                                     ") is not a range of pictures");
    const std::unique_ptr<session::ParameterFileFeed> owned = take_feed();
    session::ParameterFileFeed& feed = *owned;
    Session session(session_options_);
    VideoReader reader(o_.input, o_.raw.to_info());
    const VideoInfo info = reader.info();
    // The state at `from` comes from the metadata of the pictures before it, not from
    // synthesizing them (Session::skip_picture).
    for (int k = 0; k < from; k++) {
        const FrameInfo fi = feed.feed(session, k, info.fps_num, info.fps_den);
        session.skip_picture(info.width, info.height, &fi);
    }
    if (!reader.skip_frames(from)) return 0;
    VideoInfo out_info = info;
    if (override_format_) out_info.format = out_override_.format;
    VideoWriter writer(part, out_info, false);
    FrameBuffer in, out;
    int k = from;
    for (; k < to && reader.read(in); k++) {
        if (out.width() != in.width() || out.height() != in.height() || out.format().chroma != out_info.format.chroma ||
            out.format().bit_depth != out_info.format.bit_depth)
            out = FrameBuffer(in.width(), in.height(), out_info.format);
        synthesize(feed, session, k, info, in, out);
        writer.write(out);
    }
    writer.commit();
    return k - from;
}


void add_apply_options(CLI::App* sub, ApplyOptions& o) {
    sub->add_option("--input,-i", o.input, "input file (raw planar YUV or Y4M), - for stdin")->required();
    sub->add_option("--output,-o", o.output, "output file (.y4m writes Y4M), - for stdout")->required();
    sub->add_option("--params,-p", o.params, "parameter file: JSON (FGC SEI syntax elements, AV1 film_grain_params, or a per-frame list) or a libaom grain table (.tbl)");
    sub->add_option("--sei", o.sei,
                    "raw FGC SEI payload(s) (payloadType 19 body); one file for every picture, several for "
                    "pictures 0,1,..., or a printf pattern such as frame%d.fgc.bin (missing = no SEI)");
    sub->add_option("--afgs1", o.afgs1,
                    "AFGS1 ITU-T T.35 payload(s) (with or without the B5 5890 01 header); one file for every "
                    "picture, several for pictures 0,1,..., or a printf pattern (missing = no grain)");
    sub->add_option("--sei-codec", o.sei_codec, "SEI syntax variant: avc, hevc or vvc")->capture_default_str();
    sub->add_option("--flavour", o.flavour,
                    "rdd5 (SMPTE RDD 5 / FFmpeg), vtm (HM/VTM reference), vfgs (VersatileFilmGrain) or tr (rdd5 "
                    "plus what TR 23002-9 allows beyond the references: auto-regressive model, multiplicative "
                    "blending, film grain bit depth)")
        ->capture_default_str();
    sub->add_option("--on-invalid", o.on_invalid,
                    "invalid parameter set: error (exit non-zero) or passthrough (picture unchanged, as the references)")
        ->capture_default_str();
    sub->add_option("--persistence", o.persistence,
                    "pictures without an SEI: reference (HM: reuse the last SEI) or semantic (persistence_flag)")
        ->capture_default_str();
    sub->add_option("--block-size", o.block_size,
                    "force the block size 8, 16 or 32 (0: flavour default; vfgs has 16 only)");
    sub->add_option("--single-line-blocks", o.single_line_blocks,
                    "vtm, tr: TR 23002-9 7.3.2.3 single-line blocks, intensity averaged over 8x1, 16x1 or 32x1 "
                    "segments, one template per component and picture (0: square blocks)");
    sub->add_option("--coded-size", o.coded_size,
                    "vtm: the stream's coded picture size WxH (SPS), which picks HM's block size "
                    "(default: the picture size rounded up to a multiple of 16)");
    sub->add_option("--threads", o.threads,
                    "synthesis threads per frame, rdd5/vtm/AV1 (0: all cores; the output is the same for any count)")
        ->check(CLI::Range(0, kMaxThreads));
    sub->add_option("--seed", o.seed, "vfgs: the reference's -r seed (absent: its default state 0xDEADBEEF)");
    sub->add_option("--gain", o.gain, "vfgs: the reference's --gain in percent")->capture_default_str();
    sub->add_option("--output-pix-fmt", o.output_pix_fmt, "vfgs: output format, e.g. yuv420p for 8-bit output of 10-bit input");
    sub->add_flag("--pattern-interpolation", o.pattern_interpolation,
                  "vfgs: TR 23002-9 7.2.4.2 pattern interpolation, blending the templates of neighbouring intensity "
                  "intervals near their boundary (compiled out of the reference: not bit-exact with it)");
    sub->add_option("--matrix-coefficients", o.matrix_coefficients,
                    "AV1: the stream's matrix_coefficients (0 = identity changes the chroma clip); default from the "
                    "parameter file, else 2")
        ->check(CLI::Range(0, 255));
    sub->add_option("--clip-to-restricted-range", o.clip_to_restricted_range,
                    "AV1: override clip_to_restricted_range (0/1); libaom grain tables cannot carry it")
        ->check(CLI::Range(0, 1));
    sub->add_flag("--quiet,-q", o.quiet, "no messages on stderr except errors");
    o.raw.add_to(sub);
}

void register_apply(CLI::App& app) {
    register_subcommand(app, "apply", "add film grain to a raw YUV or Y4M file", add_apply_options,
                        [](const ApplyOptions& o) { return ApplyJob(o).run_all(); });
}

}  // namespace filmgrain::cli

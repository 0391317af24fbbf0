// `filmgrain decode INPUT -o OUT.y4m|OUT.yuv|-`: decodes a real file through FFmpeg's
// libraries with film grain exported instead of applied, and adds our grain from the
// exported parameters.
//
// Seeds: AV1 frames carry grain_seed in their parameters (AVFilmGrainParams::seed), used
// as is. For H.264/H.265 FFmpeg exports the FGC SEI in force for the frame with a seed it
// derived: H.265 the picture's PicOrderCntVal, H.264 pic_offset = POC + (idr_pic_id << 5)
// (SMPTE RDD 5). It becomes the picture's POC with idr_pic_id 0, which gives rdd5 exactly
// the seed FFmpeg computed; vtm seeds from the POC alone, so for H.264 streams with a
// non-zero idr_pic_id the vtm seed includes FFmpeg's idr_pic_id term. vfgs never reseeds.
//
// Damage: as ffmpeg and dav1d, decoding goes on past what the demuxer cannot read or the
// decoder refuses. Each damaged unit is a warning naming it (packet index, pts, byte; or
// the picture), the picture it would have given is not output (nothing else is: the grain
// parameters travel with each picture), and a summary ends the run. The exit status is 0
// unless --strict, which exits kStrictDamageExit after writing the same complete output.
// Decoding to no picture at all is an error (no output file).
#include <unistd.h>

#include <chrono>
#include <functional>
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"

#ifdef FILMGRAIN_HAVE_LIBAV
#include <optional>
#include <vector>

#include "bitstream/decode_restart.hpp"
#include "decoded_grain.hpp"
#include "filmgrain/session.hpp"
#include "libav/video_decoder.hpp"
#endif

namespace filmgrain::cli {
namespace {

struct DecodeOptions {
    std::string input, output, format, flavour = "rdd5";
    bool quiet = false;
    bool no_grain = false;
    bool strict = false;
    int threads = 0;
    // A range of the output pictures (distributed runs): pictures before it are decoded
    // from the random access point before the range (bitstream/decode_restart.hpp) but
    // neither synthesized nor written.
    int first_frame = 0;
    int frame_count = -1;
};

// --strict and damaged units: the output is complete, the status tells the damage apart from
// a failure (1, 2: nothing written).
constexpr int kStrictDamageExit = 3;

#ifdef FILMGRAIN_HAVE_LIBAV

class Progress {
public:
    Progress(bool enabled, int64_t total) : enabled_(enabled), total_(total), start_(Clock::now()), last_(start_) {}
    void frame_done(int64_t n) {
        if (!enabled_) return;
        const auto now = Clock::now();
        if (now - last_ < std::chrono::milliseconds(500)) return;
        last_ = now;
        print(n, now);
    }
    void finish(int64_t n) {
        if (!enabled_) return;
        print(n, Clock::now());
        std::fputc('\n', stderr);
        line_open_ = false;
    }
    // Ends the progress line so that a message can be printed on a line of its own.
    void break_line() {
        if (!line_open_) return;
        std::fputc('\n', stderr);
        line_open_ = false;
    }

private:
    using Clock = std::chrono::steady_clock;
    void print(int64_t n, Clock::time_point now) {
        const double s = std::chrono::duration<double>(now - start_).count();
        const double fps = s > 0 ? double(n) / s : 0;
        if (total_ > 0 && fps > 0 && n <= total_)
            std::fprintf(stderr, "\rfilmgrain: frame %lld/%lld, %.1f fps, ETA %.0f s   ", (long long)n,
                         (long long)total_, fps, double(total_ - n) / fps);
        else
            std::fprintf(stderr, "\rfilmgrain: frame %lld, %.1f fps   ", (long long)n, fps);
        std::fflush(stderr);
        line_open_ = true;
    }
    bool enabled_, line_open_ = false;
    int64_t total_;
    Clock::time_point start_, last_;
};

// The visible picture of an uncropped decoder picture (libav::DecodedFrame crop fields).
// The bytes a decoder starting at `r` reads: the IVF header or the parameter sets before it,
// then the file from the unit on.
libav::StreamWindow restart_window(const std::string& path, const bitstream::DecodeRestart& r) {
    libav::StreamWindow w;
    w.offset = int64_t(r.offset);
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw Error(ErrorCode::kIo, "cannot open '" + path + "'");
    const auto read_range = [&](std::size_t at, std::size_t size) {
        const std::size_t old = w.prefix.size();
        w.prefix.resize(old + size);
        const bool ok = fseeko(f, off_t(at), SEEK_SET) == 0 && std::fread(w.prefix.data() + old, 1, size, f) == size;
        if (!ok) {
            std::fclose(f);
            throw Error(ErrorCode::kIo, "'" + path + "': cannot read " + std::to_string(size) + " bytes at " + std::to_string(at));
        }
    };
    if (r.ivf_header_bytes) read_range(0, r.ivf_header_bytes);
    for (const auto& [at, size] : r.parameter_sets) {
        w.prefix.insert(w.prefix.end(), {0, 0, 0, 1});
        read_range(at, size);
    }
    std::fclose(f);
    return w;
}

FrameView conformance_window(const FrameView& coded, const libav::DecodedFrame& f) {
    if (f.crop_left == 0 && f.crop_top == 0 && f.crop_right == 0 && f.crop_bottom == 0) return coded;
    if (f.crop_left < 0 || f.crop_top < 0 || f.crop_right < 0 || f.crop_bottom < 0 ||
        f.crop_left + f.crop_right >= coded.width || f.crop_top + f.crop_bottom >= coded.height)
        throw Error(ErrorCode::kMalformedPayload,
                    "frame " + std::to_string(f.index) + ": conformance window " + std::to_string(f.crop_left) + "," +
                        std::to_string(f.crop_top) + "," + std::to_string(f.crop_right) + "," +
                        std::to_string(f.crop_bottom) + " (left, top, right, bottom) leaves nothing of the " +
                        std::to_string(coded.width) + "x" + std::to_string(coded.height) + " coded picture");
    FrameView v = coded;
    v.width = coded.width - f.crop_left - f.crop_right;
    v.height = coded.height - f.crop_top - f.crop_bottom;
    for (int p = 0; p < v.plane_count(); p++) {
        const int sx = p ? chroma_shift_x(v.format) : 0, sy = p ? chroma_shift_y(v.format) : 0;
        v.planes[p].data += coded.planes[p].stride * (f.crop_top >> sy) + std::ptrdiff_t(f.crop_left >> sx) * coded.bytes_per_sample();
        v.planes[p].width = plane_width(v.format, p, v.width);
        v.planes[p].height = plane_height(v.format, p, v.height);
    }
    return v;
}

int run_decode(const DecodeOptions& o) {
    const FgcFlavour flavour = parse_flavour(o.flavour);
    bool y4m = o.output == "-" || has_y4m_extension(o.output);
    if (!o.format.empty()) {
        if (o.format != "y4m" && o.format != "yuv")
            throw Error(ErrorCode::kInvalidArgument, "--format '" + o.format + "' is not known (allowed y4m, yuv)");
        y4m = o.format == "y4m";
    }
    // ffmpeg flavour: FFmpeg adds FGC grain to the coded picture and crops after, so partial
    // 8x8 blocks at the right and bottom average coded samples beyond the visible picture.
    const bool grain_before_crop = flavour == FgcFlavour::kFfmpeg && !o.no_grain;
    auto decoder = std::make_unique<libav::VideoDecoder>(o.input, o.threads, grain_before_crop);
    const libav::StreamDescription d = decoder->description();

    // FFmpeg exports each picture's grain already resolved (persistence, AV1 reference
    // slots): every picture hands its own set to the session.
    SessionOptions so;
    so.flavour = flavour;
    so.threads = o.threads;
    Session session(so);
    std::unique_ptr<VideoWriter> writer;
    VideoInfo info;
    libav::DecodedFrame frame;
    int64_t n = 0, with_grain = 0, skipped_frames = 0, picture_position = 0;
    Progress progress(!o.quiet && o.output != "-" && isatty(STDERR_FILENO), d.frames_estimate);
    const auto warn = [&progress](const std::string& text) {
        progress.break_line();
        std::fprintf(stderr, "filmgrain: warning: %s\n", text.c_str());
    };
    // only elementary streams the scanner reads can carry AFGS1 or be started part-way: no
    // second read of other files
    const bool raw_stream = d.format_name == "h264" || d.format_name == "hevc" || d.format_name == "ivf" ||
                            d.format_name == "obu" || d.format_name == "av1";
    // The scan is for what libav does not export (AFGS1) and for a range's restart point.
    const bool scan = raw_stream && (o.first_frame > 0 || (!o.no_grain && may_carry_afgs1(o.input)));
    const StreamMetadata stream = scan ? read_stream_metadata(o.input, d.codec_name, warn) : StreamMetadata{};
    // A range decodes from the random access point before it, not from the stream's start.
    int64_t first_position = 0;
    if (o.first_frame > 0 && raw_stream)
        if (const auto restart = bitstream::plan_decode_restart(stream.scan, o.first_frame)) {
            decoder = std::make_unique<libav::VideoDecoder>(o.input, o.threads, grain_before_crop,
                                                            restart_window(o.input, *restart));
            first_position = restart->output_before;
            if (!o.quiet && o.output != "-")
                std::fprintf(stderr,
                             "filmgrain: decoding from access unit %d (a random access point; output picture %lld): the "
                             "%d unit(s) before it are not decoded\n",
                             restart->unit, (long long)restart->output_before, restart->unit);
        }
    // damage is reported even with -q: it is data lost, not progress (packets count from the
    // unit decoding starts at)
    decoder->on_damage([&warn](const libav::DamagedUnit& u) { warn(libav::describe(u)); });
    // Pictures are not copied out of the decoder: the synthesis writes its output frame
    // straight from the decoder's picture (as dav1d does), and pictures without grain are
    // written from the decoder's picture itself.
    while (decoder->next(frame, /*copy_picture=*/false)) {
        frame.index += first_position;
        const FrameView coded_src = frame.decoded, coded_dst = frame.picture.view();
        const FrameView src = conformance_window(coded_src, frame), v = conformance_window(coded_dst, frame);
        if (!writer) {
            info.width = src.width;
            info.height = src.height;
            info.format = frame.picture.format();
            info.fps_num = d.fps_num;
            info.fps_den = d.fps_den;
            info.y4m = y4m;
            writer = std::make_unique<VideoWriter>(o.output, info, y4m);
        } else if (src.width != info.width || src.height != info.height ||
                   frame.picture.format().chroma != info.format.chroma ||
                   frame.picture.format().bit_depth != info.format.bit_depth) {
            // a damaged header, or a stream that really changes size: Y4M and raw YUV hold one
            // size and format, so the picture is left out like one the decoder refused
            warn("frame " + std::to_string(frame.index) +
                 (frame.pts ? " (pts " + std::to_string(*frame.pts) + ")" : std::string()) + ": " +
                 std::to_string(src.width) + "x" + std::to_string(src.height) + " " +
                 pix_fmt_name(frame.picture.format()) + ", but the output holds " + std::to_string(info.width) +
                 "x" + std::to_string(info.height) + " " + pix_fmt_name(info.format) + " (" +
                 (y4m ? "Y4M" : "raw YUV") + " has one size and format); skipped");
            skipped_frames++;
            continue;
        }
        const int64_t position = first_position + picture_position++;
        if (o.frame_count >= 0 && position >= int64_t(o.first_frame) + o.frame_count) break;
        if (position < o.first_frame) continue;
        if (!o.no_grain) take_afgs1_grain(frame, stream.afgs1, src.width, src.height);
        const std::optional<FrameInfo> fi = o.no_grain ? std::nullopt : hand_exported_grain(session, frame);
        if (!fi) {
            // the decoder's output as it is: the clean pictures grain is added to
            writer->write(src);
            n++;
            progress.frame_done(n);
            continue;
        }
        if (frame.fgc && grain_before_crop)
            session.apply(coded_src, coded_dst, &*fi);
        else
            session.apply(src, v, &*fi);
        with_grain++;
        writer->write(v);
        n++;
        progress.frame_done(n);
    }
    const int64_t damaged = decoder->damaged_units() + skipped_frames;
    // a range past the last picture is empty, not an error
    if (n == 0 && (!writer || o.first_frame == 0))
        throw Error(ErrorCode::kIo, "'" + o.input + "' decoded to no frame" +
                                        (damaged ? " (" + std::to_string(damaged) + " damaged unit(s) skipped)" : ""));
    writer->commit();
    progress.finish(n);
    if (!o.quiet && o.output != "-")
        std::fprintf(stderr, "filmgrain: %lld frame(s) (%s via %s, %lld with film grain) written to %s\n", (long long)n,
                     d.codec_name.c_str(), d.decoder_name.c_str(), (long long)with_grain, o.output.c_str());
    if (damaged == 0) return 0;
    std::fprintf(stderr, "filmgrain: warning: %lld damaged unit(s) in '%s' skipped or concealed; %lld frame(s) written\n",
                 (long long)damaged, o.input.c_str(), (long long)n);
    if (!o.strict) return 0;
    std::fprintf(stderr,
                 "filmgrain: error: --strict: %lld damaged unit(s); the output is complete (%lld frame(s)) but the "
                 "exit status is %d\n",
                 (long long)damaged, (long long)n, kStrictDamageExit);
    return kStrictDamageExit;
}

#else

int run_decode(const DecodeOptions&) {
    throw Error(ErrorCode::kUnsupported, "this build of filmgrain has no libavformat/libavcodec (see tools/install-deps)");
}

#endif

}  // namespace

void register_decode(CLI::App& app) {
    auto o = std::make_shared<DecodeOptions>();
    CLI::App* sub = app.add_subcommand(
        "decode", "decode a video file with FFmpeg's libraries and add film grain from its metadata (AV1, FGC SEI)");
    sub->add_option("input", o->input, "any file libavformat reads (AV1 via libdav1d/libaom, H.264, H.265, ...)")
        ->required();
    sub->add_option("--output,-o", o->output, "output: .y4m, .yuv (raw planar), or - for Y4M on stdout")->required();
    sub->add_option("--format", o->format, "y4m or yuv (default: from the output name; Y4M for -)");
    sub->add_option("--flavour", o->flavour, "FGC SEI model: rdd5, ffmpeg (what FFmpeg >= 6.1 outputs: grain on the uncropped picture), vtm or vfgs")->capture_default_str();
    sub->add_flag("--no-grain", o->no_grain,
                  "write the decoded pictures without film grain (the same decoding and writing, no synthesis: "
                  "the baseline tools/bench-compare subtracts)");
    sub->add_option("--threads", o->threads,
                    "threads of the decoder and of grain synthesis per frame (0: all cores; the output is the same "
                    "for any count)")
        ->check(CLI::Range(0, filmgrain::kMaxThreads));
    sub->add_flag("--strict", o->strict,
                  "exit with status 3 when the input had damaged units (the output is still written complete); "
                  "without it damage is only warned about");
    sub->add_option("--first-frame", o->first_frame,
                    "write the output from this picture on; an elementary stream (H.264, H.265 Annex B; AV1 IVF, OBU) "
                    "is decoded from the random access point before it where that gives the same pictures and "
                    "grain (IDR / key frame; not into a persisting FGC SEI), anything else from its start")
        ->check(CLI::Range(0, 1 << 30));
    sub->add_option("--frames", o->frame_count, "write at most this many pictures (default: all)")
        ->check(CLI::Range(0, 1 << 30));
    sub->add_flag("--quiet,-q", o->quiet, "no progress or messages on stderr except errors and damaged units");
    sub->callback([o]() {
        if (int rc = run_decode(*o)) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli

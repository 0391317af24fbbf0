#include "libav/video_decoder.hpp"

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <utility>

#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"
#include "libav/grain_params_mapping.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/film_grain_params.h>
#include <libavutil/pixdesc.h>
}

namespace filmgrain::libav {
namespace {

// FFmpeg's and the decoders' own error messages ("[libdav1d] Error parsing OBU data") are
// collected instead of printed, and attached to the report of the unit they are about (so
// each damaged unit is one line naming it). av_log has one process-wide callback and decoder
// threads log too, hence the lock; the messages of several decoders alive at once would mix.
std::mutex g_log_mutex;
std::string g_log;  // complete messages, "; "-separated
std::string g_log_line;  // a message still being logged in pieces

void capture_log(void* avcl, int level, const char* fmt, va_list vl) {
    if (level > AV_LOG_ERROR) return;
    if (level <= AV_LOG_FATAL) av_log_default_callback(avcl, level, fmt, vl);
    char buf[512];
    va_list copy;
    va_copy(copy, vl);
    const int len = std::vsnprintf(buf, sizeof buf, fmt, copy);
    va_end(copy);
    if (len < 0) return;
    const AVClass* avc = avcl ? *static_cast<AVClass**>(avcl) : nullptr;
    std::lock_guard<std::mutex> lock(g_log_mutex);
    if (g_log_line.empty() && avc && avc->item_name) {
        const char* name = avc->item_name(avcl);
        if (name && *name && std::strcmp(name, "NULL") != 0) g_log_line = std::string(name) + ": ";
    }
    g_log_line += buf;
    if (g_log_line.empty() || g_log_line.back() != '\n') return;
    while (!g_log_line.empty() && (g_log_line.back() == '\n' || g_log_line.back() == ' ')) g_log_line.pop_back();
    // a flood of messages on one unit is cut short
    if (g_log.size() < 400) g_log += (g_log.empty() ? "" : "; ") + g_log_line;
    g_log_line.clear();
}

// The messages logged since the last call.
std::string take_log() {
    std::lock_guard<std::mutex> lock(g_log_mutex);
    std::string t;
    t.swap(g_log);
    return t;
}

std::string av_error_text(int err) {
    char buf[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, buf, sizeof buf);
    return buf;
}

// The error with what was logged about it: "Invalid data found when processing input:
// libdav1d: Error parsing OBU data".
std::string av_error_report(int err) {
    const std::string log = take_log();
    return av_error_text(err) + (log.empty() ? "" : ": " + log);
}

PixelFormat pixel_format_of(int fmt) {
    const AVPixFmtDescriptor* d = av_pix_fmt_desc_get(AVPixelFormat(fmt));
    const std::string name = d ? d->name : "unknown";
    if (!d || (d->flags & (AV_PIX_FMT_FLAG_BE | AV_PIX_FMT_FLAG_RGB | AV_PIX_FMT_FLAG_PAL | AV_PIX_FMT_FLAG_HWACCEL |
                           AV_PIX_FMT_FLAG_ALPHA)) ||
        !(d->flags & AV_PIX_FMT_FLAG_PLANAR || d->nb_components == 1) || d->comp[0].depth > 16)
        throw Error(ErrorCode::kUnsupported, "decoded pixel format '" + name +
                                                 "' is not planar little-endian YUV/gray (allowed gray, yuv420p, "
                                                 "yuv422p, yuv444p and their 10/12/16-bit le forms)");
    PixelFormat f;
    f.bit_depth = d->comp[0].depth;
    if (d->nb_components == 1)
        f.chroma = ChromaFormat::k400;
    else if (d->log2_chroma_w == 1 && d->log2_chroma_h == 1)
        f.chroma = ChromaFormat::k420;
    else if (d->log2_chroma_w == 1 && d->log2_chroma_h == 0)
        f.chroma = ChromaFormat::k422;
    else if (d->log2_chroma_w == 0 && d->log2_chroma_h == 0)
        f.chroma = ChromaFormat::k444;
    else
        throw Error(ErrorCode::kUnsupported, "decoded pixel format '" + name + "' has an unsupported chroma layout");
    return f;
}

std::string decode_error_flags_text(int flags) {
    std::string t;
    const auto add = [&t](const char* s) { t += (t.empty() ? "" : ", ") + std::string(s); };
    if (flags & FF_DECODE_ERROR_INVALID_BITSTREAM) add("invalid bitstream");
    if (flags & FF_DECODE_ERROR_MISSING_REFERENCE) add("missing reference");
    if (flags & FF_DECODE_ERROR_CONCEALMENT_ACTIVE) add("concealment active");
    if (flags & FF_DECODE_ERROR_DECODE_SLICES) add("slices not decoded");
    return t.empty() ? "flagged corrupt" : t;
}

// Errors that end the stream rather than spoil one packet: the file cannot be read.
bool is_read_error(const AVFormatContext* fmt, int err) {
    return err == AVERROR(EIO) || (fmt->pb && fmt->pb->error < 0 && fmt->pb->error != AVERROR_EOF);
}

// A decoder that reports this many errors in a row without being given a packet is not
// going to output anything more (FFmpeg's own decoders stop at 20 + threads while draining).
constexpr int kMaxErrorsWithoutInput = 64;
// Consecutive packets the demuxer cannot read before the rest of the input is given up.
constexpr int kMaxUnreadableInARow = 1024;

}  // namespace

std::string describe(const DamagedUnit& d) {
    std::string unit;
    if (d.kind == DamagedUnit::Kind::kConcealed) {
        unit = "frame " + std::to_string(d.frame);
        if (d.pts) unit += " (pts " + std::to_string(*d.pts) + ")";
    } else {
        unit = "packet " + std::to_string(d.packet);
        std::string where;
        if (d.pts) where = "pts " + std::to_string(*d.pts);
        if (d.byte_offset >= 0)
            where += (where.empty() ? "at byte " : ", byte ") + std::to_string(d.byte_offset);
        if (!where.empty()) unit += " (" + where + ")";
    }
    switch (d.kind) {
    case DamagedUnit::Kind::kUnreadable:
        return unit + ": the demuxer cannot read it (" + d.what + "); skipped";
    case DamagedUnit::Kind::kEndUnreadable:
        return unit + ": the demuxer cannot read it or anything after it (" + d.what +
               "); the rest of the input is skipped";
    case DamagedUnit::Kind::kTruncated:
        return unit + ": the demuxer flags it damaged" + (d.what.empty() ? " (truncated or corrupt)" : " (" + d.what + ")") +
               "; passed to the decoder";
    case DamagedUnit::Kind::kRefused:
        return unit + ": the decoder refused it (" + d.what + "); skipped";
    case DamagedUnit::Kind::kFailed:
        return unit + ": decoding failed (" + d.what +
               ") on its picture or on one of an earlier packet still in the decoder's frame threads; that "
               "picture is skipped";
    case DamagedUnit::Kind::kConcealed:
        return unit + ": the decoder concealed damage in it (" + d.what + "); output as concealed";
    }
    return unit + ": " + d.what;
}

struct VideoDecoder::State {
    std::unique_ptr<StreamWindowReader> window;  // outlives fmt, whose custom I/O it is
    AVFormatContext* fmt = nullptr;
    AVCodecContext* ctx = nullptr;
    AVPacket* pkt = nullptr;
    AVFrame* frame = nullptr;
    int stream = -1;
    bool flushing = false, done = false;
    std::string path;
    int64_t packets = 0;  // video packets met (read or unreadable): the next packet's index
    int64_t frames = 0;   // pictures output
    // the last packet given to the decoder
    int64_t sent_packet = -1, sent_pos = -1;
    std::optional<int64_t> sent_pts;
    int errors_without_input = 0, unreadable_in_a_row = 0;
    // What the parsers logged while avformat_find_stream_info read the first packets: those
    // packets come back from the demuxer's buffer without being parsed (and logged) again.
    std::string probe_log;
    int64_t damaged = 0, last_counted_packet = -1;
    unsigned kinds_reported = 0;  // DamagedUnit::Kind bits already reported for last_counted_packet
    std::function<void(const DamagedUnit&)> handler;

    ~State() {
        av_frame_free(&frame);
        av_packet_free(&pkt);
        avcodec_free_context(&ctx);
        avformat_close_input(&fmt);
    }
    void report(DamagedUnit::Kind kind, int64_t packet, std::optional<int64_t> pts, int64_t pos, std::string what) {
        DamagedUnit d;
        d.kind = kind;
        d.packet = packet;
        d.pts = pts;
        d.byte_offset = pos;
        d.frame = frames;
        d.what = std::move(what);
        if (kind == DamagedUnit::Kind::kConcealed) {
            d.frame = frames - 1;
            damaged++;
        } else {
            // each packet counts once, and each kind of report on it is made once (a decoder
            // with frame threads can report several failures after the same packet)
            if (packet != last_counted_packet) {
                damaged++;
                last_counted_packet = packet;
                kinds_reported = 0;
            }
            const unsigned bit = 1u << unsigned(kind);
            if (kinds_reported & bit) return;
            kinds_reported |= bit;
        }
        if (handler) handler(d);
    }
    void start_draining() {
        avcodec_send_packet(ctx, nullptr);
        flushing = true;
    }
    // Reads the next video packet and gives it to the decoder, or starts draining at the end
    // of the input. Packets the demuxer cannot read or the decoder refuses are reported.
    void feed();
};

void VideoDecoder::State::feed() {
    for (;;) {
        const int64_t pos = fmt->pb ? avio_tell(fmt->pb) : -1;
        int err = av_read_frame(fmt, pkt);
        if (err == AVERROR_EOF) {
            start_draining();
            return;
        }
        if (err < 0) {
            if (is_read_error(fmt, err))
                throw Error(ErrorCode::kIo, "cannot read '" + path + "' at byte " + std::to_string(pos) + ": " +
                                                av_error_report(err));
            // damaged data the demuxer cannot parse: go on after it while it gets anywhere
            const int64_t after = fmt->pb ? avio_tell(fmt->pb) : -1;
            const int64_t index = packets++;
            if (after <= pos || ++unreadable_in_a_row > kMaxUnreadableInARow) {
                report(DamagedUnit::Kind::kEndUnreadable, index, std::nullopt, pos, av_error_report(err));
                start_draining();
                return;
            }
            report(DamagedUnit::Kind::kUnreadable, index, std::nullopt, pos, av_error_report(err));
            continue;
        }
        if (pkt->stream_index != stream) {
            av_packet_unref(pkt);
            continue;
        }
        unreadable_in_a_row = 0;
        sent_packet = packets++;
        sent_pos = pkt->pos;
        sent_pts = pkt->pts != AV_NOPTS_VALUE ? std::optional<int64_t>(pkt->pts)
                 : pkt->dts != AV_NOPTS_VALUE ? std::optional<int64_t>(pkt->dts)
                                              : std::nullopt;
        // The AV1 / H.26x parsers behind the demuxer log syntax errors (obu_forbidden_bit out
        // of range...) about the packet just read; dav1d then drops such a unit without an
        // error, so this is the only sign of the picture that will be missing.
        std::string parse_log = take_log();
        if (!probe_log.empty()) {
            parse_log = "while probing the stream, on this packet or one read with it: " + probe_log +
                        (parse_log.empty() ? "" : "; " + parse_log);
            probe_log.clear();
        }
        if ((pkt->flags & AV_PKT_FLAG_CORRUPT) || !parse_log.empty())
            report(DamagedUnit::Kind::kTruncated, sent_packet, sent_pts, sent_pos, parse_log);
        err = avcodec_send_packet(ctx, pkt);
        av_packet_unref(pkt);
        errors_without_input = 0;
        // libavcodec decodes as much as it can within avcodec_send_packet, so an error here
        // is this packet's; the packet is consumed either way
        if (err < 0 && err != AVERROR(EAGAIN) && err != AVERROR_EOF)
            report(DamagedUnit::Kind::kRefused, sent_packet, sent_pts, sent_pos, av_error_report(err));
        return;
    }
}

VideoDecoder::VideoDecoder(const std::string& path, int threads, bool uncropped, std::optional<StreamWindow> window)
    : s_(std::make_unique<State>()) {
    av_log_set_level(AV_LOG_ERROR);
    av_log_set_callback(capture_log);
    take_log();
    s_->path = path;
    if (window) {
        s_->window = std::make_unique<StreamWindowReader>(path, std::move(*window));
        s_->fmt = avformat_alloc_context();
        if (!s_->fmt) throw Error(ErrorCode::kOutOfMemory, "avformat_alloc_context failed");
        s_->fmt->pb = s_->window->io();
        s_->fmt->flags |= AVFMT_FLAG_CUSTOM_IO;
    }
    // the name still guides probing by its extension when the input is a window
    int err = avformat_open_input(&s_->fmt, path.c_str(), nullptr, nullptr);
    if (err < 0) throw Error(ErrorCode::kIo, "cannot open '" + path + "': " + av_error_report(err));
    // As ffmpeg does, a probe that fails on damaged first packets is not the end when the
    // streams are known: decoding reports (and skips) those packets one by one.
    if ((err = avformat_find_stream_info(s_->fmt, nullptr)) < 0 && s_->fmt->nb_streams == 0)
        throw Error(ErrorCode::kIo, "cannot read the streams of '" + path + "': " + av_error_report(err));
    s_->probe_log = take_log();
    s_->stream = av_find_best_stream(s_->fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    if (s_->stream < 0) throw Error(ErrorCode::kIo, "'" + path + "' has no video stream");
    AVStream* st = s_->fmt->streams[s_->stream];
    const AVCodec* codec = nullptr;
    if (st->codecpar->codec_id == AV_CODEC_ID_AV1) {
        // FFmpeg's native AV1 decoder needs hardware; these two decode in software and
        // export the grain parameters
        codec = avcodec_find_decoder_by_name("libdav1d");
        if (!codec) codec = avcodec_find_decoder_by_name("libaom-av1");
    } else {
        codec = avcodec_find_decoder(st->codecpar->codec_id);
    }
    if (!codec)
        throw Error(ErrorCode::kUnsupported,
                    "no decoder for codec '" + std::string(avcodec_get_name(st->codecpar->codec_id)) + "'");
    s_->ctx = avcodec_alloc_context3(codec);
    if (!s_->ctx) throw Error(ErrorCode::kOutOfMemory, "avcodec_alloc_context3 failed");
    if ((err = avcodec_parameters_to_context(s_->ctx, st->codecpar)) < 0)
        throw Error(ErrorCode::kIo, "codec parameters: " + av_error_report(err));
    s_->ctx->export_side_data |= AV_CODEC_EXPORT_DATA_FILM_GRAIN;
    if (threads < 0 || threads > kMaxThreads)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("threads", threads, 0, kMaxThreads));
    s_->ctx->thread_count = threads;
    if (uncropped) s_->ctx->apply_cropping = 0;
    if ((err = avcodec_open2(s_->ctx, codec, nullptr)) < 0)
        throw Error(ErrorCode::kUnsupported, "cannot open decoder '" + std::string(codec->name) + "': " + av_error_report(err));
    s_->pkt = av_packet_alloc();
    s_->frame = av_frame_alloc();
    if (!s_->pkt || !s_->frame) throw Error(ErrorCode::kOutOfMemory, "av_packet_alloc/av_frame_alloc failed");

    desc_.codec_name = avcodec_get_name(st->codecpar->codec_id);
    desc_.decoder_name = codec->name;
    desc_.format_name = s_->fmt->iformat ? s_->fmt->iformat->name : "";
    desc_.width = st->codecpar->width;
    desc_.height = st->codecpar->height;
    AVRational rate = st->avg_frame_rate.num > 0 ? st->avg_frame_rate : st->r_frame_rate;
    if (rate.num > 0 && rate.den > 0) {
        desc_.fps_num = rate.num;
        desc_.fps_den = rate.den;
    }
    if (st->nb_frames > 0)
        desc_.frames_estimate = st->nb_frames;
    else if (s_->fmt->duration > 0 && rate.num > 0 && rate.den > 0)
        desc_.frames_estimate = int64_t(double(s_->fmt->duration) / AV_TIME_BASE * rate.num / rate.den + 0.5);
    take_log();  // what probing the stream logged: its packets are decoded (and reported) again
}

VideoDecoder::~VideoDecoder() = default;

void VideoDecoder::on_damage(std::function<void(const DamagedUnit&)> handler) { s_->handler = std::move(handler); }

int64_t VideoDecoder::damaged_units() const { return s_->damaged; }

bool VideoDecoder::next(DecodedFrame& out, bool copy_picture) {
    State& s = *s_;
    for (;;) {
        if (s.done) return false;
        const int err = avcodec_receive_frame(s.ctx, s.frame);
        if (err >= 0) break;
        if (err == AVERROR_EOF) {
            s.done = true;
            return false;
        }
        if (err != AVERROR(EAGAIN)) {
            // a picture the decoder gives up on: it is not output, decoding goes on
            if (++s.errors_without_input > kMaxErrorsWithoutInput)
                throw Error(ErrorCode::kMalformedPayload,
                            "the decoder keeps failing without taking input after packet " +
                                std::to_string(s.sent_packet) + ": " + av_error_report(err));
            s.report(DamagedUnit::Kind::kFailed, s.sent_packet, s.sent_pts, s.sent_pos, av_error_report(err));
            continue;
        }
        // needs input
        if (s.flushing) {
            s.done = true;
            return false;
        }
        s.feed();
    }
    AVFrame* f = s.frame;
    const PixelFormat pf = pixel_format_of(f->format);
    if (out.picture.width() != f->width || out.picture.height() != f->height || out.picture.format().chroma != pf.chroma ||
        out.picture.format().bit_depth != pf.bit_depth)
        out.picture = FrameBuffer(f->width, f->height, pf);
    FrameView decoded;
    decoded.format = pf.chroma;
    decoded.bit_depth = pf.bit_depth;
    decoded.width = f->width;
    decoded.height = f->height;
    for (int p = 0; p < decoded.plane_count(); p++) {
        decoded.planes[p].data = f->data[p];
        decoded.planes[p].stride = f->linesize[p];
        decoded.planes[p].width = plane_width(pf.chroma, p, f->width);
        decoded.planes[p].height = plane_height(pf.chroma, p, f->height);
    }
    out.decoded = decoded;
    if (copy_picture) copy_frame(decoded, out.picture.view());
    out.av1.reset();
    out.fgc.reset();
    out.seed = 0;
    out.matrix_coefficients = f->colorspace == AVCOL_SPC_UNSPECIFIED ? 2 : int(f->colorspace);
    out.index = s.frames++;
    out.crop_left = int(f->crop_left);
    out.crop_top = int(f->crop_top);
    out.crop_right = int(f->crop_right);
    out.crop_bottom = int(f->crop_bottom);
    out.pts = f->best_effort_timestamp != AV_NOPTS_VALUE ? std::optional<int64_t>(f->best_effort_timestamp)
                                                         : std::nullopt;
    // what was logged while it was decoded is about this picture (or about nothing lost)
    const std::string log = take_log();
    if ((f->flags & AV_FRAME_FLAG_CORRUPT) || f->decode_error_flags)
        s.report(DamagedUnit::Kind::kConcealed, -1, out.pts, -1,
                 decode_error_flags_text(f->decode_error_flags) + (log.empty() ? "" : ": " + log));
    if (const AVFrameSideData* sd = av_frame_get_side_data(f, AV_FRAME_DATA_FILM_GRAIN_PARAMS)) {
        const auto* fgp = reinterpret_cast<const AVFilmGrainParams*>(sd->data);
        out.seed = fgp->seed;
        if (fgp->type == AV_FILM_GRAIN_PARAMS_AV1) {
            out.av1 = av1_params_from_libav(*fgp);
        } else if (fgp->type == AV_FILM_GRAIN_PARAMS_H274) {
            out.fgc = fgc_params_from_libav(*fgp);
            out.fgc_codec = s.ctx->codec_id == AV_CODEC_ID_H264 ? FgcCodec::kAvc
                          : s.ctx->codec_id == AV_CODEC_ID_VVC ? FgcCodec::kVvc
                                                                         : FgcCodec::kHevc;
        }
    }
    // The frame stays referenced until the next call (avcodec_receive_frame unreferences
    // it first), so that `decoded` stays valid.
    return true;
}

}  // namespace filmgrain::libav

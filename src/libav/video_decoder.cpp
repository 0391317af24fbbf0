#include "libav/video_decoder.hpp"

#include <cstring>

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

std::string av_error_text(int err) {
    char buf[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, buf, sizeof buf);
    return buf;
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

}  // namespace

struct VideoDecoder::State {
    AVFormatContext* fmt = nullptr;
    AVCodecContext* ctx = nullptr;
    AVPacket* pkt = nullptr;
    AVFrame* frame = nullptr;
    int stream = -1;
    bool flushing = false, done = false;
    ~State() {
        av_frame_free(&frame);
        av_packet_free(&pkt);
        avcodec_free_context(&ctx);
        avformat_close_input(&fmt);
    }
};

VideoDecoder::VideoDecoder(const std::string& path, int threads) : s_(std::make_unique<State>()) {
    av_log_set_level(AV_LOG_ERROR);
    int err = avformat_open_input(&s_->fmt, path.c_str(), nullptr, nullptr);
    if (err < 0) throw Error(ErrorCode::kIo, "cannot open '" + path + "': " + av_error_text(err));
    if ((err = avformat_find_stream_info(s_->fmt, nullptr)) < 0)
        throw Error(ErrorCode::kIo, "cannot read the streams of '" + path + "': " + av_error_text(err));
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
        throw Error(ErrorCode::kIo, "codec parameters: " + av_error_text(err));
    s_->ctx->export_side_data |= AV_CODEC_EXPORT_DATA_FILM_GRAIN;
    if (threads < 0) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("threads", threads, 0, 1 << 16));
    s_->ctx->thread_count = threads;
    if ((err = avcodec_open2(s_->ctx, codec, nullptr)) < 0)
        throw Error(ErrorCode::kUnsupported, "cannot open decoder '" + std::string(codec->name) + "': " + av_error_text(err));
    s_->pkt = av_packet_alloc();
    s_->frame = av_frame_alloc();
    if (!s_->pkt || !s_->frame) throw Error(ErrorCode::kOutOfMemory, "av_packet_alloc/av_frame_alloc failed");

    desc_.codec_name = avcodec_get_name(st->codecpar->codec_id);
    desc_.decoder_name = codec->name;
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
}

VideoDecoder::~VideoDecoder() = default;

bool VideoDecoder::next(DecodedFrame& out, bool copy_picture) {
    State& s = *s_;
    for (;;) {
        if (s.done) return false;
        int err = avcodec_receive_frame(s.ctx, s.frame);
        if (err == AVERROR_EOF) {
            s.done = true;
            return false;
        }
        if (err >= 0) break;
        if (err != AVERROR(EAGAIN)) throw Error(ErrorCode::kMalformedPayload, "decoding failed: " + av_error_text(err));
        // needs input
        if (s.flushing) {
            s.done = true;
            return false;
        }
        for (;;) {
            err = av_read_frame(s.fmt, s.pkt);
            if (err < 0) {
                avcodec_send_packet(s.ctx, nullptr);
                s.flushing = true;
                break;
            }
            if (s.pkt->stream_index != s.stream) {
                av_packet_unref(s.pkt);
                continue;
            }
            err = avcodec_send_packet(s.ctx, s.pkt);
            av_packet_unref(s.pkt);
            if (err < 0 && err != AVERROR(EAGAIN))
                throw Error(ErrorCode::kMalformedPayload, "decoding failed: " + av_error_text(err));
            break;
        }
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

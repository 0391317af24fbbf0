// Decoding any file libavformat/libavcodec read, with film grain exported instead of
// applied (AV_CODEC_EXPORT_DATA_FILM_GRAIN), one frame at a time in output order.
// AV1 goes through libdav1d (or libaom-av1 when libdav1d is missing), the decoders that
// export AV1 grain; H.264/H.265 through FFmpeg's own decoders, which export the FGC SEI
// in force for each frame.
//
// Damaged input is decoded on, as ffmpeg and dav1d do: a packet the demuxer cannot read or
// the decoder refuses is skipped (the decoder simply outputs no picture for it) and reported
// to the damage handler with its index; only errors that end the stream (I/O, no video
// stream, no decoder, a pixel format the library cannot take) are thrown.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"
#include "libav/stream_window.hpp"

namespace filmgrain::libav {

struct DecodedFrame {
    FrameBuffer picture;  // cropped (unless the decoder was opened uncropped), packed planes
    // The decoder's own picture (its planes, cropped), valid until the next call of next().
    // `picture` holds a copy of it unless next() was asked not to copy, in which case
    // `picture` only has the right size and format: a caller that adds grain writes it
    // there straight from `decoded`, so the synthesis is the copy.
    FrameView decoded;
    // Exported grain: AV1 parameters (grain_seed from the frame) or an FGC SEI with the
    // seed FFmpeg derived for it (H.265: the picture's POC; H.264: pic_offset =
    // POC + (idr_pic_id << 5), SMPTE RDD 5).
    std::optional<Av1FilmGrainParams> av1;
    std::optional<FgcParams> fgc;
    FgcCodec fgc_codec = FgcCodec::kHevc;
    uint64_t seed = 0;
    int matrix_coefficients = 2;  // H.273 MatrixCoefficients of the frame (2: unspecified)
    int64_t index = 0;            // 0-based, in the order the decoder outputs pictures
    // The conformance window, when the decoder was opened uncropped: `picture` and `decoded`
    // are the coded picture and these are the samples to crop from each side (luma).
    int crop_left = 0, crop_top = 0, crop_right = 0, crop_bottom = 0;
    std::optional<int64_t> pts;   // best-effort presentation timestamp, in the stream's time base
};

// A unit of the input that was skipped or output concealed.
struct DamagedUnit {
    enum class Kind {
        kUnreadable,  // the demuxer could not read the packet: skipped
        kEndUnreadable,  // ... and cannot read past it: the rest of the input is skipped
        kTruncated,   // the demuxer read it but flags it truncated/corrupt, or its parser logged errors
                      // about it (a damaged OBU header): passed to the decoder
        kRefused,     // the decoder refused the packet (avcodec_send_packet): skipped
        kFailed,      // decoding failed while receiving a picture, up to this packet: that picture is skipped
        kConcealed,   // the decoder output the picture with damage concealed (AV_FRAME_FLAG_CORRUPT,
                      // decode_error_flags)
    };
    Kind kind = Kind::kRefused;
    // The video packet (0-based, in file order; an AV1 temporal unit for IVF, OBU and Annex B
    // input). For kFailed: the last packet given to the decoder (a decoder with frame threads
    // can report a frame's failure a few packets late). For kConcealed: the picture's packet
    // is not known, `frame` names it.
    int64_t packet = -1;
    std::optional<int64_t> pts;  // of the packet (kConcealed: of the picture), stream time base
    int64_t byte_offset = -1;    // where the packet (or the unreadable data) starts, -1 unknown
    int64_t frame = 0;           // kConcealed: the picture's output index; otherwise pictures output so far
    std::string what;            // what FFmpeg said
};

// "packet 4 (pts 4, byte 1543): the decoder refused it (Invalid data found when processing
// input); skipped" -- one line naming the unit, the cause and what was done.
std::string describe(const DamagedUnit& d);

struct StreamDescription {
    std::string codec_name, decoder_name;
    std::string format_name;  // libavformat's demuxer ("hevc", "ivf", "mov,mp4,...")
    int width = 0, height = 0;
    int fps_num = 25, fps_den = 1;
    int64_t frames_estimate = 0;  // 0 when the container does not tell
};

class VideoDecoder {
public:
    // threads: the decoder's own threads (AVCodecContext::thread_count; 0 = libavcodec's
    // automatic choice, every core). Throws Error(kIo / kUnsupported).
    // uncropped: output the coded picture and give the conformance window apart
    // (AVCodecContext::apply_cropping = 0), for grain added before the crop as FFmpeg does.
    // window: decode a window of the file instead (stream_window.hpp); pictures are indexed
    // from the window's first.
    explicit VideoDecoder(const std::string& path, int threads = 0, bool uncropped = false,
                          std::optional<StreamWindow> window = std::nullopt);
    ~VideoDecoder();
    VideoDecoder(const VideoDecoder&) = delete;
    VideoDecoder& operator=(const VideoDecoder&) = delete;

    const StreamDescription& description() const { return desc_; }
    // false at the end of the stream. Damaged packets are skipped and reported to the damage
    // handler; throws Error only for what ends the stream (a read error, an unsupported
    // pixel format, a decoder that keeps failing without taking input).
    bool next(DecodedFrame& frame, bool copy_picture = true);

    // Called for each damaged unit as it is met, from within next().
    void on_damage(std::function<void(const DamagedUnit&)> handler);
    // Damaged units so far: packets skipped or flagged (each packet once, however many
    // errors it caused) plus concealed pictures.
    int64_t damaged_units() const;

private:
    struct State;
    std::unique_ptr<State> s_;
    StreamDescription desc_;
};

}  // namespace filmgrain::libav

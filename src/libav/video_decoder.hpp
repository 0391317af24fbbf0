// Decoding any file libavformat/libavcodec read, with film grain exported instead of
// applied (AV_CODEC_EXPORT_DATA_FILM_GRAIN), one frame at a time in output order.
// AV1 goes through libdav1d (or libaom-av1 when libdav1d is missing), the decoders that
// export AV1 grain; H.264/H.265 through FFmpeg's own decoders, which export the FGC SEI
// in force for each frame.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::libav {

struct DecodedFrame {
    FrameBuffer picture;  // cropped, packed planes
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
};

struct StreamDescription {
    std::string codec_name, decoder_name;
    int width = 0, height = 0;
    int fps_num = 25, fps_den = 1;
    int64_t frames_estimate = 0;  // 0 when the container does not tell
};

class VideoDecoder {
public:
    // threads: the decoder's own threads (AVCodecContext::thread_count; 0 = libavcodec's
    // automatic choice, every core). Throws Error(kIo / kUnsupported).
    explicit VideoDecoder(const std::string& path, int threads = 0);
    ~VideoDecoder();
    VideoDecoder(const VideoDecoder&) = delete;
    VideoDecoder& operator=(const VideoDecoder&) = delete;

    const StreamDescription& description() const { return desc_; }
    // false at the end of the stream; throws Error on a decoding failure.
    bool next(DecodedFrame& frame, bool copy_picture = true);

private:
    struct State;
    std::unique_ptr<State> s_;
    StreamDescription desc_;
};

}  // namespace filmgrain::libav

// What `decode` and `verify` both do with pictures libav decoded with their grain exported:
// read from the elementary stream what FFmpeg 5.1 does not export (AFGS1 payloads; for verify
// also POC / idr_pic_id and the AV1 frame-header state), pick a picture's AFGS1 set, and hand
// a picture's grain to the session.
#pragma once
#ifdef FILMGRAIN_HAVE_LIBAV
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "filmgrain/session.hpp"
#include "libav/video_decoder.hpp"
#include "metadata/afgs1.hpp"

namespace filmgrain::cli {

struct StreamMetadata {
    bitstream::StreamScan scan;
    std::vector<const bitstream::AccessUnit*> units;  // in output order: units[frame.index]
    std::vector<std::optional<Afgs1Payload>> afgs1;   // per output picture; empty without AFGS1
};

// The elementary stream's scan, for the codecs the scanner reads (h264, hevc, vvc, av1 as
// libav names them). Containers the scanner does not read (MP4, Matroska...) are left to
// libav: empty. Damaged AFGS1 payloads are handed to `warn`.
StreamMetadata read_stream_metadata(const std::string& path, const std::string& codec_name,
                                    const std::function<void(const std::string&)>& warn);

// False when the file's bytes nowhere hold AFGS1's ITU-T T.35 header (B5 58 90 01): then the
// stream carries no AFGS1 payload, in SEI (emulation prevention never splits those four
// bytes, none of which is zero) or in metadata OBUs. `decode` skips the whole-stream scan
// for such files: it costs about 0.1 ms per 1080p picture, which libav's exports make
// unnecessary. True when the file cannot be read (the scan then says why).
bool may_carry_afgs1(const std::string& path);

// AFGS1 in SEI or metadata OBUs (FFmpeg 5.1 neither applies nor exports it): a picture without
// exported grain takes the set AFGS1 7.3 selects for its visible width x height. An AV1
// frame's own film grain, which FFmpeg exports, takes precedence.
void take_afgs1_grain(libav::DecodedFrame& frame, const std::vector<std::optional<Afgs1Payload>>& afgs1, int width,
                      int height);

// Hands `session` the grain exported with the picture (AV1 parameters resolved as FFmpeg
// exports them; FGC with FFmpeg's seed, the RDD 5 pic_offset, as the picture's POC with
// idr_pic_id 0) and returns the FrameInfo to apply it with; nullopt when it has none.
std::optional<FrameInfo> hand_exported_grain(Session& session, const libav::DecodedFrame& frame);

}  // namespace filmgrain::cli
#endif

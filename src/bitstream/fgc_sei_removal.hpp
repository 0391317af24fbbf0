// Takes the FGC SEI messages (payloadType 19) out of an H.26x access unit before it reaches
// a decoder that would apply them itself. FFmpeg's H.264 and H.265 decoders add their own
// H.274 grain whenever the caller does not ask for the parameters to be exported, and
// GStreamer's avdec_h264 / avdec_h265 cannot ask: grain added after such a decoder from the
// same SEI would be added twice. Everything else in the access unit is kept as it is.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "bitstream/stream_scan.hpp"

namespace filmgrain::bitstream {

// The Annex B bytes with every FGC SEI message removed from their SEI NAL units (the NAL
// header kept, the other messages re-coded in order); an SEI NAL unit left without messages
// is dropped with its start code. nullopt when there is no FGC SEI message: the input is
// what to pass on.
std::optional<std::vector<uint8_t>> remove_fgc_sei(StreamCodec codec, const uint8_t* data, std::size_t size);

}  // namespace filmgrain::bitstream

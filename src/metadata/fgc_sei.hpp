// The film_grain_characteristics() SEI payload (payloadType 19): H.264 D.1.21 (ends with
// repetition_period ue(v)), H.265 D.2.20 and H.274/VSEI 8.5 (end with persistence_flag).
// The payload is the SEI message body only: no NAL header, no emulation prevention.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "filmgrain/fgc_params.hpp"

namespace filmgrain {

// Throws Error(kMalformedPayload) naming the syntax element on truncation or bad codes.
FgcParams parse_fgc_sei_payload(const uint8_t* data, std::size_t size, FgcCodec codec);
inline FgcParams parse_fgc_sei_payload(const std::vector<uint8_t>& v, FgcCodec codec) {
    return parse_fgc_sei_payload(v.data(), v.size(), codec);
}

std::vector<uint8_t> write_fgc_sei_payload(const FgcParams& params, FgcCodec codec);

FgcCodec parse_fgc_codec(const std::string& name);  // "avc"|"h264", "hevc"|"h265", "vvc"|"h266"

}  // namespace filmgrain

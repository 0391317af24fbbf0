// Where decoding of a range of a coded stream's pictures can start, so that a range (a
// distributed task, `decode --first-frame`) decodes from the random access point before it
// instead of from the stream's start, and still gives what decoding from the start gives.
//
// That is the pictures, and the grain libavcodec exports with them. libavcodec's H.264 and
// H.265 decoders keep the last FGC SEI across pictures: an SEI sets it (present unless
// cancelled), and after each picture that takes it, it stays only when
// film_grain_characteristics_persistence_flag (H.265) or ..._repetition_period != 0
// (H.264) says so; nothing else resets it, not even an IDR. A decoder started at an IDR
// begins without it, so the IDR is a restart point only when it brings its own FGC SEI or
// no FGC SEI is in force there. AV1 grain is in each frame header (a shown key frame
// refreshes every reference slot), and AFGS1 is read from the whole stream's scan.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "bitstream/stream_scan.hpp"

namespace filmgrain::bitstream {

struct DecodeRestart {
    int unit = 0;               // the access unit (decode order) decoding starts at
    int64_t output_before = 0;  // pictures output before it: the first picture it gives
    // What a decoder starting there must read first: the IVF file header (bytes [0, n)) or
    // the H.26x parameter set NAL units before it, as (offset after the start code, size).
    std::size_t ivf_header_bytes = 0;
    std::vector<std::pair<std::size_t, std::size_t>> parameter_sets;
    std::size_t offset = 0;     // then the file from here (the unit's first byte)
};

// Every restart point past the start whose first output picture is at or before
// `last_output`, in stream order (without their parameter sets); none past damaged units (a
// decoder may drop their pictures, so that the counts would not hold).
std::vector<DecodeRestart> decode_restart_points(const StreamScan& scan, int64_t last_output = std::numeric_limits<int64_t>::max());

// The latest restart point whose first output picture is at or before `first_output`;
// nullopt when there is none past the start.
std::optional<DecodeRestart> plan_decode_restart(const StreamScan& scan, int64_t first_output);

}  // namespace filmgrain::bitstream

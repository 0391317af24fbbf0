// Writes metadata into existing coded streams: SEI NAL units into Annex-B H.26x streams
// and ITU-T T.35 metadata OBUs into AV1 streams. Used to build test streams from encoder
// output (x264, x265, aomenc) with this project's own FGC SEI / T.35 payloads.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "bitstream/sei_messages.hpp"
#include "bitstream/stream_scan.hpp"

namespace filmgrain::bitstream {

// One SEI NAL unit (header for layer 0, temporal id 0) with the given messages, Annex-B
// framed with emulation prevention. `suffix` needs H.265 or H.266.
std::vector<uint8_t> sei_nal_unit(StreamCodec codec, bool suffix, const std::vector<SeiMessage>& messages);

// For each access unit (decode order index), the prefix SEI messages to put before its
// first VCL NAL unit and the suffix SEI messages to put after its last one.
struct AccessUnitSei {
    std::vector<SeiMessage> prefix, suffix;
};
std::vector<uint8_t> insert_sei(const std::vector<uint8_t>& stream, StreamCodec codec,
                                const std::function<AccessUnitSei(int au_index)>& sei_for);

// For each temporal unit, T.35 payloads (country code first) to carry as metadata OBUs
// right after its temporal delimiter. IVF and low-overhead streams; output has the
// input's container.
std::vector<uint8_t> insert_av1_t35(const std::vector<uint8_t>& stream,
                                    const std::function<std::vector<std::vector<uint8_t>>(int tu_index)>& t35_for);

}  // namespace filmgrain::bitstream

// Annex-B byte streams (H.264 Annex B, H.265 Annex B, H.266 Annex B): start-code
// framing and the emulation-prevention bytes that keep start codes out of NAL payloads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace filmgrain::bitstream {

struct NalSpan {
    std::size_t offset = 0;  // of the first NAL header byte in the stream
    std::size_t size = 0;    // without the start code and without trailing_zero_8bits
};

struct AnnexBSplit {
    std::vector<NalSpan> nals;
    std::vector<std::string> warnings;  // bytes before the first start code, empty NAL units
};

// Every NAL unit between 0x000001 start codes; zero bytes before a start code are
// leading/trailing_zero_8bits (B.2) and belong to no NAL unit. `base`: the position of
// data[0] in the stream, for the byte positions warnings give.
AnnexBSplit split_annexb(const uint8_t* data, std::size_t size, std::size_t base = 0);

// NAL unit payload -> RBSP: drops each emulation_prevention_three_byte (a 0x03 after two
// zero bytes, H.264 7.4.1 / H.265 7.4.2 / H.266 7.4.2.1).
std::vector<uint8_t> remove_emulation_prevention(const uint8_t* data, std::size_t size);

// RBSP -> NAL payload: inserts 0x03 after every two zero bytes followed by a byte <= 3,
// and after a final zero byte so that the NAL unit never ends in 0x00.
std::vector<uint8_t> add_emulation_prevention(const uint8_t* rbsp, std::size_t size);

// A start code, the NAL header bytes as given, then the escaped RBSP.
std::vector<uint8_t> annexb_nal_unit(const std::vector<uint8_t>& header, const std::vector<uint8_t>& rbsp);

}  // namespace filmgrain::bitstream

// sei_rbsp(): a list of sei_message()s, each a payloadType / payloadSize pair coded as
// runs of 0xFF bytes (H.264 7.3.2.3, H.265 7.3.5, H.266 7.3.6 / H.274 clause 7).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace filmgrain::bitstream {

inline constexpr int kSeiPayloadT35 = 4;   // user_data_registered_itu_t_t35
inline constexpr int kSeiPayloadFgc = 19;  // film_grain_characteristics

struct SeiMessage {
    int payload_type = 0;
    std::vector<uint8_t> payload;  // payloadSize bytes, RBSP (no emulation prevention)
};

struct SeiParse {
    std::vector<SeiMessage> messages;
    std::vector<std::string> warnings;  // a message running past the NAL unit, and so on
};

// `rbsp` starts after the NAL unit header. Messages before a damaged one are kept.
SeiParse parse_sei_rbsp(const std::vector<uint8_t>& rbsp);

// sei_message()s followed by rbsp_trailing_bits(), ready for annexb_nal_unit().
std::vector<uint8_t> build_sei_rbsp(const std::vector<SeiMessage>& messages);

// ITU-T T.35 prefix of a registered user data payload (T.35 itself; H.274 8.3).
struct T35Payload {
    int country_code = 0;            // itu_t_t35_country_code
    int country_code_extension = -1; // present when country_code == 0xFF
    int provider_code = -1;          // the first two bytes after the country code(s), when present
    int provider_oriented_code = -1; // the byte after, when present
    std::vector<uint8_t> bytes;      // everything after the country code(s)
};

// The T.35 bytes from the country code on, as AFGS1's metadata_aom_itu_t_t35() starts.
std::vector<uint8_t> t35_bytes(const T35Payload& t);

// Returns false (and leaves `out` untouched) on an empty payload.
bool parse_t35_payload(const uint8_t* data, std::size_t size, T35Payload& out);

// AFGS1 (AOMedia film grain synthesis 1) registration: United States, AOMedia, 0x0001.
inline bool is_afgs1_t35(const T35Payload& t) {
    return t.country_code == 0xB5 && t.provider_code == 0x5890 && t.provider_oriented_code == 0x01;
}

}  // namespace filmgrain::bitstream

// AV1 OBU streams (AV1 5.3 obu_header, 4.10.5 leb128) in the three containers found in
// files: IVF (one temporal unit per IVF frame), the low-overhead bitstream format
// (Section 5: OBUs with obu_size, temporal units started by a temporal delimiter) and
// Annex B (temporal_unit / frame_unit / obu_length size prefixes).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace filmgrain::bitstream {

enum class Av1Container { kIvf, kLowOverhead, kAnnexB };
const char* av1_container_name(Av1Container c);

enum Av1ObuType : int {
    kObuSequenceHeader = 1,
    kObuTemporalDelimiter = 2,
    kObuFrameHeader = 3,
    kObuTileGroup = 4,
    kObuMetadata = 5,
    kObuFrame = 6,
    kObuRedundantFrameHeader = 7,
    kObuTileList = 8,
    kObuPadding = 15,
};
inline constexpr int kMetadataTypeItutT35 = 4;  // AV1 6.7.1 metadata_type

struct Av1Obu {
    int type = 0;
    int temporal_id = 0, spatial_id = 0;
    std::size_t offset = 0;        // of the OBU header in the file
    std::vector<uint8_t> payload;  // obu_size bytes after the header
};

struct Av1TemporalUnit {
    std::size_t offset = 0;
    std::optional<int64_t> pts;  // IVF frame header timestamp
    std::vector<Av1Obu> obus;
    std::vector<std::string> warnings;
};

struct Av1Stream {
    Av1Container container = Av1Container::kLowOverhead;
    std::vector<Av1TemporalUnit> units;
    std::vector<std::string> warnings;  // container-level damage (truncated IVF frame and so on)
};

// Reads an unsigned leb128 (at most 8 bytes, value < 2^32 as AV1 4.10.5 requires).
bool read_leb128(const uint8_t* data, std::size_t size, std::size_t& pos, uint64_t& value);
void write_leb128(std::vector<uint8_t>& out, uint64_t value);

bool looks_like_ivf(const uint8_t* data, std::size_t size);
// A low-overhead stream starts with a temporal delimiter OBU with obu_has_size_field = 1.
bool looks_like_av1_low_overhead(const uint8_t* data, std::size_t size);
// An Annex B stream's first temporal unit parses as sizes nested consistently.
bool looks_like_av1_annexb(const uint8_t* data, std::size_t size);

Av1Stream parse_av1_stream(const uint8_t* data, std::size_t size, Av1Container container);

// parse_av1_stream of an IVF stream that arrives a run of bytes at a time: push() gives the
// frames each run completes, finish() what a truncated end leaves and the container-level
// warnings. Offsets and warnings are the whole-stream parse's; only an unfinished frame is
// held.
class IvfStreamReader {
public:
    std::vector<Av1TemporalUnit> push(const uint8_t* data, std::size_t size);
    Av1Stream finish();

private:
    std::vector<uint8_t> held_;
    std::size_t held_base_ = 0;  // stream position of held_[0]
    std::size_t pos_ = 0;        // the next frame header in held_
    bool header_read_ = false;
};

// metadata_obu() payload: metadata_type, then for ITU-T T.35 the T.35 bytes without the
// OBU's trailing bits. Returns false when the OBU is not T.35 metadata or is damaged.
bool av1_metadata_t35(const Av1Obu& obu, std::vector<uint8_t>& t35, std::string* warning);

// An OBU with obu_has_size_field = 1 (Section 5 form), for writing test streams.
std::vector<uint8_t> av1_obu_bytes(int type, const std::vector<uint8_t>& payload);
// A metadata OBU payload carrying T.35 bytes (country code first), with trailing bits.
std::vector<uint8_t> av1_t35_metadata_payload(const std::vector<uint8_t>& t35);

}  // namespace filmgrain::bitstream

// Finds every film grain payload in a coded stream and the access unit (H.26x) or
// temporal unit (AV1) it belongs to: FGC SEI messages (payloadType 19) and ITU-T T.35
// registered user data (SEI payloadType 4, AV1 metadata OBUs). Damage in one unit is a
// warning on that unit; scanning goes on with the next one.
#pragma once
#include <cstdint>
#include <memory>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bitstream/av1_frame_header.hpp"
#include "bitstream/av1_obu.hpp"
#include "bitstream/av1_sequence_header.hpp"
#include "bitstream/nal_header.hpp"
#include "filmgrain/av1_params.hpp"
#include "bitstream/sei_messages.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::bitstream {

enum class StreamCodec { kH264, kH265, kH266, kAv1 };
const char* stream_codec_name(StreamCodec c);  // "h264", "h265", "h266", "av1"
StreamCodec parse_stream_codec(const std::string& name);  // also avc/hevc/vvc; throws Error
// The FGC SEI syntax variant of a NAL-unit codec (H.264: repetition period; else persistence).
FgcCodec fgc_codec(StreamCodec c);
// The NAL unit header syntax of h264, h265 or h266; throws Error(kInvalidArgument) for av1.
NalCodec nal_codec(StreamCodec c);

// From the first bytes (IVF/OBU layouts, NAL header patterns), then the file name's
// extension; nullopt when neither tells.
std::optional<StreamCodec> detect_stream_codec(const uint8_t* data, std::size_t size, const std::string& path);

// The name of a multiplexed container the first bytes show ("Matroska/WebM", "MP4/QuickTime",
// "MPEG transport stream", "AVI", "FLV"), nullptr for anything else. The scanner reads
// elementary streams only; a container's boxes and packet headers would otherwise be
// misread as start codes or OBUs and reported as damaged units.
const char* container_name(const uint8_t* data, std::size_t size);

struct FoundFgc {
    bool suffix = false;           // in a suffix SEI NAL unit
    std::vector<uint8_t> payload;  // the payloadType 19 body
    std::optional<FgcParams> params;
    std::string error;             // why the payload did not parse
};

struct FoundT35 {
    bool suffix = false;
    T35Payload t35;
};

struct AccessUnit {
    int index = 0;            // decode order
    std::size_t offset = 0;   // first byte of the unit in the file
    std::string picture_type; // nal_unit_type name of the first VCL NAL unit
    std::optional<int> poc;
    std::optional<int> idr_pic_id;  // H.264 only
    int sequence = 0;         // coded video sequence count (IDR / IRAP with NoRaslOutputFlag)
    bool output = true;       // false for pictures a decoder drops (RASL after a CRA start)
    std::optional<int64_t> pts;  // AV1 IVF timestamp
    int nal_units = 0;        // NAL units, or OBUs for AV1
    int pictures = 0;         // VCL NAL units starting a picture, or frame/frame-header OBUs
    // Decoding can start here (is_idr; AV1: a temporal unit that carries a sequence header
    // and shows a key frame it codes), and what a decoder starting later needs of this unit:
    // its H.26x parameter set NAL units, as (file offset after the start code, size).
    bool random_access = false;
    std::vector<std::pair<std::size_t, std::size_t>> parameter_sets;
    std::vector<FoundFgc> fgc;
    std::vector<FoundT35> t35;
    std::optional<Av1SequenceHeader> av1_sequence_header;  // AV1: the last one in this unit
    // AV1 with film_grain_params_present = 1: the film grain of the frame this unit shows,
    // from its frame header (update_grain = 0 resolved; apply_grain = 0 for none).
    std::optional<Av1FilmGrainParams> av1_frame_grain;
    bool av1_show_existing_frame = false;  // the shown frame is a show_existing_frame
    // update_grain = 0: what the frame's other reference slots hold (Av1ShownFrame)
    std::vector<std::pair<int, Av1FilmGrainParams>> av1_other_slot_grain;
    std::vector<std::string> warnings;
};

struct StreamScan {
    StreamCodec codec = StreamCodec::kH265;
    std::string container;    // "annexb", "ivf", "obu", "annexb-av1"
    std::string poc_support;  // what the picture order counts rest on
    std::vector<AccessUnit> units;
    std::vector<std::string> warnings;
    int bad_units() const;    // units with warnings
};

// Reads an H.26x stream as a parser element hands it over: any run of Annex B bytes at a
// time, with the access unit boundaries the caller knows (an access-unit-aligned buffer)
// given by end_access_unit(). Picture order counts, parameter sets and the coded video
// sequence count carry over from call to call; scan_stream() is push() of the whole stream
// and one end_access_unit().
class NalStreamParser {
public:
    explicit NalStreamParser(StreamCodec codec);  // h264, h265, h266; throws Error for av1
    ~NalStreamParser();
    NalStreamParser(NalStreamParser&&) noexcept;
    NalStreamParser& operator=(NalStreamParser&&) noexcept;

    // The NAL units of `data` (Annex B; `offset` is its first byte's position in the
    // stream, for warnings). Units completed by them (a new access unit started) are
    // appended to `done`. Returns the damage found between NAL units (no start code...).
    std::vector<std::string> push(const uint8_t* data, std::size_t size, std::size_t offset,
                                  std::vector<AccessUnit>& done);
    // Ends the access unit in progress (appended to `done` when it holds any NAL unit).
    void end_access_unit(std::vector<AccessUnit>& done);
    // As a new stream: parameter sets, POC state and unit count forgotten (a seek, a flush).
    void reset();
    StreamCodec codec() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

// Reads an AV1 stream one temporal unit at a time, keeping the sequence header and the
// reference slots the frame headers' film grain resolves against.
class Av1StreamParser {
public:
    AccessUnit push(const Av1TemporalUnit& tu);
    void reset();
    // The last sequence header read (nullopt before the first).
    const std::optional<Av1SequenceHeader>& sequence_header() const { return sequence_; }

private:
    std::optional<Av1SequenceHeader> sequence_;
    Av1FrameHeaderReader frame_headers_;
    int units_ = 0;
};

StreamScan scan_stream(const uint8_t* data, std::size_t size, StreamCodec codec);

// scan_stream of an H.26x Annex B or AV1 IVF stream that arrives a run of bytes at a time:
// `first`, then what `read` gives (up to n bytes into its buffer, fewer only at the end),
// asked for `run_bytes` at a time. Only the NAL units (IVF frame) not yet parsed are held, so
// the stream's size is no limit; the result is what scan_stream gives on the whole (H.26x runs
// are cut before start codes for parsing). Throws Error(kUnsupported) for AV1 that is not IVF.
StreamScan scan_stream_incrementally(StreamCodec codec, std::vector<uint8_t> first,
                                         const std::function<std::size_t(uint8_t*, std::size_t)>& read,
                                         std::size_t run_bytes = std::size_t(4) << 20);
// The most of an AV1 low-overhead or Annex B stream scan_stream_file reads (that scan holds
// the stream in memory): 1 GiB. A regular file larger than that fails before it is read; a
// pipe or device once more arrives. H.26x and AV1 IVF are scanned as they are read, whatever
// their size.
inline constexpr std::size_t kMaxStreamFileBytes = std::size_t(1) << 30;
// Reads the file (Error kIo when it cannot, or when an AV1 low-overhead or Annex B stream
// holds more than kMaxStreamFileBytes) and scans it; codec detected when absent. A pipe or device whose first 16 MiB are neither a
// recognisable stream nor a container (e.g. /dev/zero) fails then, without reading on.
// Tool side (stream_file_scan.cpp): not in libfilmgrain, which does no file I/O.
StreamScan scan_stream_file(const std::string& path, std::optional<StreamCodec> codec);

// The units a decoder outputs, in output order: by POC within each coded video sequence
// (H.26x), in decode order for AV1 and for units without a POC.
std::vector<const AccessUnit*> units_in_output_order(const StreamScan& scan);

}  // namespace filmgrain::bitstream

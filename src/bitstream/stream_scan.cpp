#include "bitstream/stream_scan.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <memory>

#include "bitstream/av1_frame_header.hpp"
#include "bitstream/h264_poc.hpp"
#include "bitstream/h265_poc.hpp"
#include "bitstream/h266_poc.hpp"
#include "bitstream/nal_header.hpp"
#include "bitstream/nal_units.hpp"
#include "filmgrain/error.hpp"
#include "metadata/fgc_sei.hpp"

namespace filmgrain::bitstream {
namespace {

constexpr int kH266PictureHeaderNut = 19;  // H.266 Table 5

void collect_sei(const std::vector<uint8_t>& rbsp, int header_bytes, bool suffix, StreamCodec codec, AccessUnit& au) {
    const std::vector<uint8_t> body(rbsp.begin() + header_bytes, rbsp.end());
    SeiParse sei = parse_sei_rbsp(body);
    for (auto& w : sei.warnings) au.warnings.push_back(w);
    for (SeiMessage& m : sei.messages) {
        if (m.payload_type == kSeiPayloadFgc) {
            FoundFgc f;
            f.suffix = suffix;
            f.payload = std::move(m.payload);
            try {
                f.params = parse_fgc_sei_payload(f.payload, fgc_codec(codec));
            } catch (const Error& e) {
                f.error = e.what();
                au.warnings.push_back(std::string("FGC SEI: ") + e.what());
            }
            au.fgc.push_back(std::move(f));
        } else if (m.payload_type == kSeiPayloadT35) {
            FoundT35 t;
            t.suffix = suffix;
            if (parse_t35_payload(m.payload.data(), m.payload.size(), t.t35))
                au.t35.push_back(std::move(t));
            else
                au.warnings.push_back("empty ITU-T T.35 SEI payload");
        }
    }
}

const char* poc_support_text(StreamCodec codec) {
    switch (codec) {
    case StreamCodec::kH264:
        return "H.264 8.2.1: pic_order_cnt_type 0, 1, 2 for frame pictures; IDR resets; MMCO 5 and field pictures not followed";
    case StreamCodec::kH265:
        return "H.265 8.3.1 from SPS/PPS/first slice segment; IRAP NoRaslOutputFlag (IDR, BLA, CRA first or after EOS)";
    case StreamCodec::kH266:
        return "H.266 8.3.1 from SPS/PPS/picture header (PH unit or in the slice); IDR, CRA/GDR first or after EOS start a CLVS; ph_poc_msb_cycle_val followed; base layer only";
    case StreamCodec::kAv1: return "AV1: temporal units in decode order (one shown frame each)";
    }
    return "";
}

}  // namespace

struct NalStreamParser::State {
    StreamCodec codec;
    NalCodec nc;
    H264PocDecoder h264;
    H265PocDecoder h265;
    H266PocDecoder h266;
    int sequence = -1;
    int units = 0;
    AccessUnit cur;
    bool cur_has_vcl = false, cur_open = false;

    explicit State(StreamCodec c) : codec(c), nc(nal_codec(c)) {}

    void finish(std::vector<AccessUnit>& done) {
        if (cur_open) {
            done.push_back(std::move(cur));
            units++;
        }
        cur = AccessUnit{};
        cur.index = units;
        cur_has_vcl = false;
        cur_open = false;
    }
    void open_at(std::size_t offset) {
        if (!cur_open) {
            cur.offset = offset >= 3 ? offset - 3 : 0;  // the start code
            cur.index = units;
            cur_open = true;
        }
    }
    void nal_unit(const uint8_t* nal, std::size_t size, std::size_t offset, std::vector<AccessUnit>& done);
};

void NalStreamParser::State::nal_unit(const uint8_t* nal, std::size_t size, std::size_t offset,
                                      std::vector<AccessUnit>& done) {
    NalHeader h;
    if (!parse_nal_header(nc, nal, size, h)) {
        open_at(offset);
        cur.warnings.push_back("NAL unit at byte " + std::to_string(offset) + " shorter than its header");
        return;
    }
    const std::vector<uint8_t> rbsp = remove_emulation_prevention(nal, size);
    const bool vcl = is_vcl(nc, h.type);
    // H.266: a picture starts with a PH NAL unit, or with a slice carrying its picture
    // header; either way the first slice after it is the one counted.
    const bool new_picture =
        vcl && (vcl_starts_picture(nc, rbsp.data(), rbsp.size()) || (codec == StreamCodec::kH266 && h266.header_pending()));
    if (cur_has_vcl && (starts_access_unit(nc, h.type) || new_picture)) finish(done);
    open_at(offset);
    cur.nal_units++;
    if (h.forbidden_bit) {
        cur.warnings.push_back("NAL unit at byte " + std::to_string(offset) + " has forbidden_zero_bit=1; skipped");
        return;
    }
    if (h.layer_id != 0) return;  // base layer only
    if (is_parameter_set(nc, h.type)) cur.parameter_sets.push_back({offset, size});
    try {
        if (is_sps(nc, h.type)) {
            if (codec == StreamCodec::kH264) h264.parse_sps(rbsp);
            if (codec == StreamCodec::kH265) h265.parse_sps(rbsp);
            if (codec == StreamCodec::kH266) h266.parse_sps(rbsp);
        } else if (is_pps(nc, h.type)) {
            if (codec == StreamCodec::kH264) h264.parse_pps(rbsp);
            if (codec == StreamCodec::kH265) h265.parse_pps(rbsp);
            if (codec == StreamCodec::kH266) h266.parse_pps(rbsp);
        } else if (codec == StreamCodec::kH266 && h.type == kH266PictureHeaderNut) {
            h266.parse_picture_header_unit(rbsp);
        } else if (is_prefix_sei(nc, h.type) || is_suffix_sei(nc, h.type)) {
            collect_sei(rbsp, h.header_bytes, is_suffix_sei(nc, h.type), codec, cur);
        } else if (is_end_of_sequence(nc, h.type)) {
            if (codec == StreamCodec::kH265) h265.end_of_sequence();
            if (codec == StreamCodec::kH266) h266.end_of_sequence();
        } else if (vcl) {
            cur_has_vcl = true;
            if (!new_picture) {
                if (cur.pictures == 0 && cur.warnings.empty())
                    cur.warnings.push_back(nal_type_name(nc, h.type) + " NAL unit at byte " + std::to_string(offset) +
                                           ": a slice whose picture start (first slice or picture header) is missing");
                return;
            }
            cur.pictures++;
            cur.picture_type = nal_type_name(nc, h.type);
            cur.random_access = cur.pictures == 1 && is_idr(nc, h.type);
            if (codec == StreamCodec::kH264) {
                const H264PictureOrder o = h264.picture(rbsp);
                if (o.idr) sequence++;
                cur.poc = o.poc;
                cur.idr_pic_id = o.idr_pic_id;
                if (!o.poc) cur.warnings.push_back("field picture: POC not derived");
            } else if (codec == StreamCodec::kH265) {
                const H265PictureOrder o = h265.picture(rbsp);
                if (o.starts_sequence) sequence++;
                cur.poc = o.poc;
                cur.output = o.output;
            } else {
                const H266PictureOrder o = h266.picture(rbsp);
                if (o.clvs_start) sequence++;
                cur.poc = o.poc;
                cur.output = o.output;
            }
            cur.sequence = std::max(sequence, 0);
        }
    } catch (const Error& e) {
        cur.warnings.push_back(nal_type_name(nc, h.type) + " NAL unit at byte " + std::to_string(offset) + ": " + e.what());
    }
}

NalStreamParser::NalStreamParser(StreamCodec codec) {
    if (codec == StreamCodec::kAv1)
        throw Error(ErrorCode::kInvalidArgument, "NalStreamParser: codec av1 has no NAL units (allowed h264, h265, h266)");
    state_ = std::make_unique<State>(codec);
}
NalStreamParser::~NalStreamParser() = default;
NalStreamParser::NalStreamParser(NalStreamParser&&) noexcept = default;
NalStreamParser& NalStreamParser::operator=(NalStreamParser&&) noexcept = default;

std::vector<std::string> NalStreamParser::push(const uint8_t* data, std::size_t size, std::size_t offset,
                                               std::vector<AccessUnit>& done) {
    AnnexBSplit split = split_annexb(data, size, offset);
    for (const NalSpan& span : split.nals) state_->nal_unit(data + span.offset, span.size, offset + span.offset, done);
    return std::move(split.warnings);
}

void NalStreamParser::end_access_unit(std::vector<AccessUnit>& done) { state_->finish(done); }

void NalStreamParser::reset() { state_ = std::make_unique<State>(state_->codec); }

StreamCodec NalStreamParser::codec() const { return state_->codec; }

AccessUnit Av1StreamParser::push(const Av1TemporalUnit& tu) {
    AccessUnit au;
    au.index = units_++;
    au.offset = tu.offset;
    au.pts = tu.pts;
    au.warnings = tu.warnings;
    au.nal_units = int(tu.obus.size());
    for (const Av1Obu& obu : tu.obus) {
        if (obu.type == kObuFrame || obu.type == kObuFrameHeader) {
            // A random access point: the unit's first frame is a shown key frame (AV1 5.9.2:
            // show_existing_frame, frame_type, show_frame lead the uncompressed header), and
            // the unit carries its sequence header, so a decoder needs nothing before it.
            if (au.pictures == 0 && au.av1_sequence_header && !obu.payload.empty()) {
                const uint8_t b = obu.payload[0];
                au.random_access = au.av1_sequence_header->reduced_still_picture_header ||
                                   (!(b & 0x80) && ((b >> 5) & 3) == 0 && (b & 0x10));
            }
            au.pictures++;
        }
        if (obu.type == kObuSequenceHeader) {
            try {
                au.av1_sequence_header = parse_av1_sequence_header(obu.payload);
                sequence_ = au.av1_sequence_header;
            } catch (const Error& e) {
                au.warnings.push_back("sequence header OBU at byte " + std::to_string(obu.offset) + ": " + e.what());
            }
            continue;
        }
        // Frame headers are followed only where they carry film grain.
        if ((obu.type == kObuFrame || obu.type == kObuFrameHeader) && sequence_ && sequence_->film_grain_params_present) {
            try {
                if (auto shown = frame_headers_.read(*sequence_, obu)) {
                    if (au.av1_frame_grain)
                        au.warnings.push_back("more than one shown frame in the temporal unit; the last one's "
                                              "film grain is kept");
                    au.av1_frame_grain = shown->grain;
                    au.av1_show_existing_frame = shown->show_existing_frame;
                    au.av1_other_slot_grain = std::move(shown->other_slot_grain);
                }
            } catch (const Error& e) {
                au.warnings.push_back("frame header OBU at byte " + std::to_string(obu.offset) + ": " + e.what());
            }
            continue;
        }
        std::vector<uint8_t> t35;
        std::string warning;
        if (av1_metadata_t35(obu, t35, &warning)) {
            FoundT35 t;
            if (parse_t35_payload(t35.data(), t35.size(), t.t35))
                au.t35.push_back(std::move(t));
            else
                au.warnings.push_back("empty ITU-T T.35 metadata OBU at byte " + std::to_string(obu.offset));
        } else if (!warning.empty()) {
            au.warnings.push_back(warning);
        }
    }
    return au;
}

void Av1StreamParser::reset() {
    sequence_.reset();
    frame_headers_.reset();
    units_ = 0;
}

namespace {

StreamScan scan_nal_stream(const uint8_t* data, std::size_t size, StreamCodec codec) {
    StreamScan scan;
    scan.codec = codec;
    scan.container = "annexb";
    scan.poc_support = poc_support_text(codec);
    NalStreamParser parser(codec);
    scan.warnings = parser.push(data, size, 0, scan.units);
    parser.end_access_unit(scan.units);
    return scan;
}

// The start of the last start code (0x000001) in data[from, size) at or after `from`; 0 when
// there is none.
std::size_t last_start_code(const uint8_t* data, std::size_t size, std::size_t from) {
    for (std::size_t i = size >= 3 ? size - 3 : 0; i + 3 <= size && i >= from && i > 0; i--)
        if (data[i] == 0 && data[i + 1] == 0 && data[i + 2] == 1) return i;
    return 0;
}

StreamScan scan_av1_stream(const uint8_t* data, std::size_t size) {
    StreamScan scan;
    scan.codec = StreamCodec::kAv1;
    scan.poc_support = poc_support_text(StreamCodec::kAv1);
    Av1Container container = Av1Container::kLowOverhead;
    if (looks_like_ivf(data, size))
        container = Av1Container::kIvf;
    else if (!looks_like_av1_low_overhead(data, size) && looks_like_av1_annexb(data, size))
        container = Av1Container::kAnnexB;
    scan.container = container == Av1Container::kAnnexB ? "annexb-av1" : av1_container_name(container);
    Av1Stream s = parse_av1_stream(data, size, container);
    scan.warnings = s.warnings;
    Av1StreamParser parser;
    for (Av1TemporalUnit& tu : s.units) scan.units.push_back(parser.push(tu));
    return scan;
}

}  // namespace

StreamScan scan_stream_incrementally(StreamCodec codec, std::vector<uint8_t> first,
                                         const std::function<std::size_t(uint8_t*, std::size_t)>& read,
                                         std::size_t run_bytes) {
    StreamScan scan;
    scan.codec = codec;
    scan.poc_support = poc_support_text(codec);
    const std::size_t kRun = std::max<std::size_t>(run_bytes, 1);
    if (codec == StreamCodec::kAv1) {
        if (!looks_like_ivf(first.data(), first.size()))
            throw Error(ErrorCode::kUnsupported, "only AV1 in IVF is scanned as it arrives (low-overhead OBUs and Annex B whole)");
        scan.container = av1_container_name(Av1Container::kIvf);
        IvfStreamReader ivf;
        Av1StreamParser parser;
        std::vector<uint8_t> run = std::move(first);
        for (bool end = false;;) {
            for (Av1TemporalUnit& tu : ivf.push(run.data(), run.size())) scan.units.push_back(parser.push(tu));
            if (end) break;
            run.resize(kRun);
            run.resize(read(run.data(), kRun));
            end = run.size() < kRun;
        }
        Av1Stream tail = ivf.finish();
        scan.warnings = std::move(tail.warnings);
        for (Av1TemporalUnit& tu : tail.units) scan.units.push_back(parser.push(tu));
        return scan;
    }
    scan.container = "annexb";
    NalStreamParser parser(codec);
    std::vector<uint8_t> held = std::move(first);  // from the last start code on
    std::size_t held_offset = 0;                   // of held[0] in the stream
    std::size_t searched = 0;                      // held[0, searched) holds no later start code
    for (bool end = false; !end;) {
        const std::size_t at = held.size();
        held.resize(at + kRun);
        const std::size_t got = read(held.data() + at, kRun);
        held.resize(at + got);
        end = got < kRun;
        // Everything before the last start code is whole NAL units: parse it, keep the rest
        // (a unit may continue in the next run).
        std::size_t cut = end ? held.size() : last_start_code(held.data(), held.size(), searched);
        // zero bytes before the start code are its own (zero_byte, trailing_zero_8bits): they
        // go with it, as the whole-stream split leaves them out of the unit before
        while (!end && cut > 0 && held[cut - 1] == 0) cut--;
        // the first run parsed holds the stream's first start code, so that what precedes it
        // is reported as the whole-stream split reports it
        if (!end && held_offset == 0 && cut > 0) {
            std::size_t first_code = 0;
            while (first_code + 3 <= held.size() &&
                   !(held[first_code] == 0 && held[first_code + 1] == 0 && held[first_code + 2] == 1))
                first_code++;
            if (cut <= first_code) cut = 0;
        }
        if (cut == 0) {
            searched = held.size() >= 2 ? held.size() - 2 : 0;
            continue;
        }
        for (std::string& w : parser.push(held.data(), cut, held_offset, scan.units)) scan.warnings.push_back(std::move(w));
        held.erase(held.begin(), held.begin() + std::ptrdiff_t(cut));
        held_offset += cut;
        searched = 0;
    }
    parser.end_access_unit(scan.units);
    return scan;
}

namespace {

std::string lower_extension(const std::string& path) {
    const auto dot = path.rfind('.');
    if (dot == std::string::npos) return "";
    std::string e = path.substr(dot + 1);
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace

NalCodec nal_codec(StreamCodec c) {
    if (c == StreamCodec::kAv1) throw Error(ErrorCode::kInvalidArgument, "AV1 has no NAL units (allowed h264, h265, h266)");
    return c == StreamCodec::kH264 ? NalCodec::kH264 : c == StreamCodec::kH265 ? NalCodec::kH265 : NalCodec::kH266;
}

FgcCodec fgc_codec(StreamCodec c) {
    return c == StreamCodec::kH264 ? FgcCodec::kAvc : c == StreamCodec::kH265 ? FgcCodec::kHevc : FgcCodec::kVvc;
}

const char* stream_codec_name(StreamCodec c) {
    switch (c) {
    case StreamCodec::kH264: return "h264";
    case StreamCodec::kH265: return "h265";
    case StreamCodec::kH266: return "h266";
    case StreamCodec::kAv1: return "av1";
    }
    return "?";
}

StreamCodec parse_stream_codec(const std::string& n) {
    if (n == "h264" || n == "avc") return StreamCodec::kH264;
    if (n == "h265" || n == "hevc") return StreamCodec::kH265;
    if (n == "h266" || n == "vvc") return StreamCodec::kH266;
    if (n == "av1") return StreamCodec::kAv1;
    throw Error(ErrorCode::kInvalidArgument, "--codec '" + n + "' is not known (allowed h264, h265, h266, av1)");
}

std::optional<StreamCodec> detect_stream_codec(const uint8_t* data, std::size_t size, const std::string& path) {
    if (looks_like_ivf(data, size) || looks_like_av1_low_overhead(data, size)) return StreamCodec::kAv1;
    const std::string ext = lower_extension(path);
    if (ext == "264" || ext == "h264" || ext == "avc" || ext == "jsv" || ext == "26l") return StreamCodec::kH264;
    if (ext == "265" || ext == "h265" || ext == "hevc" || ext == "bit" || ext == "bin") {
        if (ext == "265" || ext == "h265" || ext == "hevc") return StreamCodec::kH265;
    }
    if (ext == "266" || ext == "h266" || ext == "vvc") return StreamCodec::kH266;
    if (ext == "obu" || ext == "av1" || ext == "ivf") return StreamCodec::kAv1;
    // The first NAL unit after a start code: parameter sets and AUDs start streams.
    AnnexBSplit split = split_annexb(data, std::min<std::size_t>(size, 4096));
    if (!split.nals.empty() && split.nals[0].size >= 2) {
        const uint8_t* n = data + split.nals[0].offset;
        const int h265_type = (n[0] >> 1) & 63, h266_type = n[1] >> 3, h264_type = n[0] & 31;
        if (!(n[0] & 0x80)) {
            if ((n[0] & 0x81) == 0 && (n[1] & 7) != 0 && h265_type >= 32 && h265_type <= 35) return StreamCodec::kH265;
            if (n[0] == 0 && (n[1] & 7) != 0 && h266_type >= 12 && h266_type <= 20) return StreamCodec::kH266;
            if (h264_type == 7 || h264_type == 9 || h264_type == 6) return StreamCodec::kH264;
        }
    }
    if (looks_like_av1_annexb(data, size)) return StreamCodec::kAv1;
    return std::nullopt;
}

const char* container_name(const uint8_t* data, std::size_t size) {
    if (size >= 4 && data[0] == 0x1A && data[1] == 0x45 && data[2] == 0xDF && data[3] == 0xA3) return "Matroska/WebM";
    if (size >= 8 && std::memcmp(data + 4, "ftyp", 4) == 0) return "MP4/QuickTime";
    if (size >= 12 && std::memcmp(data, "RIFF", 4) == 0 && std::memcmp(data + 8, "AVI ", 4) == 0) return "AVI";
    if (size >= 3 && std::memcmp(data, "FLV", 3) == 0) return "FLV";
    // MPEG-2 TS: the sync byte 0x47 at the start of three consecutive 188-byte packets.
    if (size >= 3 * 188 && data[0] == 0x47 && data[188] == 0x47 && data[376] == 0x47) return "MPEG transport stream";
    return nullptr;
}

int StreamScan::bad_units() const {
    int n = 0;
    for (const AccessUnit& u : units) n += !u.warnings.empty();
    return n;
}

StreamScan scan_stream(const uint8_t* data, std::size_t size, StreamCodec codec) {
    if (codec == StreamCodec::kAv1) return scan_av1_stream(data, size);
    return scan_nal_stream(data, size, codec);
}

std::vector<const AccessUnit*> units_in_output_order(const StreamScan& scan) {
    std::vector<const AccessUnit*> out;
    for (const AccessUnit& u : scan.units)
        if (u.output && u.pictures > 0) out.push_back(&u);
    if (scan.codec == StreamCodec::kAv1) return out;
    // Units without a POC (H.264 field pictures) keep the decode order throughout.
    for (const AccessUnit* u : out)
        if (!u->poc) return out;
    std::sort(out.begin(), out.end(), [](const AccessUnit* a, const AccessUnit* b) {
        if (a->sequence != b->sequence) return a->sequence < b->sequence;
        if (*a->poc != *b->poc) return *a->poc < *b->poc;
        return a->index < b->index;
    });
    return out;
}

}  // namespace filmgrain::bitstream

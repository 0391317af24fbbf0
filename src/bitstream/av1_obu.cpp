#include "bitstream/av1_obu.hpp"

#include <cstring>

namespace filmgrain::bitstream {
namespace {

uint32_t le32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }
int64_t le64(const uint8_t* p) {
    uint64_t v = 0;
    for (int i = 7; i >= 0; i--) v = v << 8 | p[i];
    return int64_t(v);
}

// One OBU at data[pos]; `available` bounds it. With `sized_by_container` the OBU may
// lack obu_size (Annex B obu_length gives it).
// `base`: the position of data[0] in the stream, for offsets and messages.
bool read_obu(const uint8_t* data, std::size_t end, std::size_t& pos, Av1Obu& obu, std::string& why,
              std::size_t base = 0) {
    const std::size_t at = base + pos;
    if (pos >= end) {
        why = "OBU header missing";
        return false;
    }
    const uint8_t h = data[pos++];
    if (h & 0x80) {
        why = "obu_forbidden_bit=1 at byte " + std::to_string(at);
        return false;
    }
    obu.type = (h >> 3) & 15;
    obu.offset = at;
    const bool extension = h & 4, has_size = h & 2;
    if (extension) {
        if (pos >= end) {
            why = "obu_extension_header truncated at byte " + std::to_string(at);
            return false;
        }
        obu.temporal_id = data[pos] >> 5;
        obu.spatial_id = (data[pos] >> 3) & 3;
        pos++;
    }
    uint64_t size = end - pos;
    if (has_size && !read_leb128(data, end, pos, size)) {
        why = "obu_size truncated at byte " + std::to_string(at);
        return false;
    }
    if (size > end - pos) {
        why = "OBU type " + std::to_string(obu.type) + " at byte " + std::to_string(at) + ": obu_size=" +
              std::to_string(size) + " exceeds the " + std::to_string(end - pos) + " byte(s) left";
        return false;
    }
    obu.payload.assign(data + pos, data + pos + size);
    pos += std::size_t(size);
    return true;
}

// OBUs of [pos, end) one after another (Section 5 form).
void read_obus(const uint8_t* data, std::size_t pos, std::size_t end, Av1TemporalUnit& tu, std::size_t base = 0) {
    while (pos < end) {
        Av1Obu obu;
        std::string why;
        if (!read_obu(data, end, pos, obu, why, base)) {
            tu.warnings.push_back(why);
            return;
        }
        tu.obus.push_back(std::move(obu));
    }
}

// One IVF frame at data[pos] (its 12-byte header first) of a buffer whose data[0] is stream
// byte `base`: false when the buffer holds less than the whole frame (nothing consumed).
bool read_ivf_frame(const uint8_t* data, std::size_t size, std::size_t& pos, std::size_t base, Av1TemporalUnit& tu) {
    if (size - pos < 12) return false;
    const uint32_t frame_size = le32(data + pos);
    if (frame_size > size - pos - 12) return false;
    tu.offset = base + pos;
    tu.pts = le64(data + pos + 4);
    read_obus(data, pos + 12, pos + 12 + frame_size, tu, base);
    pos += 12 + std::size_t(frame_size);
    return true;
}

// What is left of an IVF stream when it ends part-way into a frame (data[pos] onward, stream
// byte base + pos): the warning, and the part of the frame there is.
void read_ivf_tail(const uint8_t* data, std::size_t size, std::size_t pos, std::size_t base, Av1Stream& s) {
    if (pos >= size) return;
    if (size - pos < 12) {
        s.warnings.push_back("IVF frame header truncated at byte " + std::to_string(base + pos));
        return;
    }
    Av1TemporalUnit tu;
    tu.offset = base + pos;
    tu.pts = le64(data + pos + 4);
    s.warnings.push_back("IVF frame at byte " + std::to_string(tu.offset) + ": size " + std::to_string(le32(data + pos)) +
                         " exceeds the " + std::to_string(size - pos - 12) + " byte(s) left");
    read_obus(data, pos + 12, size, tu, base);  // what there is of it
    s.units.push_back(std::move(tu));
}

std::size_t ivf_header_size(const uint8_t* data) {
    const std::size_t header_size = data[6] | data[7] << 8;
    return header_size < 32 ? 32 : header_size;
}

Av1Stream parse_ivf(const uint8_t* data, std::size_t size) {
    Av1Stream s;
    s.container = Av1Container::kIvf;
    if (size < 32) {
        s.warnings.push_back("IVF header truncated (" + std::to_string(size) + " of 32 bytes)");
        return s;
    }
    std::size_t pos = ivf_header_size(data);
    for (Av1TemporalUnit tu; pos < size && read_ivf_frame(data, size, pos, 0, tu); tu = Av1TemporalUnit{})
        s.units.push_back(std::move(tu));
    read_ivf_tail(data, size, pos, 0, s);
    return s;
}

Av1Stream parse_low_overhead(const uint8_t* data, std::size_t size) {
    Av1Stream s;
    s.container = Av1Container::kLowOverhead;
    std::size_t pos = 0;
    while (pos < size) {
        Av1Obu obu;
        std::string why;
        const std::size_t start = pos;
        if (!read_obu(data, size, pos, obu, why)) {
            s.warnings.push_back(why);
            break;
        }
        if (obu.type == kObuTemporalDelimiter || s.units.empty()) {
            if (obu.type != kObuTemporalDelimiter)
                s.warnings.push_back("stream does not start with a temporal delimiter");
            s.units.emplace_back();
            s.units.back().offset = start;
        }
        s.units.back().obus.push_back(std::move(obu));
    }
    return s;
}

Av1Stream parse_annexb(const uint8_t* data, std::size_t size) {
    Av1Stream s;
    s.container = Av1Container::kAnnexB;
    std::size_t pos = 0;
    while (pos < size) {
        const std::size_t tu_start = pos;
        uint64_t tu_size = 0;
        if (!read_leb128(data, size, pos, tu_size) || tu_size > size - pos) {
            s.warnings.push_back("temporal_unit_size at byte " + std::to_string(tu_start) + " truncated or too large");
            break;
        }
        Av1TemporalUnit tu;
        tu.offset = tu_start;
        const std::size_t tu_end = pos + std::size_t(tu_size);
        while (pos < tu_end) {
            uint64_t fu_size = 0;
            if (!read_leb128(data, tu_end, pos, fu_size) || fu_size > tu_end - pos) {
                tu.warnings.push_back("frame_unit_size at byte " + std::to_string(pos) + " truncated or too large");
                break;
            }
            const std::size_t fu_end = pos + std::size_t(fu_size);
            while (pos < fu_end) {
                uint64_t obu_length = 0;
                if (!read_leb128(data, fu_end, pos, obu_length) || obu_length > fu_end - pos) {
                    tu.warnings.push_back("obu_length at byte " + std::to_string(pos) + " truncated or too large");
                    pos = fu_end;
                    break;
                }
                std::size_t obu_pos = pos;
                Av1Obu obu;
                std::string why;
                if (read_obu(data, pos + std::size_t(obu_length), obu_pos, obu, why))
                    tu.obus.push_back(std::move(obu));
                else
                    tu.warnings.push_back(why);
                pos += std::size_t(obu_length);
            }
            pos = fu_end;
        }
        pos = tu_end;
        s.units.push_back(std::move(tu));
    }
    return s;
}

}  // namespace

const char* av1_container_name(Av1Container c) {
    switch (c) {
    case Av1Container::kIvf: return "ivf";
    case Av1Container::kLowOverhead: return "obu";
    case Av1Container::kAnnexB: return "annexb";
    }
    return "?";
}

bool read_leb128(const uint8_t* data, std::size_t size, std::size_t& pos, uint64_t& value) {
    value = 0;
    for (int i = 0; i < 8; i++) {
        if (pos >= size) return false;
        const uint8_t b = data[pos++];
        value |= uint64_t(b & 0x7F) << (7 * i);
        if (!(b & 0x80)) return value <= 0xFFFFFFFFull;
    }
    return false;
}

void write_leb128(std::vector<uint8_t>& out, uint64_t value) {
    do {
        uint8_t b = value & 0x7F;
        value >>= 7;
        if (value) b |= 0x80;
        out.push_back(b);
    } while (value);
}

bool looks_like_ivf(const uint8_t* data, std::size_t size) { return size >= 4 && std::memcmp(data, "DKIF", 4) == 0; }

bool looks_like_av1_low_overhead(const uint8_t* data, std::size_t size) {
    // 0x12 0x00: temporal delimiter, has_size, obu_size 0
    return size >= 2 && data[0] == 0x12 && data[1] == 0x00;
}

bool looks_like_av1_annexb(const uint8_t* data, std::size_t size) {
    std::size_t pos = 0;
    uint64_t tu = 0, fu = 0, ol = 0;
    if (!read_leb128(data, size, pos, tu) || tu > size - pos || tu == 0) return false;
    const std::size_t tu_end = pos + tu;
    if (!read_leb128(data, tu_end, pos, fu) || fu > tu_end - pos || fu == 0) return false;
    const std::size_t fu_end = pos + fu;
    if (!read_leb128(data, fu_end, pos, ol) || ol > fu_end - pos || ol == 0) return false;
    // the first OBU of a temporal unit is its temporal delimiter
    return ((data[pos] >> 3) & 15) == kObuTemporalDelimiter && !(data[pos] & 0x80);
}

std::vector<Av1TemporalUnit> IvfStreamReader::push(const uint8_t* data, std::size_t size) {
    held_.insert(held_.end(), data, data + size);
    std::vector<Av1TemporalUnit> out;
    if (!header_read_) {
        if (held_.size() < 32) return out;
        pos_ = ivf_header_size(held_.data());
        header_read_ = true;
    }
    if (pos_ > held_.size()) return out;  // a header longer than what has arrived
    for (Av1TemporalUnit tu; read_ivf_frame(held_.data(), held_.size(), pos_, held_base_, tu); tu = Av1TemporalUnit{})
        out.push_back(std::move(tu));
    held_.erase(held_.begin(), held_.begin() + std::ptrdiff_t(pos_));
    held_base_ += pos_;
    pos_ = 0;
    return out;
}

Av1Stream IvfStreamReader::finish() {
    Av1Stream s;
    s.container = Av1Container::kIvf;
    if (!header_read_)
        s.warnings.push_back("IVF header truncated (" + std::to_string(held_.size()) + " of 32 bytes)");
    else if (pos_ < held_.size())
        read_ivf_tail(held_.data(), held_.size(), pos_, held_base_, s);
    held_.clear();
    return s;
}

Av1Stream parse_av1_stream(const uint8_t* data, std::size_t size, Av1Container container) {
    switch (container) {
    case Av1Container::kIvf: return parse_ivf(data, size);
    case Av1Container::kAnnexB: return parse_annexb(data, size);
    case Av1Container::kLowOverhead: break;
    }
    return parse_low_overhead(data, size);
}

bool av1_metadata_t35(const Av1Obu& obu, std::vector<uint8_t>& t35, std::string* warning) {
    if (obu.type != kObuMetadata) return false;
    std::size_t pos = 0;
    uint64_t metadata_type = 0;
    if (!read_leb128(obu.payload.data(), obu.payload.size(), pos, metadata_type)) {
        if (warning) *warning = "metadata_type truncated in the metadata OBU at byte " + std::to_string(obu.offset);
        return false;
    }
    if (metadata_type != kMetadataTypeItutT35) return false;
    std::size_t end = obu.payload.size();
    // trailing_bits(): the last non-zero byte holds the final 1 bit (AV1 5.3.4)
    while (end > pos && obu.payload[end - 1] == 0) end--;
    if (end == pos) {
        if (warning) *warning = "ITU-T T.35 metadata OBU at byte " + std::to_string(obu.offset) + " has no payload";
        return false;
    }
    if (obu.payload[end - 1] != 0x80) {
        // T.35 bytes are byte aligned, so trailing_bits() is a whole 0x80 byte
        if (warning) *warning = "ITU-T T.35 metadata OBU at byte " + std::to_string(obu.offset) +
                                " does not end with trailing_bits (0x80)";
        return false;
    }
    t35.assign(obu.payload.begin() + long(pos), obu.payload.begin() + long(end - 1));
    return true;
}

std::vector<uint8_t> av1_obu_bytes(int type, const std::vector<uint8_t>& payload) {
    std::vector<uint8_t> out = {uint8_t((type << 3) | 2)};
    write_leb128(out, payload.size());
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
}

std::vector<uint8_t> av1_t35_metadata_payload(const std::vector<uint8_t>& t35) {
    std::vector<uint8_t> out;
    write_leb128(out, kMetadataTypeItutT35);
    out.insert(out.end(), t35.begin(), t35.end());
    out.push_back(0x80);
    return out;
}

}  // namespace filmgrain::bitstream

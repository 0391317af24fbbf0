#include "bitstream/sei_messages.hpp"

namespace filmgrain::bitstream {
namespace {

// True when what is left is rbsp_trailing_bits(): 0x80 then nothing but zero bytes.
bool only_trailing_bits(const std::vector<uint8_t>& rbsp, std::size_t pos) {
    if (pos >= rbsp.size()) return true;
    if (rbsp[pos] != 0x80) return false;
    for (std::size_t i = pos + 1; i < rbsp.size(); i++)
        if (rbsp[i] != 0) return false;
    return true;
}

bool read_ff_coded(const std::vector<uint8_t>& rbsp, std::size_t& pos, int& value) {
    value = 0;
    while (pos < rbsp.size() && rbsp[pos] == 0xFF) {
        value += 255;
        pos++;
        if (value > (1 << 24)) return false;  // no real message is this large
    }
    if (pos >= rbsp.size()) return false;
    value += rbsp[pos++];
    return true;
}

void write_ff_coded(std::vector<uint8_t>& out, int value) {
    while (value >= 255) {
        out.push_back(0xFF);
        value -= 255;
    }
    out.push_back(uint8_t(value));
}

}  // namespace

SeiParse parse_sei_rbsp(const std::vector<uint8_t>& rbsp) {
    SeiParse out;
    std::size_t pos = 0;
    while (!only_trailing_bits(rbsp, pos)) {
        const std::size_t start = pos;
        int type = 0, size = 0;
        if (!read_ff_coded(rbsp, pos, type)) {
            out.warnings.push_back("SEI payloadType truncated at RBSP byte " + std::to_string(start));
            break;
        }
        if (!read_ff_coded(rbsp, pos, size)) {
            out.warnings.push_back("SEI payloadSize of payloadType " + std::to_string(type) + " truncated");
            break;
        }
        if (std::size_t(size) > rbsp.size() - pos) {
            out.warnings.push_back("SEI payloadType " + std::to_string(type) + ": payloadSize=" + std::to_string(size) +
                                   " exceeds the " + std::to_string(rbsp.size() - pos) + " byte(s) left in the NAL unit");
            break;
        }
        SeiMessage m;
        m.payload_type = type;
        m.payload.assign(rbsp.begin() + long(pos), rbsp.begin() + long(pos + size));
        out.messages.push_back(std::move(m));
        pos += std::size_t(size);
    }
    return out;
}

std::vector<uint8_t> build_sei_rbsp(const std::vector<SeiMessage>& messages) {
    std::vector<uint8_t> out;
    for (const SeiMessage& m : messages) {
        write_ff_coded(out, m.payload_type);
        write_ff_coded(out, int(m.payload.size()));
        out.insert(out.end(), m.payload.begin(), m.payload.end());
    }
    out.push_back(0x80);  // rbsp_stop_one_bit + alignment
    return out;
}

bool parse_t35_payload(const uint8_t* data, std::size_t size, T35Payload& out) {
    if (size == 0) return false;
    T35Payload t;
    std::size_t pos = 0;
    t.country_code = data[pos++];
    if (t.country_code == 0xFF) {
        if (pos >= size) return false;
        t.country_code_extension = data[pos++];
    }
    t.bytes.assign(data + pos, data + size);
    if (size - pos >= 2) t.provider_code = (data[pos] << 8) | data[pos + 1];
    if (size - pos >= 3) t.provider_oriented_code = data[pos + 2];
    out = std::move(t);
    return true;
}

std::vector<uint8_t> t35_bytes(const T35Payload& t) {
    std::vector<uint8_t> b{uint8_t(t.country_code)};
    if (t.country_code == 0xFF) b.push_back(uint8_t(t.country_code_extension));
    b.insert(b.end(), t.bytes.begin(), t.bytes.end());
    return b;
}

}  // namespace filmgrain::bitstream

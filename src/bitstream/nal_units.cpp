#include "bitstream/nal_units.hpp"

namespace filmgrain::bitstream {

AnnexBSplit split_annexb(const uint8_t* data, std::size_t size, std::size_t base) {
    AnnexBSplit out;
    // Positions just after each 00 00 01.
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i + 2 < size; i++) {
        if (data[i] == 0 && data[i + 1] == 0 && data[i + 2] == 1) {
            starts.push_back(i + 3);
            i += 2;
        }
    }
    if (starts.empty()) {
        if (size > 0) out.warnings.push_back("no start code (00 00 01) in " + std::to_string(size) + " bytes");
        return out;
    }
    std::size_t lead = starts[0] - 3;
    for (std::size_t i = 0; i < lead; i++)
        if (data[i] != 0) {
            out.warnings.push_back(std::to_string(lead) + " byte(s) before the first start code ignored");
            break;
        }
    for (std::size_t k = 0; k < starts.size(); k++) {
        const std::size_t begin = starts[k];
        std::size_t end = k + 1 < starts.size() ? starts[k + 1] - 3 : size;
        while (end > begin && data[end - 1] == 0) end--;  // trailing_zero_8bits / zero_byte
        if (end == begin) {
            out.warnings.push_back("empty NAL unit at byte " + std::to_string(base + begin));
            continue;
        }
        out.nals.push_back({begin, end - begin});
    }
    return out;
}

std::vector<uint8_t> remove_emulation_prevention(const uint8_t* data, std::size_t size) {
    std::vector<uint8_t> out;
    out.reserve(size);
    int zeros = 0;
    for (std::size_t i = 0; i < size; i++) {
        if (zeros >= 2 && data[i] == 3) {
            zeros = 0;
            continue;
        }
        zeros = data[i] == 0 ? zeros + 1 : 0;
        out.push_back(data[i]);
    }
    return out;
}

std::vector<uint8_t> add_emulation_prevention(const uint8_t* rbsp, std::size_t size) {
    std::vector<uint8_t> out;
    out.reserve(size + size / 64 + 2);
    int zeros = 0;
    for (std::size_t i = 0; i < size; i++) {
        if (zeros >= 2 && rbsp[i] <= 3) {
            out.push_back(3);
            zeros = 0;
        }
        out.push_back(rbsp[i]);
        zeros = rbsp[i] == 0 ? zeros + 1 : 0;
    }
    if (!out.empty() && out.back() == 0) out.push_back(3);  // cabac_zero_word style ending
    return out;
}

std::vector<uint8_t> annexb_nal_unit(const std::vector<uint8_t>& header, const std::vector<uint8_t>& rbsp) {
    std::vector<uint8_t> out = {0, 0, 0, 1};
    // The header is escaped together with the payload: an H.264 header byte is never 0,
    // but H.266's first header byte is 0 for layer 0.
    std::vector<uint8_t> nal = header;
    nal.insert(nal.end(), rbsp.begin(), rbsp.end());
    const std::vector<uint8_t> escaped = add_emulation_prevention(nal.data(), nal.size());
    out.insert(out.end(), escaped.begin(), escaped.end());
    return out;
}

}  // namespace filmgrain::bitstream

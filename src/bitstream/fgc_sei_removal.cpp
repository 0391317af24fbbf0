#include "bitstream/fgc_sei_removal.hpp"

#include <algorithm>

#include "bitstream/nal_header.hpp"
#include "bitstream/nal_units.hpp"
#include "bitstream/sei_messages.hpp"

namespace filmgrain::bitstream {

std::optional<std::vector<uint8_t>> remove_fgc_sei(StreamCodec codec, const uint8_t* data, std::size_t size) {
    if (codec == StreamCodec::kAv1) return std::nullopt;
    const NalCodec nc = nal_codec(codec);
    const AnnexBSplit split = split_annexb(data, size);
    std::vector<uint8_t> out;
    bool changed = false;
    std::size_t copied = 0;  // bytes of `data` already in `out` or deliberately left out
    for (const NalSpan& span : split.nals) {
        const uint8_t* nal = data + span.offset;
        NalHeader h;
        if (!parse_nal_header(nc, nal, span.size, h) || h.forbidden_bit) continue;
        if (!is_prefix_sei(nc, h.type) && !is_suffix_sei(nc, h.type)) continue;
        const std::vector<uint8_t> rbsp = remove_emulation_prevention(nal, span.size);
        if (rbsp.size() < std::size_t(h.header_bytes)) continue;
        const SeiParse sei = parse_sei_rbsp(std::vector<uint8_t>(rbsp.begin() + h.header_bytes, rbsp.end()));
        std::vector<SeiMessage> kept;
        std::copy_if(sei.messages.begin(), sei.messages.end(), std::back_inserter(kept),
                     [](const SeiMessage& m) { return m.payload_type != kSeiPayloadFgc; });
        if (kept.size() == sei.messages.size()) continue;
        changed = true;
        // The start code in front of this NAL unit: three bytes, and a zero_byte before them
        // when there is one.
        std::size_t start = span.offset - 3;
        if (start > copied && data[start - 1] == 0) start--;
        out.insert(out.end(), data + copied, data + start);
        if (!kept.empty()) {
            const std::vector<uint8_t> header(nal, nal + h.header_bytes);
            const std::vector<uint8_t> unit = annexb_nal_unit(header, build_sei_rbsp(kept));
            out.insert(out.end(), unit.begin(), unit.end());
        }
        copied = span.offset + span.size;
    }
    if (!changed) return std::nullopt;
    out.insert(out.end(), data + copied, data + size);
    return out;
}

}  // namespace filmgrain::bitstream

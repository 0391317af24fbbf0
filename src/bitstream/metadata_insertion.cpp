#include "bitstream/metadata_insertion.hpp"

#include "bitstream/av1_obu.hpp"
#include "bitstream/nal_header.hpp"
#include "bitstream/nal_units.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::bitstream {
namespace {

std::vector<uint8_t> sei_header(StreamCodec codec, bool suffix) {
    switch (codec) {
    case StreamCodec::kH264: return {0x06};
    case StreamCodec::kH265: return {uint8_t((suffix ? 40 : 39) << 1), 0x01};
    case StreamCodec::kH266: return {0x00, uint8_t(((suffix ? 24 : 23) << 3) | 1)};
    case StreamCodec::kAv1: break;
    }
    throw Error(ErrorCode::kInvalidArgument, "SEI NAL units need an H.26x stream");
}

void put_le32(std::vector<uint8_t>& v, std::size_t at, uint32_t x) {
    for (int i = 0; i < 4; i++) v[at + i] = uint8_t(x >> (8 * i));
}

}  // namespace

std::vector<uint8_t> sei_nal_unit(StreamCodec codec, bool suffix, const std::vector<SeiMessage>& messages) {
    if (suffix && codec == StreamCodec::kH264) throw Error(ErrorCode::kInvalidArgument, "H.264 has no suffix SEI");
    return annexb_nal_unit(sei_header(codec, suffix), build_sei_rbsp(messages));
}

std::vector<uint8_t> insert_sei(const std::vector<uint8_t>& stream, StreamCodec codec,
                                const std::function<AccessUnitSei(int)>& sei_for) {
    const NalCodec nc = nal_codec(codec);
    const AnnexBSplit split = split_annexb(stream.data(), stream.size());
    std::vector<uint8_t> out;
    int au = -1;
    bool au_has_vcl = false;
    AccessUnitSei pending;
    auto close_au = [&] {
        if (au >= 0 && !pending.suffix.empty()) {
            const auto nal = sei_nal_unit(codec, true, pending.suffix);
            out.insert(out.end(), nal.begin(), nal.end());
        }
    };
    for (const NalSpan& s : split.nals) {
        const uint8_t* nal = stream.data() + s.offset;
        NalHeader h;
        if (!parse_nal_header(nc, nal, s.size, h)) continue;
        const bool vcl = is_vcl(nc, h.type);
        const bool new_pic = vcl && vcl_starts_picture(nc, nal, s.size);
        if (au < 0 || (au_has_vcl && (starts_access_unit(nc, h.type) || new_pic))) {
            close_au();
            au++;
            au_has_vcl = false;
            pending = sei_for(au);
        }
        if (vcl && !au_has_vcl && !pending.prefix.empty()) {
            const auto sei = sei_nal_unit(codec, false, pending.prefix);
            out.insert(out.end(), sei.begin(), sei.end());
        }
        au_has_vcl = au_has_vcl || vcl;
        static const uint8_t start[] = {0, 0, 0, 1};
        out.insert(out.end(), start, start + 4);
        out.insert(out.end(), nal, nal + s.size);
    }
    close_au();
    return out;
}

std::vector<uint8_t> insert_av1_t35(const std::vector<uint8_t>& stream,
                                    const std::function<std::vector<std::vector<uint8_t>>(int)>& t35_for) {
    const bool ivf = looks_like_ivf(stream.data(), stream.size());
    if (!ivf && !looks_like_av1_low_overhead(stream.data(), stream.size()))
        throw Error(ErrorCode::kInvalidArgument, "T.35 insertion needs an IVF or low-overhead AV1 stream");
    const Av1Stream s =
        parse_av1_stream(stream.data(), stream.size(), ivf ? Av1Container::kIvf : Av1Container::kLowOverhead);
    std::vector<uint8_t> out;
    if (ivf) out.assign(stream.begin(), stream.begin() + 32);
    for (std::size_t k = 0; k < s.units.size(); k++) {
        const Av1TemporalUnit& tu = s.units[k];
        std::vector<uint8_t> body;
        bool inserted = false;
        const auto payloads = t35_for(int(k));
        for (const Av1Obu& obu : tu.obus) {
            const auto bytes = av1_obu_bytes(obu.type, obu.payload);
            body.insert(body.end(), bytes.begin(), bytes.end());
            if (obu.type == kObuTemporalDelimiter && !inserted) {
                for (const auto& t35 : payloads) {
                    const auto m = av1_obu_bytes(kObuMetadata, av1_t35_metadata_payload(t35));
                    body.insert(body.end(), m.begin(), m.end());
                }
                inserted = true;
            }
        }
        if (ivf) {
            const std::size_t at = out.size();
            out.resize(at + 12);
            put_le32(out, at, uint32_t(body.size()));
            for (int i = 0; i < 8; i++) out[at + 4 + i] = uint8_t(uint64_t(tu.pts.value_or(0)) >> (8 * i));
        }
        out.insert(out.end(), body.begin(), body.end());
    }
    return out;
}

}  // namespace filmgrain::bitstream

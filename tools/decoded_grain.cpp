#include "decoded_grain.hpp"

#ifdef FILMGRAIN_HAVE_LIBAV
#include "bitstream/av1_grain_extraction.hpp"
#include "filmgrain/error.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iterator>

namespace filmgrain::cli {

StreamMetadata read_stream_metadata(const std::string& path, const std::string& codec_name,
                                    const std::function<void(const std::string&)>& warn) {
    StreamMetadata m;
    if (codec_name != "h264" && codec_name != "hevc" && codec_name != "vvc" && codec_name != "av1") return m;
    try {
        m.scan = bitstream::scan_stream_file(path, std::nullopt);
    } catch (const Error&) {
        return m;
    }
    m.units = bitstream::units_in_output_order(m.scan);
    std::vector<std::string> warnings;
    m.afgs1 = bitstream::afgs1_payloads_in_output_order(m.scan, warnings);
    for (const std::string& w : warnings) warn(w);
    return m;
}

bool may_carry_afgs1(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return true;
    static constexpr uint8_t kHeader[4] = {0xB5, 0x58, 0x90, 0x01};
    std::vector<uint8_t> buf(std::size_t(1) << 20);
    std::size_t kept = 0;  // the last bytes of the previous chunk, so a header across chunks is found
    bool found = false;
    for (std::size_t n; !found && (n = std::fread(buf.data() + kept, 1, buf.size() - kept, f)) > 0;) {
        const std::size_t end = kept + n;
        found = std::search(buf.begin(), buf.begin() + long(end), std::begin(kHeader), std::end(kHeader)) !=
                buf.begin() + long(end);
        kept = std::min<std::size_t>(end, sizeof kHeader - 1);
        std::memmove(buf.data(), buf.data() + end - kept, kept);
    }
    const bool failed = std::ferror(f) != 0;
    std::fclose(f);
    return found || failed;
}

void take_afgs1_grain(libav::DecodedFrame& frame, const std::vector<std::optional<Afgs1Payload>>& afgs1, int width,
                      int height) {
    const std::size_t k = std::size_t(frame.index);
    if (frame.av1 || frame.fgc || k >= afgs1.size() || !afgs1[k]) return;
    Afgs1Picture pic;
    pic.width = width;
    pic.height = height;
    pic.format = frame.picture.format().chroma;
    pic.bit_depth = frame.picture.format().bit_depth;
    if (frame.matrix_coefficients != 2) pic.matrix_coefficients = frame.matrix_coefficients;
    if (const auto sel = select_afgs1_set(*afgs1[k], pic); sel && sel->params.apply_grain) {
        frame.av1 = sel->params;
        frame.matrix_coefficients = sel->matrix_coefficients;
    }
}

std::optional<FrameInfo> hand_exported_grain(Session& session, const libav::DecodedFrame& frame) {
    FrameInfo fi;
    if (frame.av1) {
        Av1FilmGrainParams p = *frame.av1;
        p.update_grain = 1;
        session.receive_av1_params(p, 0, frame.matrix_coefficients);
    } else if (frame.fgc) {
        session.receive_fgc_params(*frame.fgc, frame.fgc_codec);
        fi.ids = FgcPictureIds{int(frame.seed), 0};
    } else {
        return std::nullopt;
    }
    return fi;
}

}  // namespace filmgrain::cli
#endif

// Makes the Annex-B streams of the ffmpeg71-* conformance family: an encoder's
// stream with one FGC SEI (the project's writer) before the first VCL NAL unit of
// every access unit. Not part of the tool or the library; tools/make-ffmpeg-goldens runs it.
//
//   filmgrain_fgc_sei_stream IN OUT FGC.json [hevc|h264|vvc [EVERY]]
//
// EVERY: the SEI in every EVERY-th access unit only (0, EVERY, 2*EVERY...), so that the
// pictures between rely on persistence (tests/verify/decoder_acceptance.py).
//
// FGC.json holds the SEI's syntax elements in the project's JSON form (params convert).
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "bitstream/metadata_insertion.hpp"
#include "io/input_file.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/json_access.hpp"

int main(int argc, char** argv) {
    if (argc < 4 || argc > 6) {
        std::fprintf(stderr, "usage: %s IN OUT FGC.json [hevc|h264|vvc [EVERY]]\n", argv[0]);
        return 2;
    }
    try {
        const auto codec = filmgrain::bitstream::parse_stream_codec(argc >= 5 ? argv[4] : "hevc");
        int every = 1;
        if (argc == 6) {
            const std::string_view text(argv[5]);
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), every);
            if (ec != std::errc() || end != text.data() + text.size() || every < 1)
                throw std::runtime_error("EVERY '" + std::string(text) + "' is not a whole number 1.." +
                                         std::to_string(INT32_MAX));
        }
        if (codec == filmgrain::bitstream::StreamCodec::kAv1) throw std::runtime_error("AV1 carries no SEI (allowed hevc, h264, vvc)");
        const std::vector<uint8_t> in = filmgrain::read_whole_file(argv[1], std::size_t(1) << 30, "an Annex-B stream");
        const filmgrain::FgcParams params = filmgrain::fgc_params_from_json(filmgrain::read_json_file(argv[3]));
        filmgrain::bitstream::SeiMessage sei;
        sei.payload_type = 19;  // film_grain_characteristics
        sei.payload = filmgrain::write_fgc_sei_payload(params, filmgrain::bitstream::fgc_codec(codec));
        const std::vector<uint8_t> out = filmgrain::bitstream::insert_sei(
            in, codec, [&](int au) {
            if (au % every) return filmgrain::bitstream::AccessUnitSei{};
            return filmgrain::bitstream::AccessUnitSei{{sei}, {}};
        });
        std::ofstream of(argv[2], std::ios::binary);
        of.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
        if (!of) throw std::runtime_error(std::string("cannot write '") + argv[2] + "'");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filmgrain_fgc_sei_stream: %s\n", e.what());
        return 1;
    }
}

// Makes the H.265 / H.264 streams of the ffmpeg71-* conformance family: an encoder's
// Annex-B stream with one FGC SEI (the project's writer) before the first VCL NAL unit of
// every access unit. Not part of the tool or the library; tools/make-ffmpeg-goldens runs it.
//
//   filmgrain_fgc_sei_stream IN.h265|IN.h264 OUT FGC.json [hevc|h264]
//
// FGC.json holds the SEI's syntax elements in the project's JSON form (params convert).
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bitstream/metadata_insertion.hpp"
#include "filmgrain/error.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "nlohmann/json.hpp"

namespace {
std::vector<uint8_t> read_all(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot open '" + path + "'");
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 4 || argc > 5) {
        std::fprintf(stderr, "usage: %s IN OUT FGC.json [hevc|h264]\n", argv[0]);
        return 2;
    }
    try {
        const std::string codec_name = argc == 5 ? argv[4] : "hevc";
        if (codec_name != "hevc" && codec_name != "h264") throw std::runtime_error("codec '" + codec_name + "' (allowed hevc, h264)");
        const bool hevc = codec_name == "hevc";
        const std::vector<uint8_t> in = read_all(argv[1]);
        std::ifstream jf(argv[3]);
        if (!jf) throw std::runtime_error(std::string("cannot open '") + argv[3] + "'");
        const filmgrain::FgcParams params = filmgrain::fgc_params_from_json(nlohmann::json::parse(jf));
        filmgrain::bitstream::SeiMessage sei;
        sei.payload_type = 19;  // film_grain_characteristics
        sei.payload = filmgrain::write_fgc_sei_payload(params, hevc ? filmgrain::FgcCodec::kHevc : filmgrain::FgcCodec::kAvc);
        const std::vector<uint8_t> out = filmgrain::bitstream::insert_sei(
            in, hevc ? filmgrain::bitstream::StreamCodec::kH265 : filmgrain::bitstream::StreamCodec::kH264,
            [&](int) { return filmgrain::bitstream::AccessUnitSei{{sei}, {}}; });
        std::ofstream of(argv[2], std::ios::binary);
        of.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
        if (!of) throw std::runtime_error(std::string("cannot write '") + argv[2] + "'");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filmgrain_fgc_sei_stream: %s\n", e.what());
        return 1;
    }
}

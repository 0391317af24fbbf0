// FGC SEI payload parser (H.264/H.265/H.266 film_grain_characteristics()). The first
// byte picks the codec. A payload that parses must be rewritten identically after
// write -> parse -> write.
#include <cstdint>
#include <cstdlib>

#include "filmgrain/error.hpp"
#include "metadata/fgc_sei.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const filmgrain::FgcCodec codec = static_cast<filmgrain::FgcCodec>(data[0] % 3);
    try {
        const filmgrain::FgcParams p = filmgrain::parse_fgc_sei_payload(data + 1, size - 1, codec);
        const auto bytes = filmgrain::write_fgc_sei_payload(p, codec);
        if (filmgrain::write_fgc_sei_payload(filmgrain::parse_fgc_sei_payload(bytes, codec), codec) != bytes) std::abort();
    } catch (const filmgrain::Error&) {
    }
    return 0;
}

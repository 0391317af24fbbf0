// AFGS1 T.35 payload reader. The input is split into two payloads received by one
// reader (so stored sets, update_grain_flag = 0 and prediction are reached). Every
// payload that parses must be written back and re-read (from the same stored
// state) to the same sets; selection must not crash.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 2) return 0;
    const bool header = data[0] & 1;
    const std::size_t split = std::min<std::size_t>(data[1], size - 2);
    const uint8_t* body = data + 2;
    const std::size_t body_size = size - 2;
    filmgrain::Afgs1Reader reader;
    try {
        reader.receive(body, split, header);
    } catch (const filmgrain::Error&) {
    }
    const filmgrain::Afgs1Reader before = reader;
    filmgrain::Afgs1Payload got;
    try {
        got = reader.receive(body + split, body_size - split, header);
    } catch (const filmgrain::Error&) {
        return 0;
    }
    for (int f = 0; f < 4; ++f) {
        filmgrain::Afgs1Picture pic;
        pic.width = 1 + (data[0] >> 1) * 37;
        pic.height = 1 + (data[1] >> 1) * 29;
        pic.format = static_cast<filmgrain::ChromaFormat>(f);
        pic.bit_depth = 8 + 2 * (data[0] >> 6);
        (void)filmgrain::select_afgs1_set(got, pic);
    }
    filmgrain::Afgs1WriteOptions wo;
    wo.t35_header = header;
    const std::vector<uint8_t> bytes = filmgrain::write_afgs1(got, wo);
    filmgrain::Afgs1Reader again = before;
    if (!(again.receive(bytes, header) == got)) std::abort();
    return 0;
}

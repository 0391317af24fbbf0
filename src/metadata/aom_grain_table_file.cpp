// Reading a libaom grain table from a file: tool side (file I/O stays out of libfilmgrain,
// which parses the table's text: aom_grain_table.cpp).
#include <fstream>

#include "filmgrain/error.hpp"
#include "io/input_file.hpp"
#include "metadata/aom_grain_table.hpp"

namespace filmgrain {

AomGrainTable read_aom_grain_table(const std::string& path) {
    // bounded: a device such as /dev/zero or a huge file fails fast instead of filling memory
    const std::vector<uint8_t> bytes = read_whole_file(path, kDefaultMaxFileBytes, "a libaom grain table");
    try {
        return parse_aom_grain_table(std::string(bytes.begin(), bytes.end()));
    } catch (const Error& e) {
        throw Error(e.code(), path + ": " + e.what());
    }
}

void write_aom_grain_table(const AomGrainTable& table, const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(ErrorCode::kIo, "cannot open grain table '" + path + "' for writing");
    const std::string text = format_aom_grain_table(table);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out) throw Error(ErrorCode::kIo, "cannot write grain table '" + path + "'");
}

}  // namespace filmgrain

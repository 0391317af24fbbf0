// Whole-file reading: .xz decompression (liblzma; the conformance inputs are stored
// xz-compressed) and plain files, both bounded (input_file.hpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/input_file.hpp"

namespace filmgrain {
// The decompressed content of an .xz file: the compressed file at most kDefaultMaxFileBytes,
// the content at most kMaxXzContentBytes (1 GiB). Throws Error(kIo) naming the file.
inline constexpr std::size_t kMaxXzContentBytes = std::size_t(1) << 30;
std::vector<uint8_t> read_xz_file(const std::string& path);
// read_whole_file(path, kDefaultMaxFileBytes, "a file read whole"): at most 64 MiB.
std::vector<uint8_t> read_whole_file(const std::string& path);
}  // namespace filmgrain

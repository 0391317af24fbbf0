// Whole-file .xz decompression (liblzma); the conformance inputs are stored xz-compressed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace filmgrain {
std::vector<uint8_t> read_xz_file(const std::string& path);
std::vector<uint8_t> read_whole_file(const std::string& path);
}  // namespace filmgrain

// PNG files read back with libpng's own decoder, so that the tests judge what a viewer would
// show rather than trust the writer's bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace filmgrain::test_support {

struct DecodedPng {
    int width = 0, height = 0;
    int bit_depth = 0, color_type = -1;  // as the IHDR says
    std::vector<uint8_t> rgb;            // 8-bit RGB rows without padding
    const uint8_t* at(int x, int y) const { return &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3]; }
};

// Throws std::runtime_error naming the file when it is no PNG libpng decodes.
DecodedPng read_png(const std::string& path);

}  // namespace filmgrain::test_support

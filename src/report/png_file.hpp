// Pictures of the HTML reports (the analysis report's plots, the verification report's heat
// maps) as PNG files, written with libpng: one encoder for every report, and no image codec
// library (OpenCV's imgcodecs would bring GDAL and about 80 more shared libraries into every
// process of the tool) for a few 8-bit RGB pictures.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace filmgrain::report {

// An 8-bit RGB picture (3 bytes a pixel, R first; `stride` bytes from one row to the next,
// negative for bottom-up buffers) as a PNG at `path`, through OutputFile: no half-written
// file on failure. Throws Error(kIo) naming the file when it cannot be written,
// Error(kInvalidArgument) for an empty picture or a stride shorter than a row.
void write_png_rgb(const std::string& path, int width, int height, const uint8_t* rgb, std::ptrdiff_t stride);

}  // namespace filmgrain::report

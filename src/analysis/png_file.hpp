// The analysis report's pictures (OpenCV BGR matrices) as PNG files, through the reports'
// shared libpng writer (report/png_file.hpp) rather than OpenCV's own image codecs
// (opencv_imgcodecs would bring GDAL and about 80 more shared libraries into every process
// of the tool, for three 8-bit RGB pictures).
#pragma once
#include <string>

#include <opencv2/core.hpp>

namespace filmgrain::analysis {

// An 8-bit, 3-channel BGR picture (OpenCV's order) as an RGB PNG at `path`, through
// OutputFile (no half-written file on failure). Throws Error(kIo) naming the file.
void write_png_file(const std::string& path, const cv::Mat& bgr);

}  // namespace filmgrain::analysis

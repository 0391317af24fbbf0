#include "analysis/png_file.hpp"

#include <opencv2/imgproc.hpp>

#include "filmgrain/error.hpp"
#include "report/png_file.hpp"

namespace filmgrain::analysis {

void write_png_file(const std::string& path, const cv::Mat& bgr) {
    if (bgr.type() != CV_8UC3 || bgr.empty())
        throw Error(ErrorCode::kInternal, "write_png_file: '" + path + "' is not an 8-bit 3-channel picture");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    report::write_png_rgb(path, rgb.cols, rgb.rows, rgb.ptr<uint8_t>(0), std::ptrdiff_t(rgb.step));
}

}  // namespace filmgrain::analysis

#include "analysis/png_file.hpp"

#include <png.h>

#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

namespace filmgrain::analysis {
namespace {

struct PngFailure {
    char message[256] = "";
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
    auto* failure = static_cast<PngFailure*>(png_get_error_ptr(png));
    std::snprintf(failure->message, sizeof failure->message, "%s", message);
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: this frame holds nothing with a destructor, so the jump
// back into it skips none.
bool encode_png(std::FILE* file, const cv::Mat& rgb, PngFailure* failure) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, failure, on_png_error, on_png_warning);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, png_uint_32(rgb.cols), png_uint_32(rgb.rows), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < rgb.rows; y++) png_write_row(png, rgb.ptr<png_byte>(y));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void write_png_file(const std::string& path, const cv::Mat& bgr) {
    if (bgr.type() != CV_8UC3 || bgr.empty())
        throw Error(ErrorCode::kInternal, "write_png_file: '" + path + "' is not an 8-bit 3-channel picture");
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    OutputFile out(path);
    PngFailure failure;
    if (!encode_png(out.stream(), rgb, &failure))
        throw Error(ErrorCode::kIo, "cannot write '" + path + "'" +
                                        (failure.message[0] ? std::string(": ") + failure.message : std::string()));
    out.commit();
}

}  // namespace filmgrain::analysis

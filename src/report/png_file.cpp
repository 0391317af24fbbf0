#include "report/png_file.hpp"

#include <png.h>

#include <cstdio>
#include <cstdlib>

#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

namespace filmgrain::report {
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
bool encode_png(std::FILE* file, int width, int height, const uint8_t* rgb, std::ptrdiff_t stride,
                PngFailure* failure) {
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
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; y++) png_write_row(png, rgb + stride * y);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

void write_png_rgb(const std::string& path, int width, int height, const uint8_t* rgb, std::ptrdiff_t stride) {
    if (width <= 0 || height <= 0 || !rgb || std::abs(stride) < std::ptrdiff_t(width) * 3)
        throw Error(ErrorCode::kInvalidArgument, "write_png_rgb: '" + path + "': " + std::to_string(width) + "x" +
                                                     std::to_string(height) + " RGB picture with stride " +
                                                     std::to_string(stride) + " is empty or its rows overlap");
    OutputFile out(path);
    PngFailure failure;
    if (!encode_png(out.stream(), width, height, rgb, stride, &failure))
        throw Error(ErrorCode::kIo, "cannot write '" + path + "'" +
                                        (failure.message[0] ? std::string(": ") + failure.message : std::string()));
    out.commit();
}

}  // namespace filmgrain::report

#include "png_read_back.hpp"

#include <png.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

namespace filmgrain::test_support {

DecodedPng read_png(const std::string& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) throw std::runtime_error("cannot open '" + path + "'");
    uint8_t signature[8] = {};
    if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
        throw std::runtime_error("'" + path + "' has no PNG signature");
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    DecodedPng out;
    std::vector<png_bytep> rows;
    // libpng's default error handler longjmps here; everything with a destructor was made
    // before setjmp, so none is skipped.
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw std::runtime_error("libpng cannot decode '" + path + "'");
    }
    png_init_io(png, file.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    out.width = int(png_get_image_width(png, info));
    out.height = int(png_get_image_height(png, info));
    out.bit_depth = png_get_bit_depth(png, info);
    out.color_type = png_get_color_type(png, info);
    out.rgb.resize(std::size_t(out.width) * std::size_t(out.height) * 3);
    rows.resize(std::size_t(out.height));
    for (int y = 0; y < out.height; y++) rows[std::size_t(y)] = &out.rgb[std::size_t(y) * std::size_t(out.width) * 3];
    if (out.bit_depth != 8 || out.color_type != PNG_COLOR_TYPE_RGB) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw std::runtime_error("'" + path + "' is not 8-bit RGB");
    }
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return out;
}

}  // namespace filmgrain::test_support

// report::write_png_rgb: what libpng decodes from the file is the picture written (rows read
// through the stride), and a file that cannot be written fails naming it and leaves nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "error_message.hpp"
#include "filmgrain/error.hpp"
#include "png_read_back.hpp"
#include "report/png_file.hpp"

using namespace filmgrain;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("filmgrain-png-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

uint8_t pattern(int x, int y, int c) { return uint8_t(x * 40 + y * 7 + c * 90); }

TEST(PngFile, DecodesToThePixelsWrittenThroughTheStride) {
    const fs::path dir = fresh_dir("round-trip");
    const int width = 5, height = 3;
    const std::ptrdiff_t stride = width * 3 + 7;  // padded rows: only the picture's bytes are read
    std::vector<uint8_t> buffer(std::size_t(stride) * height, 0xEE);
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < 3; c++) buffer[std::size_t(y * stride + x * 3 + c)] = pattern(x, y, c);
    const fs::path file = dir / "picture.png";
    report::write_png_rgb(file.string(), width, height, buffer.data(), stride);

    const test_support::DecodedPng png = test_support::read_png(file.string());
    EXPECT_EQ(png.width, width);
    EXPECT_EQ(png.height, height);
    EXPECT_EQ(png.bit_depth, 8);
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++)
            for (int c = 0; c < 3; c++) ASSERT_EQ(png.at(x, y)[c], pattern(x, y, c)) << x << "," << y << " channel " << c;
    // nothing but the picture is left in the directory (no temporary)
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    fs::remove_all(dir);
}

TEST(PngFile, BottomUpBufferIsWrittenTopRowFirst) {
    const fs::path dir = fresh_dir("bottom-up");
    const uint8_t rows[2][3] = {{10, 20, 30}, {200, 210, 220}};  // memory order: bottom row first
    const fs::path file = dir / "flip.png";
    report::write_png_rgb(file.string(), 1, 2, rows[1], -3);
    const test_support::DecodedPng png = test_support::read_png(file.string());
    EXPECT_EQ(png.at(0, 0)[0], 200);
    EXPECT_EQ(png.at(0, 1)[2], 30);
    fs::remove_all(dir);
}

TEST(PngFile, UnwritableFileThrowsIoNamingItAndLeavesNothing) {
    const fs::path dir = fresh_dir("unwritable");
    const fs::path file = dir / "no-such-directory" / "picture.png";
    const uint8_t rgb[3] = {1, 2, 3};
    try {
        report::write_png_rgb(file.string(), 1, 1, rgb, 3);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kIo);
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(fs::exists(file.parent_path()));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 0);
    fs::remove_all(dir);
}

TEST(PngFile, OverlappingRowsAreRefusedBeforeAnythingIsWritten) {
    const fs::path dir = fresh_dir("bad-stride");
    const fs::path file = dir / "picture.png";
    const uint8_t rgb[12] = {};
    const std::string message =
        test_support::error_of([&] { report::write_png_rgb(file.string(), 4, 1, rgb, 6); });
    EXPECT_NE(message.find("picture.png"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(file));
    fs::remove_all(dir);
}

}  // namespace

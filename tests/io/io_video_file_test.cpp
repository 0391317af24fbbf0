// src/io: the Y4M header parser, the picture limit, bounded whole-file reads, cancellable
// reads and the reader/writer pair for every format.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <thread>

#include "error_message.hpp"
#include "core/frame_buffer.hpp"
#include "filmgrain/error.hpp"
#include "io/input_file.hpp"
#include "io/video_file.hpp"
#include "io/xz_file.hpp"
#include "io/y4m_header.hpp"

using namespace filmgrain;
namespace fs = std::filesystem;

namespace {

using filmgrain::test_support::error_of;

fs::path temp_dir() {
    const fs::path d = fs::temp_directory_path() / ("filmgrain-io-" + std::to_string(::getpid()) + "-" +
                                                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

TEST(IoY4mHeader, ReadsWhatFfmpegWrites) {
    const Y4mHeader h = parse_y4m_header("YUV4MPEG2 W48 H32 F30000:1001 Ip A0:0 C420p10 XYSCSS=420P10 XCOLORRANGE=LIMITED");
    EXPECT_EQ(h.width, 48);
    EXPECT_EQ(h.height, 32);
    EXPECT_EQ(h.fps_num, 30000);
    EXPECT_EQ(h.fps_den, 1001);
    EXPECT_EQ(h.format.chroma, ChromaFormat::k420);
    EXPECT_EQ(h.format.bit_depth, 10);
    EXPECT_EQ(h.extra, " Ip A0:0 XCOLORRANGE=LIMITED");  // XYSCSS repeats C: the writer writes C

    const Y4mHeader g = parse_y4m_header("YUV4MPEG2 W16 H8 F25:1 Ip A0:0 Cmono16");
    EXPECT_EQ(g.format.chroma, ChromaFormat::k400);
    EXPECT_EQ(g.format.bit_depth, 16);
    // no C: 4:2:0 8-bit; no F, or F0:0: unknown
    const Y4mHeader d = parse_y4m_header("YUV4MPEG2 W2 H2");
    EXPECT_EQ(d.format.chroma, ChromaFormat::k420);
    EXPECT_EQ(d.format.bit_depth, 8);
    EXPECT_EQ(d.fps_num, 0);
    EXPECT_EQ(parse_y4m_header("YUV4MPEG2 W2 H2 F0:0").fps_num, 0);
    EXPECT_EQ(parse_y4m_header("YUV4MPEG2 W2 H2 F2147483647:1").fps_num, 2147483647);
    EXPECT_EQ(parse_y4m_header("YUV4MPEG2  W65536  H4096 ").width, 65536);
}

TEST(IoY4mHeader, ColourTagsAreFfmpegsAndReadBack) {
    const struct {
        ChromaFormat c;
        int depth;
        const char* tag;
    } tags[] = {
        {ChromaFormat::k400, 8, "mono"},      {ChromaFormat::k400, 10, "mono10"},   {ChromaFormat::k400, 12, "mono12"},
        {ChromaFormat::k400, 16, "mono16"},   {ChromaFormat::k420, 8, "420jpeg"},   {ChromaFormat::k420, 10, "420p10"},
        {ChromaFormat::k420, 12, "420p12"},   {ChromaFormat::k420, 16, "420p16"},   {ChromaFormat::k422, 8, "422"},
        {ChromaFormat::k422, 10, "422p10"},   {ChromaFormat::k422, 12, "422p12"},   {ChromaFormat::k422, 16, "422p16"},
        {ChromaFormat::k444, 8, "444"},       {ChromaFormat::k444, 10, "444p10"},   {ChromaFormat::k444, 12, "444p12"},
        {ChromaFormat::k444, 16, "444p16"},
    };
    for (const auto& t : tags) {
        EXPECT_EQ(y4m_colorspace_tag(PixelFormat{t.c, t.depth}), t.tag);
        const PixelFormat f = parse_y4m_colorspace(t.tag);
        EXPECT_EQ(f.chroma, t.c) << t.tag;
        EXPECT_EQ(f.bit_depth, t.depth) << t.tag;
    }
    // what filmgrain wrote before, and the other 4:2:0 siting names
    EXPECT_EQ(parse_y4m_colorspace("monop16").bit_depth, 16);
    EXPECT_EQ(parse_y4m_colorspace("monop10").chroma, ChromaFormat::k400);
    EXPECT_EQ(parse_y4m_colorspace("420mpeg2").bit_depth, 8);
    EXPECT_EQ(parse_y4m_colorspace("420paldv").chroma, ChromaFormat::k420);
    EXPECT_EQ(parse_y4m_colorspace("422p9").bit_depth, 9);
    EXPECT_EQ(parse_y4m_colorspace("444p14").bit_depth, 14);
}

TEST(IoY4mHeader, NumbersAreStrictAndErrorsNameTagValueAndRange) {
    const struct {
        const char* line;
        const char* message;
    } cases[] = {
        {"YUV4MPEG2 W4294967312 H16", "Y4M header tag W: value '4294967312' is out of range (allowed 1..65536)"},
        {"YUV4MPEG2 W16 H0", "Y4M header tag H: value '0' is out of range (allowed 1..65536)"},
        {"YUV4MPEG2 W+16 H16", "Y4M header tag W: value '+16' is not a number (allowed 1..65536)"},
        {"YUV4MPEG2 W H16", "Y4M header tag W: value '' is not a number"},
        {"YUV4MPEG2 W16 H16 F30:0", "Y4M header tag F: value '30:0' is out of range"},
        {"YUV4MPEG2 W16 H16 F0:1", "Y4M header tag F: value '0:1' is out of range"},
        {"YUV4MPEG2 W16 H16 F2147483648:1", "Y4M header tag F: value '2147483648:1' is out of range (allowed N:D with N and D 1..2147483647, or 0:0 for unknown)"},
        {"YUV4MPEG2 W16 H16 F25:1x", "Y4M header tag F: value '25:1x' is not a number"},
        {"YUV4MPEG2 W16 H16 F25", "Y4M header tag F: value '25' is not a frame rate"},
        {"YUV4MPEG2 W16 H16 C420p", "Y4M header tag C: value '420p' is not supported"},
        {"YUV4MPEG2 W16 H16 C420p8", "Y4M header tag C: value '420p8' is not supported"},
        {"YUV4MPEG2 W16 H16 Cmono0", "Y4M header tag C: value 'mono0' is not supported"},
        {"YUV4MPEG2 W16 H16 C444alpha", "Y4M header tag C: value '444alpha' is not supported (allowed 420jpeg, 420paldv"},
        {"YUV4MPEG2 W16 H16 C411", "Y4M header tag C: value '411' is not supported"},
        {"YUV4MPEG2 W16", "Y4M header has no H (height) tag"},
        {"YUV4MPEG2 H16", "Y4M header has no W (width) tag"},
        {"YUV4MPEG2 W65536 H65536", "picture size 65536x65536 is out of range (allowed width and height 1..65536 and at most 268435456"},
        {"YUV4MPEGX W16 H16", "does not start with YUV4MPEG2"},
        {"YUV4MPEG2W16 H16", "is not YUV4MPEG2 followed by a space"},
        {"YUV4MPEG2 W16 H16 I\x01", "holds a control character"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of([&] { parse_y4m_header(c.line); });
        EXPECT_NE(e.find(c.message), std::string::npos) << c.line << " -> " << e;
    }
    EXPECT_NE(error_of([] { parse_y4m_header("YUV4MPEG2 W16 H16 I" + std::string(5000, 'p')); }).find("longer than 4096"),
              std::string::npos);
}

TEST(IoY4mHeader, FrameHeaders) {
    EXPECT_NO_THROW(parse_y4m_frame_header("FRAME"));
    EXPECT_NO_THROW(parse_y4m_frame_header("FRAME Ixyz"));
    EXPECT_NE(error_of([] { parse_y4m_frame_header("FRAMES"); }).find("is not FRAME"), std::string::npos);
    EXPECT_NE(error_of([] { parse_y4m_frame_header("FRA"); }).find("is not FRAME"), std::string::npos);
    EXPECT_NE(error_of([] { parse_y4m_frame_header(std::string("FRAME\0", 6)); }).find("'FRAME\\x00'"), std::string::npos);
}

TEST(IoFrameBuffer, PictureLimit) {
    EXPECT_NO_THROW(check_picture_size(16384, 16384));
    EXPECT_NO_THROW(check_picture_size(65536, 4096));
    EXPECT_NO_THROW(check_picture_size(1, 65536));
    for (auto [w, h] : {std::pair{0, 1}, {1, 0}, {65537, 1}, {1, 65537}, {16385, 16384}, {65536, 4097}, {-1, 5}}) {
        const std::string e = error_of([&] { check_picture_size(w, h); });
        EXPECT_NE(e.find("picture size " + std::to_string(w) + "x" + std::to_string(h) + " is out of range"),
                  std::string::npos)
            << e;
        EXPECT_NE(e.find("268435456"), std::string::npos) << e;
        EXPECT_NE(error_of([&] { FrameBuffer(w, h, PixelFormat{}); }), "");
        EXPECT_NE(error_of([&] { FrameBuffer::uninitialized(w, h, PixelFormat{}); }), "");
    }
    // the zero-filling constructor still zero-fills; the other has the same geometry
    FrameBuffer z(33, 17, PixelFormat{ChromaFormat::k422, 10});
    for (std::size_t i = 0; i < z.byte_size(); i++) ASSERT_EQ(z.bytes()[i], 0);
    FrameBuffer u = FrameBuffer::uninitialized(33, 17, PixelFormat{ChromaFormat::k422, 10});
    EXPECT_EQ(u.byte_size(), z.byte_size());
    EXPECT_EQ(u.plane_offset(2), z.plane_offset(2));
    FrameBuffer copy = z;
    EXPECT_EQ(copy.byte_size(), z.byte_size());
}

// Every picture starts on a cache line, the small ones from the heap and the large ones malloc
// would map at 16 mod 64, copies and moves included.
TEST(IoFrameBuffer, StartsOnACacheLine) {
    std::vector<FrameBuffer> frames;
    for (auto [w, h] : {std::pair{1, 1}, {33, 17}, {640, 360}, {1920, 1080}, {3840, 2160}, {720, 576}})
        for (int bd : {8, 10}) {
            frames.emplace_back(w, h, PixelFormat{ChromaFormat::k420, bd});
            frames.push_back(FrameBuffer::uninitialized(w, h, PixelFormat{ChromaFormat::k444, bd}));
            frames.push_back(frames.back());
        }
    for (const FrameBuffer& f : frames)
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(f.bytes()) % kFrameAlignment, 0u)
            << f.width() << "x" << f.height() << " at " << static_cast<const void*>(f.bytes());
}

TEST(IoReadWholeFile, BoundedOnDevicesAndFiles) {
    const std::string e = error_of([] { read_whole_file("/dev/zero", 1 << 20, "a test input"); });
    EXPECT_NE(e.find("'/dev/zero' holds more than 1048576 bytes (1 MiB); the limit for a test input is 1048576 bytes (1 MiB)"),
              std::string::npos)
        << e;
    const fs::path d = temp_dir();
    std::ofstream(d / "f.bin", std::ios::binary) << std::string(5000, 'a');
    EXPECT_EQ(read_whole_file((d / "f.bin").string(), 5000, "x").size(), 5000u);
    const std::string big = error_of([&] { read_whole_file((d / "f.bin").string(), 4999, "a payload"); });
    EXPECT_NE(big.find("holds 5000 bytes; the limit for a payload is 4999 bytes"), std::string::npos) << big;
    EXPECT_EQ(read_whole_file((d / "f.bin").string()).size(), 5000u);  // the one-argument form: 64 MiB
    EXPECT_EQ(kDefaultMaxFileBytes, std::size_t(64) << 20);
    EXPECT_NE(error_of([&] { read_whole_file((d / "missing").string()); }).find("cannot open input"), std::string::npos);
    EXPECT_NE(error_of([&] { read_whole_file(d.string()); }).find("is a directory"), std::string::npos);
    fs::remove_all(d);
}

// A read waiting on a pipe that delivers nothing ends as soon as its cancellation is
// cancelled from another thread (the frame pipeline's failure path).
TEST(IoInputFile, CancelledReadOnAQuietPipeEndsPromptly) {
    const fs::path d = temp_dir();
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ASSERT_EQ(::write(fds[1], "abc", 3), 3);
    const std::string path = "/dev/fd/" + std::to_string(fds[0]);
    InputFile in(path);
    EXPECT_FALSE(in.is_regular());
    EXPECT_FALSE(in.remaining().has_value());
    ReadCancellation cancel;
    std::string error;
    std::size_t first = 0;
    const auto start = std::chrono::steady_clock::now();
    std::thread reader([&] {
        ReadCancellation::Scope scope(cancel);
        char buf[16];
        try {
            first = in.read(buf, 3);
            in.read(buf, 16);  // waits: the writer keeps the pipe open
        } catch (const Error& e) {
            error = e.what();
        }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    cancel.cancel();
    reader.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(first, 3u);
    EXPECT_NE(error.find("was cancelled"), std::string::npos) << error;
    EXPECT_LT(seconds, 5.0);
    EXPECT_TRUE(cancel.cancelled());
    EXPECT_EQ(ReadCancellation::current(), nullptr);
    ::close(fds[1]);
    fs::remove_all(d);
}

TEST(IoInputFile, RegularFilesTellWhatIsLeft) {
    const fs::path d = temp_dir();
    std::ofstream(d / "f.bin", std::ios::binary) << "YUV4MPEG2 W2 H2\nFRAME\n" << std::string(6, 'x');
    InputFile in((d / "f.bin").string());
    EXPECT_TRUE(in.is_regular());
    EXPECT_EQ(in.remaining(), std::optional<uint64_t>(28));
    EXPECT_EQ(in.peek(), 'Y');
    EXPECT_EQ(in.get(), 'Y');
    EXPECT_EQ(in.remaining(), std::optional<uint64_t>(27));
    char buf[32];
    EXPECT_EQ(in.read(buf, 15), 15u);
    EXPECT_EQ(in.remaining(), std::optional<uint64_t>(12));
    EXPECT_EQ(in.read(buf, 32), 12u);
    EXPECT_EQ(in.get(), -1);
    fs::remove_all(d);
}

// Every format through VideoWriter and VideoReader, raw and Y4M: the same samples, the
// header FFmpeg's names, and the reader's size checks against the file.
TEST(IoVideoFile, EveryFormatRoundTrips) {
    const fs::path d = temp_dir();
    std::mt19937 rng(7);
    for (ChromaFormat c : {ChromaFormat::k400, ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444})
        for (int depth : {8, 10, 12, 16})
            for (bool y4m : {false, true}) {
                const PixelFormat f{c, depth};
                SCOPED_TRACE(pix_fmt_name(f) + (y4m ? " y4m" : " raw"));
                VideoInfo info;
                info.width = 18;
                info.height = 10;
                info.format = f;
                std::vector<FrameBuffer> frames;
                for (int k = 0; k < 2; k++) {
                    FrameBuffer fb(18, 10, f);
                    for (std::size_t i = 0; i < fb.byte_size(); i += depth > 8 ? 2 : 1) {
                        const unsigned v = rng() & ((1u << depth) - 1);
                        fb.bytes()[i] = uint8_t(v);
                        if (depth > 8) fb.bytes()[i + 1] = uint8_t(v >> 8);
                    }
                    frames.push_back(fb);
                }
                const std::string path = (d / (y4m ? "v.y4m" : "v.yuv")).string();
                {
                    VideoWriter w(path, info, y4m);
                    for (const auto& fb : frames) w.write(fb);
                    w.commit();
                }
                VideoReader r(path, info);
                EXPECT_EQ(r.info().y4m, y4m);
                EXPECT_EQ(r.info().format.chroma, c);
                EXPECT_EQ(r.info().format.bit_depth, depth);
                FrameBuffer got;
                for (const auto& fb : frames) {
                    ASSERT_TRUE(r.read(got));
                    ASSERT_EQ(got.byte_size(), fb.byte_size());
                    EXPECT_TRUE(std::equal(fb.bytes(), fb.bytes() + fb.byte_size(), got.bytes()));
                }
                EXPECT_FALSE(r.read(got));
                if (y4m) {
                    std::ifstream in(path);
                    std::string header;
                    std::getline(in, header);
                    EXPECT_NE(header.find(" C" + y4m_colorspace_tag(f)), std::string::npos) << header;
                }
            }
    fs::remove_all(d);
}

TEST(IoVideoFile, ShortFilesFailBeforeTheFrameIsAllocated) {
    const fs::path d = temp_dir();
    std::ofstream(d / "t.yuv", std::ios::binary) << std::string(1000, 'x');
    VideoInfo info;
    info.width = 16384;
    info.height = 16384;
    info.format = PixelFormat{ChromaFormat::k444, 16};
    VideoReader r((d / "t.yuv").string(), info);
    FrameBuffer fb;
    const std::string e = error_of([&] { r.read(fb); });
    EXPECT_NE(e.find("holds 1000 bytes, less than one 16384x16384 yuv444p16le frame (1610612736 bytes)"),
              std::string::npos)
        << e;
    EXPECT_EQ(fb.byte_size(), 0u);  // nothing allocated
    // a truncated later frame keeps its message
    info.width = 10;
    info.height = 10;
    info.format = PixelFormat{ChromaFormat::k400, 8};
    VideoReader r2((d / "t.yuv").string(), info);
    for (int k = 0; k < 10; k++) ASSERT_TRUE(r2.read(fb));
    EXPECT_FALSE(r2.read(fb));
    std::ofstream(d / "t.yuv", std::ios::binary) << std::string(150, 'x');
    VideoReader r3((d / "t.yuv").string(), info);
    ASSERT_TRUE(r3.read(fb));
    EXPECT_NE(error_of([&] { r3.read(fb); }).find("is truncated: frame 1 has 50 of 100 bytes (10x10 gray)"),
              std::string::npos);
    // raw sizes beyond the limit fail when the reader is made
    info.width = 65536;
    info.height = 65536;
    EXPECT_NE(error_of([&] { VideoReader((d / "t.yuv").string(), info); }).find("picture size 65536x65536"),
              std::string::npos);
    fs::remove_all(d);
}

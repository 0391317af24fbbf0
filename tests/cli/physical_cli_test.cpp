// `filmgrain render`, `stats` and `tradeoff` as other tools call them: outputs that exist and
// carry the expected grain, clear errors with a non-zero exit and no half-written output.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "conformance_case.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

class PhysicalCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-phys-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
        // two 64x48 yuv420p frames: luma 128, chroma 128
        std::ofstream f(dir / "in.y4m", std::ios::binary);
        f << "YUV4MPEG2 W64 H48 F25:1 C420jpeg\n";
        for (int k = 0; k < 2; k++) f << "FRAME\n" << std::string(64 * 48 * 3 / 2, char(128));
    }
    void TearDown() override { fs::remove_all(dir); }
    int run(const std::string& args, std::string* log) {
        return run_command(std::string("'") + FILMGRAIN_TOOL_PATH + "' " + args, log);
    }
    std::size_t header_length(const std::string& name) const {
        std::ifstream f(dir / name);
        std::string line;
        std::getline(f, line);
        return line.size() + 1;
    }
    std::string p(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
    fs::path dir;
};

TEST_F(PhysicalCli, RenderVideoThenStatsSeeTheGrain) {
    std::string log;
    ASSERT_EQ(run("render " + p("in.y4m") + " -o " + p("out.y4m") + " --radius 0.2 --samples 64", &log), 0) << log;
    EXPECT_NE(log.find("N used per pixel 64.0"), std::string::npos) << log;
    ASSERT_TRUE(fs::exists(dir / "out.y4m"));
    EXPECT_EQ(fs::file_size(dir / "out.y4m") - header_length("out.y4m"), fs::file_size(dir / "in.y4m") - header_length("in.y4m"));
    ASSERT_EQ(run("stats --json " + p("in.y4m") + " " + p("out.y4m") + " > " + p("stats.json"), &log), 0) << log;
    nlohmann::json j;
    std::ifstream(dir / "stats.json") >> j;
    const double var = j["autocovariance"]["rows_dy_from_minus_max"][4][4];
    EXPECT_GT(var, 1e-4);  // grain std of a few code values
    // new grain every frame: frame-to-frame correlation near 0 (3072 pixels: |r| < 0.15)
    EXPECT_LT(std::abs(j["frame_to_frame_correlation"].get<double>()), 0.15);
}

TEST_F(PhysicalCli, RenderRoiAndTolerance) {
    std::string log;
    ASSERT_EQ(run("render " + p("in.y4m") + " -o " + p("roi.y4m") + " --roi 8,4,32,16 --tolerance 0.05", &log), 0) << log;
    EXPECT_NE(log.find("N used per pixel"), std::string::npos) << log;
    EXPECT_EQ(fs::file_size(dir / "roi.y4m") - header_length("roi.y4m"), 2u * (6 + 32 * 16 * 3 / 2));
    std::ifstream f(dir / "roi.y4m");
    std::string header;
    std::getline(f, header);
    EXPECT_NE(header.find(" W32 H16 "), std::string::npos) << header;
}

TEST_F(PhysicalCli, BadParametersFailWithoutOutput) {
    std::string log;
    EXPECT_EQ(run("render " + p("in.y4m") + " -o " + p("bad.y4m") + " --radius -2", &log), 2);
    EXPECT_NE(log.find("radius_mean = -2"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "bad.y4m"));
    EXPECT_NE(run("render " + p("in.y4m") + " -o " + p("bad.y4m") + " --roi 60,0,10,10", &log), 0);
    EXPECT_NE(log.find("--roi"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "bad.y4m"));
    EXPECT_NE(run("render " + p("in.y4m") + " -o " + p("bad.y4m") + " --samples 5 --tolerance 0.1", &log), 0);
    EXPECT_FALSE(fs::exists(dir / "bad.y4m"));
}

TEST_F(PhysicalCli, RenderStills) {
    // an 8-bit grey PGM (OpenImageIO reads PNM) of a left/right step 64 | 192
    {
        std::ofstream f(dir / "in.pgm", std::ios::binary);
        f << "P5\n64 48\n255\n";
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 64; x++) f << char(x < 32 ? 64 : 192);
    }
    std::string log;
#ifdef FILMGRAIN_HAVE_OIIO
    for (const char* out : {"out.png", "out.tif", "out.exr"}) {
        ASSERT_EQ(run("render " + p("in.pgm") + " -o " + p(out) + " --radius 0.3 --samples 32 -q", &log), 0) << out << log;
        EXPECT_TRUE(fs::exists(dir / out)) << out;
    }
    // into a pipe: the reader gets the same PNG and the pipe stays a pipe (a temporary renamed
    // over it would replace it)
    {
        int status;
        bool still_fifo;
        const std::string png = read_through_fifo(
            (dir / "pipe.png").string(),
            "'" + std::string(FILMGRAIN_TOOL_PATH) + "' render " + p("in.pgm") + " -o " + p("pipe.png") +
                " --radius 0.3 --samples 32 -q",
            &status, &still_fifo, &log);
        EXPECT_EQ(status, 0) << log;
        EXPECT_TRUE(still_fifo);
        std::ifstream f(dir / "out.png", std::ios::binary);
        const std::string file((std::istreambuf_iterator<char>(f)), {});
        EXPECT_EQ(png.size(), file.size());
        EXPECT_TRUE(png == file);
    }
    ASSERT_EQ(run("render " + p("in.pgm") + " -o " + p("zoom.png") + " --zoom 2 --samples 16 --roi 10,10,40,30 -q", &log), 0) << log;
    ASSERT_EQ(run("stats --json --bins 4 " + p("in.pgm") + " " + p("out.png") + " > " + p("s.json"), &log), 0) << log;
    nlohmann::json j;
    std::ifstream(dir / "s.json") >> j;
    // the dark half (bin [0.25, 0.5)) and the bright half (bin [0.75, 1)) both carry grain
    ASSERT_EQ(j["variance_vs_intensity"].size(), 2u);
    for (const auto& b : j["variance_vs_intensity"]) {
        EXPECT_EQ(b["count"].get<int>(), 32 * 48);
        EXPECT_GT(b["variance"].get<double>(), 1e-4);
        EXPECT_LT(std::abs(b["mean"].get<double>()), 0.02);  // the Boolean model keeps the mean
    }
#else
    EXPECT_NE(run("render " + p("in.pgm") + " -o " + p("out.png"), &log), 0);
    EXPECT_NE(log.find("OpenImageIO"), std::string::npos) << log;
#endif
    EXPECT_NE(run("render " + p("missing.png") + " -o " + p("never.png"), &log), 0);
    EXPECT_FALSE(fs::exists(dir / "never.png"));
}

// Stills go through the image module (tools/image_module.hpp), which the tool loads only
// when a command reads or writes one: without it, still commands fail naming the module and
// the paths tried, and video commands are unaffected.
TEST_F(PhysicalCli, StillsWithoutTheImageModuleFailClearlyAndVideoStillWorks) {
    {
        std::ofstream f(dir / "in.pgm", std::ios::binary);
        f << "P5\n16 8\n255\n" << std::string(16 * 8, char(100));
    }
    const std::string missing = (dir / "nowhere" / "filmgrain-oiio.so").string();
    const std::string env = "FILMGRAIN_IMAGE_MODULE='" + missing + "' ";
    std::string log;
    EXPECT_EQ(run_command(env + "'" + FILMGRAIN_TOOL_PATH + "' render " + p("in.pgm") + " -o " + p("out.png") + " -q", &log),
              1)
        << log;
    EXPECT_NE(log.find(missing + " does not exist"), std::string::npos) << log;
    EXPECT_NE(log.find("in.pgm"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.png"));
    ASSERT_EQ(run_command(env + "'" + FILMGRAIN_TOOL_PATH + "' render " + p("in.y4m") + " -o " + p("out.y4m") +
                              " --radius 0.2 --samples 8 -q",
                          &log),
              0)
        << log;
    EXPECT_TRUE(fs::exists(dir / "out.y4m"));
}

TEST_F(PhysicalCli, TradeoffWritesTableWithEveryMethod) {
    std::string log;
    ASSERT_EQ(run("tradeoff --skip-benchmark --size 256x128 --boolean-size 32 --samples 8 32 --frames 1 --output " +
                      p("T.md") + " --plot " + p("t.png"),
                  &log),
              0)
        << log;
    std::ifstream f(dir / "T.md");
    const std::string md((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    for (const char* m : {"Boolean model, N=8", "Boolean model, N=32", "Gaussian approximation", "FGC SEI, rdd5",
                          "FGC SEI, vtm", "FGC SEI, vfgs", "AV1 / AFGS1"})
        EXPECT_NE(md.find(m), std::string::npos) << m;
#ifdef FILMGRAIN_HAVE_OIIO
    // the plot, a whole PNG (signature first, IEND chunk last), linked from the table
    auto whole_png = [](const std::string& b) {
        return b.size() > 20 && b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 && b.compare(b.size() - 8, 4, "IEND") == 0;
    };
    {
        std::ifstream png(dir / "t.png", std::ios::binary);
        EXPECT_TRUE(whole_png(std::string((std::istreambuf_iterator<char>(png)), {})));
        EXPECT_NE(md.find("](t.png)"), std::string::npos) << md;
    }
    // and into a pipe: written straight into it, the pipe left a pipe
    int status;
    bool still_fifo;
    const std::string piped = read_through_fifo(
        (dir / "plot.png").string(),
        "'" + std::string(FILMGRAIN_TOOL_PATH) + "' tradeoff --skip-benchmark --size 256x128 --boolean-size 32 " +
            "--samples 8 --frames 1 --output " + p("T2.md") + " --plot " + p("plot.png"),
        &status, &still_fifo, &log);
    EXPECT_EQ(status, 0) << log;
    EXPECT_TRUE(still_fifo);
    EXPECT_TRUE(whole_png(piped)) << piped.size() << " bytes";
#endif
}

}  // namespace

// Standard input is read once: the job that learns the clip's shape must hand its reader on
// (a second open of "-" finds no Y4M header), for render and for analyze.
TEST_F(PhysicalCli, RenderAndAnalyzeReadStandardInput) {
    std::string log;
    ASSERT_EQ(run("render - -o " + p("stdin.y4m") + " --samples 16 -q < " + p("in.y4m"), &log), 0) << log;
    ASSERT_EQ(run("render " + p("in.y4m") + " -o " + p("file.y4m") + " --samples 16 -q", &log), 0) << log;
    std::ifstream a(dir / "stdin.y4m", std::ios::binary), b(dir / "file.y4m", std::ios::binary);
    const std::string from_stdin((std::istreambuf_iterator<char>(a)), {}), from_file((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(from_stdin.empty());
    EXPECT_EQ(from_stdin, from_file);
    const int rc = run("analyze - --model av1 --spatial -q -o " + p("stdin.json") + " < " + p("in.y4m"), &log);
    if (log.find("needs OpenCV") == std::string::npos) {
        ASSERT_EQ(rc, 0) << log;
        EXPECT_TRUE(fs::exists(dir / "stdin.json"));
    }
}

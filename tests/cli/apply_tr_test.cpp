// `filmgrain apply` with what only some flavours synthesize: film_grain_model_id 1 and
// blending_mode_id 1 (accepted by tr, model 1 by vfgs; rejected by rdd5 and vtm with a
// message, or passed through on request), single-line blocks, the block size with vfgs,
// and vfgs pattern interpolation, with a statistics test that it removes the visible
// template switch at an interval boundary.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "conformance_case.hpp"
#include "io/xz_file.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

class ApplyTrCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-cli-tr-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
        // two 176x144 yuv420p frames: a luma ramp, neutral chroma
        std::string frame(176 * 144 * 3 / 2, char(128));
        for (int y = 0; y < 144; y++)
            for (int x = 0; x < 176; x++) frame[std::size_t(y) * 176 + x] = char(40 + x);
        std::ofstream(dir / "in.yuv", std::ios::binary) << frame << frame;
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
    int run(const std::string& args, std::string* log) {
        return run_command(std::string("'") + FILMGRAIN_TOOL_PATH + "' apply " + args, log);
    }
    std::string base(const std::string& params) const {
        return "-i '" + path("in.yuv") + "' -o '" + path("out.yuv") + "' --size 176x144 --pix-fmt yuv420p --params '" +
               path(params) + "' ";
    }
    bool output_is_input() const {
        return filmgrain::read_whole_file(path("out.yuv")) == filmgrain::read_whole_file(path("in.yuv"));
    }
    fs::path dir;
};

// Luma-only, so that vfgs (model 1 only for luma) takes it too.
const char* kModel1 = R"({"film_grain_model_id": 1, "log2_scale_factor": 5, "comp_model_present_flag": [1, 0, 0],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [5, 0, 0],
  "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
  "comp_model_value": [[[200, 10, 0, 3, 32, -2]], [], []]})";

const char* kMultiplicative = R"({"blending_mode_id": 1, "log2_scale_factor": 5, "comp_model_present_flag": [1, 1, 1],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [0], [0]], "intensity_interval_upper_bound": [[255], [255], [255]],
  "comp_model_value": [[[200, 8, 8]], [[100]], [[100]]]})";

}  // namespace

TEST_F(ApplyTrCli, AutoRegressiveModelIsSynthesizedByTrAndVfgsAndRejectedByRdd5AndVtm) {
    write("p.json", kModel1);
    std::string log;
    for (const char* flavour : {"rdd5", "vtm"}) {
        log.clear();
        EXPECT_NE(run(base("p.json") + "--flavour " + flavour, &log), 0) << flavour;
        EXPECT_NE(log.find(std::string("film_grain_model_id = 1 is not supported by the ") + flavour + " flavour"),
                  std::string::npos)
            << log;
        EXPECT_NE(log.find("--flavour tr"), std::string::npos) << log;
        EXPECT_FALSE(fs::exists(dir / "out.yuv"));
        // as the reference decoders do it, on request: the pictures pass through untouched
        log.clear();
        ASSERT_EQ(run(base("p.json") + "--flavour " + flavour + " --on-invalid passthrough", &log), 0) << log;
        EXPECT_TRUE(output_is_input()) << flavour;
        EXPECT_NE(log.find("film grain not applied: film_grain_model_id = 1"), std::string::npos) << log;
        fs::remove(dir / "out.yuv");
    }
    for (const char* flavour : {"tr", "vfgs"}) {
        log.clear();
        ASSERT_EQ(run(base("p.json") + "--flavour " + flavour, &log), 0) << flavour << ": " << log;
        EXPECT_EQ(fs::file_size(dir / "out.yuv"), 2u * 176 * 144 * 3 / 2);
        EXPECT_FALSE(output_is_input()) << flavour;
        fs::remove(dir / "out.yuv");
    }
}

TEST_F(ApplyTrCli, MultiplicativeBlendingIsSynthesizedByTrOnly) {
    write("p.json", kMultiplicative);
    std::string log;
    for (const char* flavour : {"rdd5", "vtm", "vfgs"}) {
        log.clear();
        EXPECT_NE(run(base("p.json") + "--flavour " + flavour, &log), 0) << flavour;
        EXPECT_NE(log.find("blending_mode_id = 1"), std::string::npos) << log;
        EXPECT_FALSE(fs::exists(dir / "out.yuv"));
    }
    for (const char* flavour : {"rdd5", "vtm"}) {
        log.clear();
        ASSERT_EQ(run(base("p.json") + "--flavour " + flavour + " --on-invalid passthrough", &log), 0) << log;
        EXPECT_TRUE(output_is_input()) << flavour;
        fs::remove(dir / "out.yuv");
    }
    ASSERT_EQ(run(base("p.json") + "--flavour tr", &log), 0) << log;
    EXPECT_FALSE(output_is_input());
    // Multiplicative: the dark end of the ramp (40 + x) gets less grain than the bright end.
    const auto out = filmgrain::read_whole_file(path("out.yuv"));
    double dark = 0, bright = 0;
    for (int y = 0; y < 144; y++)
        for (int x = 0; x < 40; x++) {
            dark += std::pow(int(out[std::size_t(y) * 176 + x]) - (40 + x), 2);
            bright += std::pow(int(out[std::size_t(y) * 176 + 136 + x]) - (176 + x), 2);
        }
    EXPECT_GT(bright, 4 * dark);  // intensities ~60 and ~196: variance ratio ~10
}

TEST_F(ApplyTrCli, BlockOptionsPerFlavour) {
    write("p.json", kMultiplicative);
    std::string log;
    write("ff.json", R"({"log2_scale_factor": 5, "comp_model_present_flag": [1, 0, 0],
      "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
      "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
      "comp_model_value": [[[100, 8, 8]], [], []]})");
    for (const char* flavour : {"vtm", "tr"}) {
        ASSERT_EQ(run(base("ff.json") + "--flavour " + flavour + " --single-line-blocks 16", &log), 0) << log;
        fs::remove(dir / "out.yuv");
    }
    log.clear();
    EXPECT_NE(run(base("ff.json") + "--single-line-blocks 16", &log), 0);
    EXPECT_NE(log.find("single-line blocks are an option of the vtm and tr flavours"), std::string::npos) << log;
    log.clear();
    EXPECT_NE(run(base("ff.json") + "--flavour vfgs --single-line-blocks 16", &log), 0);
    EXPECT_NE(log.find("--single-line-blocks is an option of --flavour vtm and tr"), std::string::npos) << log;
    ASSERT_EQ(run(base("ff.json") + "--flavour vfgs --block-size 16", &log), 0) << log;
    fs::remove(dir / "out.yuv");
    log.clear();
    EXPECT_NE(run(base("ff.json") + "--flavour vfgs --block-size 32", &log), 0);
    EXPECT_NE(log.find("block size 32 is not supported (allowed 0 or 16"), std::string::npos) << log;
    log.clear();
    EXPECT_NE(run(base("ff.json") + "--flavour rdd5 --pattern-interpolation", &log), 0);
    EXPECT_NE(log.find("--pattern-interpolation belong to --flavour vfgs"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

TEST_F(ApplyTrCli, PatternInterpolationRemovesTheTemplateSwitchAtAnIntervalBoundary) {
    // A 512x256 4:4:4 picture whose luma rises by one level every 8 columns, 96..159, across
    // the boundary at 128 between two intervals of equal scale and very different templates
    // (cut-offs 2 and 14). The grain texture is measured per level as the horizontal lag-1
    // autocorrelation of the grain (pairs inside a 16x16 block, clear of the deblocked
    // columns). Without interpolation it jumps between levels 127 and 128; with
    // --pattern-interpolation the change is spread over 16 levels, so the largest jump
    // between neighbouring levels must fall below a third of the switch (the estimate per
    // level, ~1300 pairs, spreads by ~0.03), and the change across the whole ramp stays.
    const int w = 512, h = 256;
    std::string frame(std::size_t(w) * h * 3, char(128));
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) frame[std::size_t(y) * w + x] = char(96 + x / 8);
    std::ofstream(dir / "ramp.yuv", std::ios::binary) << frame;
    write("pi.json", R"({"log2_scale_factor": 4, "comp_model_present_flag": [1, 0, 0],
      "num_intensity_intervals_minus1": [1, 0, 0], "num_model_values_minus1": [2, 0, 0],
      "intensity_interval_lower_bound": [[0, 128], [], []], "intensity_interval_upper_bound": [[127, 255], [], []],
      "comp_model_value": [[[255, 2, 2], [255, 14, 14]], [], []]})");
    auto texture = [&](bool interpolate) {
        std::string log;
        const std::string args = "-q -i '" + path("ramp.yuv") + "' -o '" + path("ramp-out.yuv") +
                                 "' --size 512x256 --pix-fmt yuv444p --flavour vfgs --seed 7 --params '" +
                                 path("pi.json") + "'" + (interpolate ? " --pattern-interpolation" : "");
        EXPECT_EQ(run(args, &log), 0) << log;
        const auto out = filmgrain::read_whole_file(path("ramp-out.yuv"));
        std::vector<double> r;
        for (int level = 0; level < 64; level++) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
            for (int y = 0; y < h; y++)
                for (int x = 8 * level; x < 8 * level + 7; x++) {
                    if (x % 16 == 0 || x % 16 == 14) continue;  // deblocked samples
                    const double a = int(out[std::size_t(y) * w + x]) - (96 + level);
                    const double b = int(out[std::size_t(y) * w + x + 1]) - (96 + level);
                    sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, n++;
                }
            const double cov = sab / n - sa / n * sb / n;
            r.push_back(cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n)));
        }
        return r;
    };
    auto largest_step = [](const std::vector<double>& r) {
        double m = 0;
        for (std::size_t i = 1; i < r.size(); i++) m = std::max(m, std::abs(r[i] - r[i - 1]));
        return m;
    };
    const std::vector<double> off = texture(false), on = texture(true);
    const double switch_off = std::abs(off[32] - off[31]);  // levels 127 -> 128
    std::printf("lag-1 autocorrelation at levels 127/128: %.3f/%.3f without, %.3f/%.3f with interpolation; "
                "largest step between levels %.3f without, %.3f with\n",
                off[31], off[32], on[31], on[32], largest_step(off), largest_step(on));
    EXPECT_GT(switch_off, 0.2);
    EXPECT_NEAR(largest_step(off), switch_off, 1e-9);  // the switch is the largest step
    EXPECT_LT(largest_step(on), switch_off / 3);
    EXPECT_NEAR(on[0] - on[63], off[0] - off[63], 0.1);  // same textures far from the boundary
}

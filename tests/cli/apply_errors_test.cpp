// `filmgrain apply` on bad input: a clear message naming what is wrong, a non-zero exit,
// and no output file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "conformance_case.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

class ApplyCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-cli-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
        // two 176x144 yuv420p frames of mid grey
        std::ofstream(dir / "in.yuv", std::ios::binary) << std::string(2 * 176 * 144 * 3 / 2, char(120));
    }
    void TearDown() override { fs::remove_all(dir); }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir / name) << text; }
    int run(const std::string& args, std::string* log) {
        return run_command(std::string("'") + FILMGRAIN_TOOL_PATH + "' apply " + args, log);
    }
    std::string base() const {
        return "-i '" + (dir / "in.yuv").string() + "' -o '" + (dir / "out.yuv").string() +
               "' --size 176x144 --pix-fmt yuv420p ";
    }
    fs::path dir;
};

const char* kValid = R"({"log2_scale_factor": 5, "comp_model_present_flag": [1, 0, 0],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
  "comp_model_value": [[[100, 8, 8]], [], []]})";

}  // namespace

TEST_F(ApplyCli, ValidRunWritesEveryFrame) {
    write("p.json", kValid);
    std::string log;
    ASSERT_EQ(run(base() + "--params '" + (dir / "p.json").string() + "'", &log), 0) << log;
    EXPECT_EQ(fs::file_size(dir / "out.yuv"), 2u * 176 * 144 * 3 / 2);
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "temporary left behind";
}

TEST_F(ApplyCli, InvalidParameterSetIsRejectedWithoutOutput) {
    std::string bad = kValid;
    bad.replace(bad.find("\"log2_scale_factor\": 5"), 22, "\"log2_scale_factor\": 9");
    write("p.json", bad);
    std::string log;
    EXPECT_NE(run(base() + "--params '" + (dir / "p.json").string() + "'", &log), 0);
    EXPECT_NE(log.find("log2_scale_factor = 9"), std::string::npos) << log;
    EXPECT_NE(log.find("allowed 2..7"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
    // the references' behaviour on request: the picture passes through untouched
    log.clear();
    EXPECT_EQ(run(base() + "--on-invalid passthrough --params '" + (dir / "p.json").string() + "'", &log), 0) << log;
    EXPECT_EQ(filmgrain::read_whole_file((dir / "out.yuv").string()), filmgrain::read_whole_file((dir / "in.yuv").string()));
}

TEST_F(ApplyCli, TruncatedInputIsAnErrorNotAShortOutput) {
    fs::resize_file(dir / "in.yuv", 176 * 144 * 3 / 2 + 1000);
    write("p.json", kValid);
    std::string log;
    EXPECT_NE(run(base() + "--params '" + (dir / "p.json").string() + "'", &log), 0);
    EXPECT_NE(log.find("truncated"), std::string::npos) << log;
    EXPECT_NE(log.find("frame 1 has 1000 of 38016 bytes"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

TEST_F(ApplyCli, MalformedJsonAndSeiNameTheProblem) {
    write("p.json", "{\"log2_scale_factor\": ");
    std::string log;
    EXPECT_NE(run(base() + "--params '" + (dir / "p.json").string() + "'", &log), 0);
    EXPECT_NE(log.find("not valid JSON"), std::string::npos) << log;
    std::ofstream(dir / "s.bin", std::ios::binary) << std::string("\x05", 1);
    log.clear();
    EXPECT_NE(run(base() + "--sei '" + (dir / "s.bin").string() + "'", &log), 0);
    EXPECT_NE(log.find("truncated while reading"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

TEST_F(ApplyCli, BadOptionsAreNamed) {
    write("p.json", kValid);
    std::string log;
    EXPECT_NE(run(base() + "--flavour dolby --params '" + (dir / "p.json").string() + "'", &log), 0);
    EXPECT_NE(log.find("allowed rdd5, ffmpeg, vtm, vfgs"), std::string::npos) << log;
    log.clear();
    EXPECT_NE(run("-i '" + (dir / "in.yuv").string() + "' -o '" + (dir / "out.yuv").string() +
                      "' --size 176x144 --pix-fmt yuv411p --params '" + (dir / "p.json").string() + "'",
                  &log),
              0);
    EXPECT_NE(log.find("yuv411p"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

TEST_F(ApplyCli, Y4mPipeRoundTrip) {
    write("p.json", kValid);
    std::string hdr = "YUV4MPEG2 W176 H144 F25:1 Ip A1:1 C420jpeg\n";
    std::string frame(176 * 144 * 3 / 2, char(120));
    std::ofstream(dir / "in.y4m", std::ios::binary) << hdr << "FRAME\n" << frame << "FRAME\n" << frame;
    std::string log;
    const std::string cmd = "cat '" + (dir / "in.y4m").string() + "' | '" + FILMGRAIN_TOOL_PATH +
                            "' apply -q -i - -o - --params '" + (dir / "p.json").string() + "' > '" +
                            (dir / "out.y4m").string() + "'";
    ASSERT_EQ(run_command(cmd, &log), 0) << log;
    const auto out = filmgrain::read_whole_file((dir / "out.y4m").string());
    ASSERT_EQ(out.size(), hdr.size() + 2 * (6 + frame.size()));
    EXPECT_EQ(std::string(out.begin(), out.begin() + 9), "YUV4MPEG2");
}

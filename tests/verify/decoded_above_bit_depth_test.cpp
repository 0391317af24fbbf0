// `verify` reads the decoder's output under test: there a sample above the bit depth is what
// the decoder did (no clip, or output in another format than the one named), a mismatch to
// name. It used to be refused as unreadable input (exit 2, nothing compared). The clean input
// is still refused so, as every command's input is (tests/cli/hardening_io_test.cpp). Runs
// the build's tool, and the ASan/UBSan tool under asan_ubsan.verify_tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "tool_under_test.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

// one FGC luma interval over the whole range, 8-bit values as the SEI carries them
constexpr const char* kParams = R"({"film_grain_characteristics_cancel_flag": false, "film_grain_model_id": 0,
  "separate_colour_description_present_flag": false, "blending_mode_id": 0, "log2_scale_factor": 5,
  "comp_model_present_flag": [true, false, false],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
  "comp_model_value": [[[100, 8, 8]], [], []]})";

class DecodedAboveBitDepth : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-verify-range-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        write(dir / "p.json", kParams);
    }
    void TearDown() override { fs::remove_all(dir); }
    static void write(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }
    static std::string read(const fs::path& p) {
        std::ifstream f(p, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    }
    CommandResult verify(const char* clean, const char* decoded) const {
        return run_tool("verify --clean " + quoted(dir / clean) + " -p " + quoted(dir / "p.json") + " -d " +
                        quoted(dir / decoded) + kRaw);
    }
    static constexpr const char* kRaw = " --size 64x32 --pix-fmt yuv420p10le";
    fs::path dir;
};

TEST_F(DecodedAboveBitDepth, IsAMismatchVerifyNamesAndTheCleanInputIsStillRefused) {
    const int w = 64, h = 32;
    std::vector<uint16_t> words(std::size_t(w) * h * 3 / 2);
    std::mt19937 rng(5);
    for (auto& v : words) v = uint16_t(64 + rng() % 896);
    write(dir / "clean.yuv", std::string(reinterpret_cast<const char*>(words.data()), words.size() * 2));
    const CommandResult made = run_tool("apply -i " + quoted(dir / "clean.yuv") + kRaw + " -p " +
                                        quoted(dir / "p.json") + " -o " + quoted(dir / "ref.yuv"));
    ASSERT_TRUE(made.exited_with(0)) << made.output;
    const CommandResult exact = verify("clean.yuv", "ref.yuv");
    EXPECT_TRUE(exact.exited_with(0)) << exact.output;
    // Y at x 5, y 3 and x 9, y 7
    std::string bad = read(dir / "ref.yuv");
    for (const auto& [x, y, value] : {std::tuple{5, 3, 2000}, std::tuple{9, 7, 1500}}) {
        const std::size_t at = 2 * (std::size_t(y) * w + std::size_t(x));
        bad[at] = char(value & 0xFF);
        bad[at + 1] = char(value >> 8);
    }
    write(dir / "bad.yuv", bad);
    const CommandResult r = verify("clean.yuv", "bad.yuv");
    EXPECT_TRUE(r.exited_with(1)) << r.output;
    EXPECT_NE(r.output.find("first at Y x 5 y 3:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("2 decoded samples are above the bit depth (first: Y 2000 at x 5, y 3)"),
              std::string::npos)
        << r.output;
    const CommandResult refused = verify("bad.yuv", "ref.yuv");
    ASSERT_TRUE(refused.clean_error()) << refused.output;
    EXPECT_NE(refused.output.find("frame 0: Y sample 2000 at x 5, y 3 is above the 10-bit range 0..1023"),
              std::string::npos)
        << refused.output;
}

}  // namespace

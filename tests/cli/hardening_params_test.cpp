// Issue 24's reproducers for parameter files and option values: each one crashed, wrapped
// or was silently misread before. CTest runs these suites against the release tool and
// against the ASan/UBSan build of it (asan_ubsan.cli_hardening), and every check asks for
// an orderly error exit (not a signal, not a sanitizer report) with a message that names
// the field, the value and the allowed range, and no output file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tool_under_test.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

class HardeningParams : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-hp-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir);
        std::ofstream(dir / "in.yuv", std::ios::binary) << std::string(2 * 128 * 128 * 3 / 2, char(120));
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
    }
    CommandResult apply(const std::string& args) {
        return run_tool("apply -i " + p("in.yuv") + " -o " + p("out.yuv") + " --size 128x128 " + args);
    }
    // An error exit naming every one of `words`, and no output file.
    void expect_error(const CommandResult& r, std::initializer_list<const char*> words) {
        EXPECT_TRUE(r.clean_error()) << "exit " << r.exit_code << " signal " << r.signal << "\n" << r.output;
        for (const char* w : words) EXPECT_NE(r.output.find(w), std::string::npos) << "missing '" << w << "' in:\n" << r.output;
        EXPECT_FALSE(fs::exists(dir / "out.yuv"));
    }
    fs::path dir;
};

std::string nested(const std::string& key, int depth) {
    return "{\"" + key + "\": " + std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']') + "}";
}

const char* kFgc = R"({"log2_scale_factor": 5, "comp_model_present_flag": [1, 0, 0],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [], []], "intensity_interval_upper_bound": [[255], [], []],
  "comp_model_value": [[[100, 8, 8]], [], []]})";

std::string av1_json(const std::string& extra) {
    return R"({"apply_grain": 1, "grain_seed": 7, "num_y_points": 4, "point_y_value": [0, 64, 128, 255],
      "point_y_scaling": [20, 30, 40, 50], "chroma_scaling_from_luma": 0, "num_cb_points": 0, "num_cr_points": 0,
      "grain_scaling_minus_8": 3, "ar_coeff_lag": 0, "ar_coeffs_y_plus_128": [], "ar_coeff_shift_minus_6": 1,
      "grain_scale_shift": 0, "overlap_flag": 1, "clip_to_restricted_range": 0)" +
           extra + "}";
}

}  // namespace

// C1: 100000 levels of nesting overflowed the stack (SIGSEGV) in every JSON reader.
TEST_F(HardeningParams, DeeplyNestedJsonIsRefusedAtParseTime) {
    write("deep.json", nested("log2_scale_factor", 100000));
    expect_error(apply("-p " + p("deep.json")), {"deeper than 64 levels"});
    expect_error(run_tool("params convert " + p("deep.json") + " -o " + p("out.yuv")), {"deeper than 64 levels"});
    write("seed.json", "{\"av1\": {\"apply_grain\": 1, \"grain_seed\": " + std::string(100000, '[') +
                           std::string(100000, ']') + "}}");
    expect_error(apply("-p " + p("seed.json")), {"deeper than 64 levels"});
    write("poc.json", "{\"frames\": [{\"poc\": " + std::string(100000, '[') + std::string(100000, ']') + "}]}");
    expect_error(apply("-p " + p("poc.json")), {"deeper than 64 levels"});
}

// Within the depth bound a wrongly typed value is named briefly, not dumped recursively.
TEST_F(HardeningParams, WronglyTypedValuesAreNamedBriefly) {
    write("arr.json", nested("log2_scale_factor", 60));
    const CommandResult r = apply("-p " + p("arr.json"));
    expect_error(r, {"log2_scale_factor", "an array of 1 entries", "is not an integer"});
    EXPECT_LT(r.output.size(), 1000u) << r.output;
}

// C2: the --sei file name was a printf format: x%n.bin crashed, strength100%.fgc.bin gave no grain.
TEST_F(HardeningParams, SeiFileNamesAreNeverFormats) {
    expect_error(apply("--sei " + p("x%n.bin")), {"cannot open payload file", "x%n.bin"});
    write("p.json", kFgc);
    ASSERT_TRUE(run_tool("params convert -q " + p("p.json") + " -o " + p("strength100%.fgc.bin")).exited_with(0));
    ASSERT_TRUE(fs::exists(dir / "strength100%.fgc.bin"));
    const CommandResult r = apply("-q --sei " + p("strength100%.fgc.bin"));
    ASSERT_TRUE(r.exited_with(0)) << r.output;
    std::ifstream out(dir / "out.yuv", std::ios::binary), in(dir / "in.yuv", std::ios::binary);
    const std::string a((std::istreambuf_iterator<char>(out)), {}), b((std::istreambuf_iterator<char>(in)), {});
    ASSERT_EQ(a.size(), b.size());
    EXPECT_NE(a, b) << "the SEI in a file whose name holds a '%' was not applied";
}

// C3: --blocks 0 divided by zero (SIGFPE); --blocks -8 and --periods 0 were accepted.
TEST_F(HardeningParams, StatsRefusesBlockSizesAndPeriodsOutsideTheirRange) {
    std::ofstream(dir / "g.yuv", std::ios::binary) << std::string(16 * 16, char(100));
    const std::string base = "stats " + p("g.yuv") + " " + p("g.yuv") + " --size 16x16 --pix-fmt gray ";
    for (const char* bad : {"--blocks 0", "--blocks -8", "--blocks 1"}) {
        const CommandResult r = run_tool(base + bad);
        EXPECT_TRUE(r.clean_error()) << bad << ": " << r.output;
        EXPECT_NE(r.output.find("--blocks"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("not in range 2 to 4096"), std::string::npos) << r.output;
    }
    const CommandResult r = run_tool(base + "--periods 0");
    EXPECT_TRUE(r.clean_error()) << r.output;
    EXPECT_NE(r.output.find("--periods"), std::string::npos) << r.output;
    EXPECT_TRUE(run_tool(base + "--blocks 8 --periods 4").exited_with(0));
}

// F2: AV1 array values wrapped modulo 2^32, and the picture facts were not checked.
TEST_F(HardeningParams, Av1JsonValuesAreCheckedAgainstTheirSyntax) {
    std::string j = av1_json("");
    j.replace(j.find("[20, 30, 40, 50]"), 16, "[20, 30, 40, 4294967301]");
    write("wrap.json", j);
    expect_error(apply("-p " + p("wrap.json")), {"\"point_y_scaling[3]\" = 4294967301", "allowed 0..255"});
    const std::pair<const char*, const char*> facts[] = {
        {"\"bit_depth\": 99", "\"bit_depth\" = 99"},
        {"\"matrix_coefficients\": 1000", "\"matrix_coefficients\" = 1000"},
        {"\"matrix_coefficients\": -1", "\"matrix_coefficients\" = -1"},
        {"\"subsampling_x\": 7", "\"subsampling_x\" = 7"},
        {"\"mono_chrome\": 5", "\"mono_chrome\" = 5"},
    };
    for (const auto& [fact, message] : facts) {
        write("facts.json", "{\"frames\": [{\"av1\": " + av1_json("") + ", " + fact + "}]}");
        const CommandResult r = apply("-p " + p("facts.json"));
        expect_error(r, {message, "allowed"});
    }
    write("seed.json", "{\"av1\": " + [] {
        std::string s = av1_json("");
        s.replace(s.find("\"grain_seed\": 7"), 15, "\"grain_seed\": 18446744073709551615");
        return s;
    }() + "}");
    expect_error(apply("-p " + p("seed.json")), {"\"grain_seed\" = 18446744073709551615", "allowed 0..65535"});
}

// F1's JSON path: 2^64 - 1 wrapped to -1 on the way into comp_model_value.
TEST_F(HardeningParams, FgcJsonValuesDoNotWrap) {
    std::string j = kFgc;
    j.replace(j.find("[[[100, 8, 8]]"), 14, "[[[18446744073709551615, 8, 8]]");
    write("p.json", j);
    expect_error(apply("-p " + p("p.json")), {"comp_model_value[0][0][0] = 18446744073709551615", "allowed"});
}

// F4: loosely parsed option values were read as something else.
TEST_F(HardeningParams, OptionValuesAreParsedWhole) {
    write("p.json", kFgc);
    expect_error(run_tool("apply -i " + p("in.yuv") + " -o " + p("out.yuv") + " --size 16x16x16 -p " + p("p.json")),
                 {"--size", "16x16x16"});
    expect_error(apply("--fps 1e9 -p " + p("p.json")), {"--fps", "1e9"});
    expect_error(apply("--fps 0 -p " + p("p.json")), {"--fps numerator = 0", "allowed 1..1000000"});
    expect_error(apply("--threads 257 -p " + p("p.json")), {"--threads", "257"});
    expect_error(apply("--coded-size 1920x1080junk --flavour vtm -p " + p("p.json")), {"--coded-size"});
    expect_error(apply("--matrix-coefficients 1000 -p " + p("p.json")), {"--matrix-coefficients"});
}

TEST_F(HardeningParams, RenderRegionCannotOverflow) {
    std::ofstream(dir / "g.yuv", std::ios::binary) << std::string(16 * 16, char(100));
    const std::string base = "render " + p("g.yuv") + " -o " + p("out.yuv") + " --size 16x16 --pix-fmt gray --samples 4 ";
    expect_error(run_tool(base + "--roi 2147483647,2147483647,2,2"), {"--roi x = 2147483647", "allowed 0..1073741824"});
    expect_error(run_tool(base + "--roi 1073741824,0,1073741824,2"), {"is not inside the 16x16 output"});
    expect_error(run_tool(base + "--roi 1,2,3"), {"--roi '1,2,3'"});
    expect_error(run_tool(base + "--threads 100000"), {"--threads"});
}

TEST_F(HardeningParams, ParamsConvertDoesNotTakePicturesForPayloads) {
    expect_error(run_tool("params convert " + p("in.yuv") + " -o " + p("out.json")), {"cannot tell which parameter form", "--from"});
    EXPECT_FALSE(fs::exists(dir / "out.json"));
}

// F3 for parameter files: /dev/zero and oversized files were read without a bound.
TEST_F(HardeningParams, ParameterAndPayloadFilesAreReadWithABound) {
    expect_error(apply("-p /dev/zero"), {"/dev/zero", "16777216 bytes"});
    expect_error(apply("--sei /dev/zero"), {"/dev/zero", "1048576 bytes"});
    expect_error(apply("--afgs1 /dev/zero"), {"/dev/zero", "1048576 bytes"});
    {
        std::ofstream big(dir / "big.json", std::ios::binary);
        big << "{\"log2_scale_factor\": 5, \"pad\": \"" << std::string(17u << 20, 'x') << "\"}";
    }
    expect_error(apply("-p " + p("big.json")), {"big.json", "16777216"});
}

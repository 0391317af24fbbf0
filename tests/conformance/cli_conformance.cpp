// Every conformance case through the `filmgrain apply` command, as other tools call it:
// raw YUV in and out, parameters from case.json (and, for AV1, also from grain.tbl).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <filesystem>

#include "conformance_case.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> all_cases() {
    std::vector<std::string> out;
    for (const char* p : {"vtm_", "rdd5_", "vfgs-", "av1_", "afgs1-"})
        for (auto& n : list_cases(p))
            if (n.rfind("vfgs-afgs1", 0) != 0) out.push_back(n);
    return out;
}

std::string q(const std::string& s) { return "'" + s + "'"; }

void run_cli(const ConformanceCase& c, const std::string& params_args) {
    const fs::path tmp = fs::temp_directory_path() / ("filmgrain-cli-" + c.name + "-" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    const fs::path in = tmp / "in.yuv", out = tmp / "out.yuv";
    {
        std::FILE* f = std::fopen(in.c_str(), "wb");
        ASSERT_TRUE(f);
        std::fwrite(c.input.data(), 1, c.input.size(), f);
        std::fclose(f);
    }
    const std::string cmd = std::string(q(FILMGRAIN_TOOL_PATH)) + " apply -q -i " + q(in) + " -o " + q(out) +
                            " --size " + std::to_string(c.width) + "x" + std::to_string(c.height) + " --pix-fmt " +
                            c.json.at("pix_fmt").get<std::string>() + " " + params_args;
    std::string log;
    const int rc = run_command(cmd, &log);
    ASSERT_EQ(rc, 0) << cmd << "\n" << log;
    const std::vector<uint8_t> data = read_whole_file(out.string());
    ASSERT_EQ(data.size(), c.output_frame_bytes() * std::size_t(c.frames)) << cmd;
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        std::string why = describe_mismatch(c, k, data.data() + c.output_frame_bytes() * k, c.output_frame_bytes());
        if (!why.empty()) {
            mismatches++;
            ADD_FAILURE() << why << "\n  command: " << cmd;
        }
    }
    EXPECT_EQ(mismatches, 0);
    fs::remove_all(tmp);
}

class CliConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(CliConformance, ApplyWithCaseJson) {
    const ConformanceCase c = load_case(GetParam());
    const std::string fam = c.json.at("family");
    std::string args = "--params " + q((fs::path(c.dir) / "case.json").string());
    if (fam == "afgs1") {
        // the payload files as a decoder would hand them over: missing ones are pictures
        // without an SEI
        args = "--afgs1 " + q((fs::path(c.dir) / "afgs1_%d.bin").string());
    } else if (fam == "vtm" || fam == "rdd5") {
        args += " --flavour " + fam + " --on-invalid passthrough";
    } else if (fam == "vfgs") {
        args += " --flavour vfgs";
        if (!c.json.at("seed").is_null()) args += " --seed " + std::to_string(c.json.at("seed").get<long long>());
        if (c.json.value("vfgs_gain_percent", 100) != 100)
            args += " --gain " + std::to_string(c.json.at("vfgs_gain_percent").get<int>());
        if (c.json.value("output_pix_fmt", c.json.at("pix_fmt")) != c.json.at("pix_fmt"))
            args += " --output-pix-fmt " + c.json.at("output_pix_fmt").get<std::string>();
    }
    run_cli(c, args);
}

class CliConformanceGrainTable : public ::testing::TestWithParam<std::string> {};

TEST_P(CliConformanceGrainTable, ApplyWithGrainTable) {
    const ConformanceCase c = load_case(GetParam());
    const auto& p = c.frame_info(0).at("params");
    // filmgrn1 tables cannot carry clip_to_restricted_range or the matrix (README caveat 6)
    const std::string args = "--params " + q((fs::path(c.dir) / "grain.tbl").string()) + " --matrix-coefficients " +
                             std::to_string(p.value("matrix_coefficients", 2)) + " --clip-to-restricted-range " +
                             std::to_string(p.at("av1").value("clip_to_restricted_range", 0));
    run_cli(c, args);
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
    std::string n = info.param;
    for (auto& ch : n)
        if (!std::isalnum((unsigned char)ch)) ch = '_';
    return n;
}

INSTANTIATE_TEST_SUITE_P(Cases, CliConformance, ::testing::ValuesIn(all_cases()), test_name);
INSTANTIATE_TEST_SUITE_P(Av1Cases, CliConformanceGrainTable, ::testing::ValuesIn(list_cases("av1_")), test_name);

// AFGS1 carried in an H.265 stream (T.35 SEI, B-frames: decode order differs from output
// order): `decode` finds each access unit's payload, keeps the stored sets in decode order and
// gives every output picture its golden.
TEST(CliConformanceDecode, Afgs1InHevcWithBFramesEqualsTheGoldens) {
    const ConformanceCase c = load_case("afgs1-352x288-420p8-bframes");
    const fs::path tmp = fs::temp_directory_path() / ("filmgrain-afgs1-decode-" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    const fs::path out = tmp / "out.yuv";
    std::string log;
    const std::string cmd = std::string(q(FILMGRAIN_TOOL_PATH)) + " decode -q " +
                            q((fs::path(c.dir) / "stream.hevc").string()) + " -o " + q(out.string());
    const int rc = run_command(cmd, &log);
    if (log.find("no libavformat") != std::string::npos) GTEST_SKIP() << "built without libav*";
    ASSERT_EQ(rc, 0) << cmd << "\n" << log;
    const std::vector<uint8_t> data = read_whole_file(out.string());
    ASSERT_EQ(data.size(), c.frame_bytes() * std::size_t(c.frames)) << cmd;
    for (int k = 0; k < c.frames; k++)
        EXPECT_EQ(describe_mismatch(c, k, data.data() + c.frame_bytes() * std::size_t(k), c.frame_bytes()), "")
            << "picture " << k;
    fs::remove_all(tmp);
}

// The same stream through `params extract` (the picture the sets are selected for given, as
// the scanner does not read sizes) and `apply --params`: the goldens again. Without the
// picture, extract refuses naming the options.
TEST(CliConformanceDecode, Afgs1InHevcExtractedAndAppliedEqualsTheGoldens) {
    const ConformanceCase c = load_case("afgs1-352x288-420p8-bframes");
    const fs::path tmp = fs::temp_directory_path() / ("filmgrain-afgs1-extract-" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    const std::string stream = q((fs::path(c.dir) / "stream.hevc").string());
    std::string log;
    const std::string tool = std::string(q(FILMGRAIN_TOOL_PATH));
    EXPECT_NE(run_command(tool + " params extract " + stream + " -o " + q((tmp / "x.json").string()), &log), 0);
    EXPECT_NE(log.find("give --size WxH and --pix-fmt"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(tmp / "x.json"));
    const std::string extract = tool + " params extract -q " + stream + " -o " + q((tmp / "p.json").string()) +
                                " --size 352x288 --pix-fmt yuv420p";
    ASSERT_EQ(run_command(extract, &log), 0) << extract << "\n" << log;
    run_cli(c, "--params " + q((tmp / "p.json").string()));
    fs::remove_all(tmp);
}

// vtm and rdd5, vfgs (the 16 shared cases and vfgs-made-420p10-256x144), av1, afgs1
TEST(CliConformanceSet, EveryFamilyPresent) { EXPECT_EQ(all_cases().size(), 16u + 17u + 28u + 10u); }

}  // namespace

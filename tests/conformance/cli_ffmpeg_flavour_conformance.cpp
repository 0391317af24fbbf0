// The ffmpeg71-* family: H.265 streams with an FGC SEI in every access unit, decoded with
// grain by FFmpeg 7.1 (tools/make-ffmpeg-goldens, conformance/README.md). `filmgrain decode
// --flavour ffmpeg` must give FFmpeg's every picture; on the cases made to show one of
// FFmpeg's departures from RDD 5 (case.json "departures"), the rdd5 flavour must not, so that
// each case is known to exercise what it names.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <set>

#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// Per-picture MD5s of `filmgrain decode --flavour F`.
std::vector<std::string> decode_md5s(const ConformanceCase& c, const std::string& flavour, const std::string& extra = "") {
    const fs::path out =
        fs::temp_directory_path() / ("filmgrain-ff71-" + c.name + "-" + flavour + "-" + std::to_string(::getpid()) + ".yuv");
    std::string log;
    const std::string cmd = q(FILMGRAIN_TOOL_PATH) + " decode -q --format yuv --flavour " + flavour + " " + extra + " " +
                            q((fs::path(c.dir) / "stream.hevc").string()) + " -o " + q(out.string());
    const int rc = run_command(cmd, &log);
    EXPECT_EQ(rc, 0) << cmd << "\n" << log;
    std::vector<std::string> md5s;
    if (rc != 0) return md5s;
    const std::vector<uint8_t> data = read_whole_file(out.string());
    fs::remove(out);
    EXPECT_EQ(data.size(), c.frame_bytes() * std::size_t(c.frames)) << cmd;
    for (std::size_t k = 0; (k + 1) * c.frame_bytes() <= data.size(); k++)
        md5s.push_back(md5_hex(data.data() + k * c.frame_bytes(), c.frame_bytes()));
    return md5s;
}

class FfmpegFlavourConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(FfmpegFlavourConformance, DecodeEqualsFfmpeg71EveryPicture) {
    const ConformanceCase c = load_case_description(GetParam());
    const auto& expected = c.json.at("expected_md5");
    ASSERT_EQ(int(expected.size()), c.frames);
    for (const std::string threads : {"1", "2"}) {
        const std::vector<std::string> got = decode_md5s(c, "ffmpeg", "--threads " + threads);
        ASSERT_EQ(int(got.size()), c.frames);
        for (int k = 0; k < c.frames; k++)
            EXPECT_EQ(got[std::size_t(k)], expected[std::size_t(k)].get<std::string>())
                << c.name << " picture " << k << " threads " << threads;
    }
}

TEST_P(FfmpegFlavourConformance, TheDeparturesTheCaseNamesChangeTheRdd5Output) {
    const ConformanceCase c = load_case_description(GetParam());
    const auto& departures = c.json.at("departures");
    const std::vector<std::string> rdd5 = decode_md5s(c, "rdd5");
    ASSERT_EQ(int(rdd5.size()), c.frames);
    int equal = 0;
    for (int k = 0; k < c.frames; k++) equal += rdd5[std::size_t(k)] == c.json.at("expected_md5")[std::size_t(k)].get<std::string>();
    if (departures.empty())
        EXPECT_EQ(equal, c.frames) << c.name << ": no departure is used, so rdd5 must equal FFmpeg";
    else
        EXPECT_LT(equal, c.frames) << c.name << ": made to show " << departures.dump() << ", but rdd5 equals FFmpeg";
}

std::vector<std::string> cases() { return list_cases("ffmpeg71-"); }

INSTANTIATE_TEST_SUITE_P(Cases, FfmpegFlavourConformance, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param;
                             for (char& ch : n)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return n;
                         });

TEST(FfmpegFlavourConformanceSet, TenCasesCoverEveryDeparture) {
    const std::vector<std::string> names = cases();
    EXPECT_EQ(names.size(), 10u);
    std::set<std::string> seen;
    for (const auto& n : names) {
        const ConformanceCase c = load_case_description(n);
        for (const auto& d : c.json.at("departures")) seen.insert(d.get<std::string>());
    }
    EXPECT_EQ(seen, (std::set<std::string>{"a", "b", "p"}));
}

}  // namespace

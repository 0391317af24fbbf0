// `filmgrain params extract` on AV1 streams whose film grain is in the frame headers
// (aomenc --film-grain-test=N, no AFGS1 metadata): `apply --params` with the extracted file
// on the pictures `decode --no-grain` gives must equal `decode` (itself bit-exact with
// dav1d, decode_cli_test.cpp). Stream shapes that exercise the frame header syntax before
// film_grain_params(): hidden alt-ref frames shown later, tiles, error resilience, loop
// restoration, superres, monochrome, no order hints, several key frames.
#include <gtest/gtest.h>

#include <random>

#include "bitstream/av1_grain_extraction.hpp"
#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"
#include "metadata/av1_params_json.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

struct HeaderCase {
    const char* name;
    int film_grain_test;
    int bit_depth;
    int width, height, frames;
    const char* aomenc_args;
};

class FrameHeaderGrain : public ::testing::TestWithParam<HeaderCase> {};

}  // namespace

TEST_P(FrameHeaderGrain, ExtractedParametersApplyAsDecodeDoes) {
    const HeaderCase c = GetParam();
    const fs::path dir = fresh_test_dir(std::string("frame-header-grain-") + c.name);
    write_synthetic_y4m(dir / "src.y4m", c.width, c.height, c.frames, c.bit_depth);
    const std::string depth = c.bit_depth > 8 ? " --bit-depth=10 --input-bit-depth=10" : "";
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --cpu-used=6 --limit=" + std::to_string(c.frames) + depth +
                            " --film-grain-test=" + std::to_string(c.film_grain_test) + " " + c.aomenc_args + " -o " +
                            q(dir / "g.ivf") + " " + q(dir / "src.y4m")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "g.ivf") + " -o " + q(dir / "decoded.y4m")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "g.ivf") + " -o " + q(dir / "clean.y4m")));
    ASSERT_TRUE(run_or_fail(tool() + " params extract -q " + q(dir / "g.ivf") + " -o " + q(dir / "p.json")));
    ASSERT_TRUE(run_or_fail(tool() + " apply -q -i " + q(dir / "clean.y4m") + " -o " + q(dir / "applied.y4m") +
                            " --params " + q(dir / "p.json")));
    const auto decoded = read_bytes(dir / "decoded.y4m"), applied = read_bytes(dir / "applied.y4m");
    ASSERT_FALSE(decoded.empty());
    EXPECT_TRUE(decoded == applied) << "apply with the extracted parameters differs from decode";
    EXPECT_NE(decoded, read_bytes(dir / "clean.y4m"));

    // one entry per shown frame, each with grain and its own seed
    const auto text = read_bytes(dir / "p.json");
    const auto frames = av1_frame_params_from_json(nlohmann::json::parse(text.begin(), text.end()));
    ASSERT_EQ(frames.size(), std::size_t(c.frames));
    for (const auto& f : frames) {
        EXPECT_EQ(f.grain.apply_grain, 1);
        ASSERT_TRUE(f.color.has_value());
        EXPECT_EQ(f.color->bit_depth, c.bit_depth);
    }
    const auto stream = read_bytes(dir / "g.ivf");
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    for (const auto& u : scan.units) EXPECT_TRUE(u.warnings.empty()) << u.warnings[0];
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Aomenc, FrameHeaderGrain,
    ::testing::Values(HeaderCase{"test1_8bit", 1, 8, 96, 64, 6, ""},
                      HeaderCase{"test10_10bit", 10, 10, 96, 64, 6, ""},
                      HeaderCase{"altref_tiles", 7, 8, 352, 288, 20, "--tile-columns=1 --tile-rows=1"},
                      HeaderCase{"error_resilient", 12, 10, 96, 64, 12, "--error-resilient=1"},
                      HeaderCase{"restoration", 3, 8, 200, 120, 10, "--enable-restoration=1 --enable-cdef=1"},
                      HeaderCase{"superres", 6, 8, 160, 96, 8, "--superres-mode=1 --superres-denominator=12"},
                      HeaderCase{"monochrome", 5, 8, 96, 64, 6, "--monochrome"},
                      HeaderCase{"no_order_hint", 9, 8, 96, 64, 8, "--enable-order-hint=0"},
                      HeaderCase{"key_frames", 15, 10, 96, 64, 24, "--kf-max-dist=8 --enable-fwd-kf=1"}),
    [](const auto& info) { return std::string(info.param.name); });

// A damaged frame header is a warning on its unit; that frame is written without grain and
// the others keep theirs.
TEST(FrameHeaderGrain, DamagedHeaderIsAWarningOnItsUnit) {
    const fs::path dir = fresh_test_dir("frame-header-grain-damaged");
    write_synthetic_y4m(dir / "src.y4m", 96, 64, 4, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --cpu-used=6 --limit=4 --lag-in-frames=0 --film-grain-test=2 -o " +
                            q(dir / "g.ivf") + " " + q(dir / "src.y4m")));
    std::vector<uint8_t> stream = read_bytes(dir / "g.ivf");
    const StreamScan clean = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    ASSERT_EQ(clean.units.size(), 4u);
    std::vector<std::string> warnings;
    const auto good = av1_params_from_scan(clean, warnings);
    EXPECT_TRUE(warnings.empty());
    // Cut the last temporal unit a few bytes into its data: its frame OBU runs past the end.
    std::vector<uint8_t> cut(stream.begin(), stream.begin() + long(clean.units[3].offset) + 12 + 6);
    const StreamScan scan = scan_stream(cut.data(), cut.size(), StreamCodec::kAv1);
    warnings.clear();
    const auto frames = av1_params_from_scan(scan, warnings);
    ASSERT_EQ(frames.size(), 4u);
    for (int k = 0; k < 3; k++) EXPECT_EQ(frames[std::size_t(k)].grain, good[std::size_t(k)].grain) << k;
    EXPECT_EQ(good[3].grain.apply_grain, 1);
    EXPECT_EQ(frames[3].grain.apply_grain, 0);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("TU 3"), std::string::npos) << warnings[0];
    EXPECT_FALSE(scan.units[3].warnings.empty() && scan.warnings.empty());
    fs::remove_all(dir);
}

// Truncated and bit-flipped copies of a frame-header grain stream: the header reader gives
// warnings (or the extraction an Error), never a crash, and never more frames than units.
TEST(FrameHeaderGrain, MutatedStreamsAreReportedNotFatal) {
    const fs::path dir = fresh_test_dir("frame-header-grain-mutated");
    write_synthetic_y4m(dir / "src.y4m", 96, 64, 10, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --cpu-used=6 --limit=10 --film-grain-test=7 -o " + q(dir / "g.ivf") +
                            " " + q(dir / "src.y4m")));
    const std::vector<uint8_t> stream = read_bytes(dir / "g.ivf");
    std::mt19937 rng(17);
    int reported = 0;
    for (int trial = 0; trial < 400; trial++) {
        std::vector<uint8_t> s(stream.begin(), stream.begin() + long(1 + rng() % stream.size()));
        const int flips = int(rng() % 5);
        for (int i = 0; i < flips; i++) s[rng() % s.size()] ^= uint8_t(1u << (rng() % 8));
        const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kAv1);
        std::vector<std::string> warnings;
        try {
            const auto frames = av1_params_from_scan(scan, warnings);
            EXPECT_EQ(frames.size(), scan.units.size());
            reported += !warnings.empty() || scan.bad_units() > 0 || !scan.warnings.empty();
        } catch (const Error&) {
            reported++;
        }
    }
    EXPECT_GT(reported, 0);
    fs::remove_all(dir);
}

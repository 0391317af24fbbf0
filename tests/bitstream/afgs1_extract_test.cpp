// `filmgrain params extract` on AV1 streams: aomenc output with AFGS1 T.35 metadata OBUs
// inserted (payloads from the project's AFGS1 writer). The per-frame JSON must hold the set
// each frame's payload selects for the coded picture, and `apply --params` with it must
// equal `apply --afgs1` with the same payloads. (Frame-header grain: frame_header_grain_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>

#include "bitstream/av1_grain_extraction.hpp"
#include "bitstream/av1_sequence_header.hpp"
#include "bitstream/metadata_insertion.hpp"
#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/av1_params_json.hpp"
#include "stream_fixtures.hpp"
#include "tool_under_test.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 96, kHeight = 64, kFrames = 6;


Afgs1SetTarget target(int width, int height, int bit_depth) {
    Afgs1SetTarget t;
    t.apply_horz_resolution = width;
    t.apply_vert_resolution = height;
    t.video_signal_characteristics_flag = 1;
    t.bit_depth_minus8 = bit_depth - 8;
    return t;
}

// What each temporal unit carries, and which parameters its frame must get:
//   0, 1, 2, 5: two sets, one for the coded picture (index 0, av1_params_for(k)) and one for a
//               half-size picture (index 1), in alternating order;
//   3: set 0 again with update_grain_flag = 0 and a new seed (the stored set of TU 2);
//   4: no payload (no grain).
struct Fixture {
    std::vector<std::vector<uint8_t>> payloads;  // per TU, empty = none
    std::vector<Av1FilmGrainParams> expected;    // per frame
};

Fixture make_fixture(int bit_depth) {
    Fixture f;
    for (int k = 0; k < kFrames; k++) {
        Afgs1Payload pl;
        Av1FilmGrainParams want;  // apply_grain = 0
        if (k == 3) {
            Afgs1ParamSet reseed;
            reseed.film_grain_param_set_idx = 0;
            reseed.params = av1_params_for(2);
            reseed.params.update_grain = 0;
            reseed.params.grain_seed = 4321;
            reseed.target = target(kWidth, kHeight, bit_depth);
            pl.sets = {reseed};
            want = av1_params_for(2);
            want.grain_seed = 4321;
        } else if (k != 4) {
            Afgs1ParamSet full, half;
            full.film_grain_param_set_idx = 0;
            full.params = av1_params_for(k);
            full.target = target(kWidth, kHeight, bit_depth);
            half.film_grain_param_set_idx = 1;
            half.params = av1_params_for(k + 10);
            half.target = target(kWidth / 2, kHeight / 2, bit_depth);
            pl.sets = k % 2 ? std::vector<Afgs1ParamSet>{half, full} : std::vector<Afgs1ParamSet>{full, half};
            want = av1_params_for(k);
        }
        f.payloads.push_back(pl.sets.empty() ? std::vector<uint8_t>{} : write_afgs1(pl));
        f.expected.push_back(want);
    }
    return f;
}

std::vector<uint8_t> with_payloads(const std::vector<uint8_t>& stream, const Fixture& f) {
    return insert_av1_t35(stream, [&](int tu) {
        std::vector<std::vector<uint8_t>> out;
        if (tu < kFrames && !f.payloads[std::size_t(tu)].empty()) out.push_back(f.payloads[std::size_t(tu)]);
        return out;
    });
}

void expect_frames(const std::vector<Av1FrameParams>& got, const Fixture& f, int bit_depth) {
    ASSERT_EQ(got.size(), std::size_t(kFrames));
    for (int k = 0; k < kFrames; k++) {
        SCOPED_TRACE("frame " + std::to_string(k));
        if (f.expected[std::size_t(k)].apply_grain) {
            EXPECT_EQ(got[std::size_t(k)].grain, f.expected[std::size_t(k)]);
        } else {
            EXPECT_EQ(got[std::size_t(k)].grain.apply_grain, 0);
        }
        ASSERT_TRUE(got[std::size_t(k)].color.has_value());
        EXPECT_EQ(got[std::size_t(k)].color->bit_depth, bit_depth);
        EXPECT_EQ(got[std::size_t(k)].color->subsampling_x, 1);
        EXPECT_EQ(got[std::size_t(k)].color->subsampling_y, 1);
    }
}

struct EncodedAv1 {
    std::string container;  // aomenc option: --ivf or --obu
    int bit_depth;
};

class ExtractAfgs1 : public ::testing::TestWithParam<EncodedAv1> {};

}  // namespace

TEST_P(ExtractAfgs1, JsonHoldsEachFramesSelectedSetAndAppliesAsThePayloads) {
    const EncodedAv1 c = GetParam();
    const fs::path dir = fresh_test_dir("afgs1-extract" + c.container.substr(2) + std::to_string(c.bit_depth));
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, kFrames, c.bit_depth);
    const std::string depth = c.bit_depth > 8 ? " --bit-depth=10 --input-bit-depth=10" : "";
    ASSERT_TRUE(run_or_fail("aomenc --quiet " + c.container + " --limit=" + std::to_string(kFrames) +
                            " --cpu-used=6" + depth + " -o " + q(dir / "raw.bin") + " " + q(dir / "src.y4m")));
    const Fixture f = make_fixture(c.bit_depth);
    const std::vector<uint8_t> stream = with_payloads(read_bytes(dir / "raw.bin"), f);
    write_bytes(dir / "afgs1.obu", stream);

    // the library: sequence header facts and the selected sets
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    ASSERT_EQ(scan.units.size(), std::size_t(kFrames));
    ASSERT_TRUE(scan.units[0].av1_sequence_header.has_value());
    const Av1SequenceHeader& sh = *scan.units[0].av1_sequence_header;
    EXPECT_EQ(sh.max_frame_width, kWidth);
    EXPECT_EQ(sh.max_frame_height, kHeight);
    EXPECT_EQ(sh.bit_depth, c.bit_depth);
    EXPECT_EQ(sh.mono_chrome, 0);
    EXPECT_EQ(sh.film_grain_params_present, 0);
    std::vector<std::string> warnings;
    expect_frames(av1_params_from_scan(scan, warnings), f, c.bit_depth);
    EXPECT_TRUE(warnings.empty()) << warnings[0];

    // the command: the JSON file holds the same, and applies as the payloads do
    ASSERT_TRUE(run_or_fail(tool() + " params extract -q " + q(dir / "afgs1.obu") + " -o " + q(dir / "params.json")));
    const std::vector<uint8_t> text = read_bytes(dir / "params.json");
    expect_frames(av1_frame_params_from_json(nlohmann::json::parse(text.begin(), text.end())), f, c.bit_depth);
    for (int k = 0; k < kFrames; k++)
        if (!f.payloads[std::size_t(k)].empty())
            write_bytes(dir / ("tu" + std::to_string(k) + ".bin"), f.payloads[std::size_t(k)]);
    ASSERT_TRUE(run_or_fail(tool() + " apply -q -i " + q(dir / "src.y4m") + " -o " + q(dir / "from_json.y4m") +
                            " --params " + q(dir / "params.json")));
    ASSERT_TRUE(run_or_fail(tool() + " apply -q -i " + q(dir / "src.y4m") + " -o " + q(dir / "from_afgs1.y4m") +
                            " --afgs1 " + q(dir / "tu%d.bin")));
    const std::vector<uint8_t> a = read_bytes(dir / "from_json.y4m"), b = read_bytes(dir / "from_afgs1.y4m");
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "apply --params (extracted) differs from apply --afgs1";
    EXPECT_NE(a, read_bytes(dir / "src.y4m"));
    fs::remove_all(dir);
}

// A stream with both (aomenc --film-grain-test writes grain into every frame header, AFGS1
// metadata OBUs added): the frame header's grain wins wherever it applies, as AV1 decoders
// apply it, in `params extract` and in `decode` alike; the AFGS1 payloads change nothing.
TEST(ExtractAfgs1, FrameHeaderGrainWinsWhereItApplies) {
    const fs::path dir = fresh_test_dir("afgs1-and-frame-headers");
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, kFrames, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=" + std::to_string(kFrames) +
                            " --cpu-used=6 --film-grain-test=1 -o " + q(dir / "plain.ivf") + " " + q(dir / "src.y4m")));
    const std::vector<uint8_t> plain = read_bytes(dir / "plain.ivf");
    const std::vector<uint8_t> both = with_payloads(plain, make_fixture(8));
    write_bytes(dir / "both.ivf", both);
    std::vector<std::string> warnings, plain_warnings;
    const auto from_both = av1_params_from_scan(scan_stream(both.data(), both.size(), StreamCodec::kAv1), warnings);
    const auto from_headers =
        av1_params_from_scan(scan_stream(plain.data(), plain.size(), StreamCodec::kAv1), plain_warnings);
    ASSERT_EQ(from_both.size(), std::size_t(kFrames));
    ASSERT_EQ(from_headers.size(), std::size_t(kFrames));
    for (int k = 0; k < kFrames; k++) {
        EXPECT_EQ(from_headers[std::size_t(k)].grain.apply_grain, 1) << "frame " << k;
        EXPECT_EQ(from_both[std::size_t(k)].grain, from_headers[std::size_t(k)].grain) << "frame " << k;
    }
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("the 6 frame(s) whose header applies grain keep it"), std::string::npos) << warnings[0];
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "both.ivf") + " -o " + q(dir / "both.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "plain.ivf") + " -o " + q(dir / "plain.yuv")));
    const std::vector<uint8_t> decoded = read_bytes(dir / "both.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(kFrames * kWidth * kHeight * 3 / 2));
    EXPECT_TRUE(decoded == read_bytes(dir / "plain.yuv")) << "the AFGS1 metadata changed decode's pictures";
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Aomenc, ExtractAfgs1,
                         ::testing::Values(EncodedAv1{"--ivf", 8}, EncodedAv1{"--obu", 10}),
                         [](const auto& info) {
                             return info.param.container.substr(2) + "_" + std::to_string(info.param.bit_depth) + "bit";
                         });

TEST(ExtractAfgs1, DamagedPayloadIsAWarningAndTheFrameGetsNoGrain) {
    const fs::path dir = fresh_test_dir("afgs1-extract-damaged");
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, kFrames, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=" + std::to_string(kFrames) + " --cpu-used=6 -o " +
                            q(dir / "raw.ivf") + " " + q(dir / "src.y4m")));
    Fixture f = make_fixture(8);
    f.payloads[1].resize(f.payloads[1].size() / 2);  // truncated
    const std::vector<uint8_t> stream = with_payloads(read_bytes(dir / "raw.ivf"), f);
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    std::vector<std::string> warnings;
    const std::vector<Av1FrameParams> frames = av1_params_from_scan(scan, warnings);
    ASSERT_EQ(frames.size(), std::size_t(kFrames));
    EXPECT_EQ(frames[1].grain.apply_grain, 0);
    EXPECT_EQ(frames[0].grain, f.expected[0]);
    EXPECT_EQ(frames[2].grain, f.expected[2]);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("TU 1"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("truncated"), std::string::npos) << warnings[0];
    fs::remove_all(dir);
}

// Truncated and bit-flipped copies: warnings or a filmgrain::Error, never a crash, and
// frames that keep their payload intact keep their parameters.
TEST(ExtractAfgs1, DamagedStreamsAreReportedNotFatal) {
    const fs::path dir = fresh_test_dir("afgs1-extract-fuzzed");
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, kFrames, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --obu --limit=" + std::to_string(kFrames) + " --cpu-used=6 -o " +
                            q(dir / "raw.obu") + " " + q(dir / "src.y4m")));
    const Fixture f = make_fixture(8);
    const std::vector<uint8_t> stream = with_payloads(read_bytes(dir / "raw.obu"), f);
    std::mt19937 rng(11);
    int reported = 0, refused = 0;
    for (int trial = 0; trial < 300; trial++) {
        std::vector<uint8_t> s(stream.begin(), stream.begin() + long(rng() % stream.size()));
        for (int flips = 0; flips < 3 && !s.empty(); flips++) s[rng() % s.size()] ^= uint8_t(1u << (rng() % 8));
        const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kAv1);
        std::vector<std::string> warnings;
        try {
            const auto frames = av1_params_from_scan(scan, warnings);
            EXPECT_LE(frames.size(), scan.units.size());
            reported += !warnings.empty() || scan.bad_units() > 0 || !scan.warnings.empty();
        } catch (const Error&) {
            refused++;
        }
    }
    EXPECT_GT(reported + refused, 0);
    fs::remove_all(dir);
}

// AFGS1 carried in H.265 / H.264 (T.35 registered user data SEI, payloadType 4) of an x265 /
// x264 stream with B-frames: `decode` gives each picture the set of its own access unit's payload (stored sets
// in decode order), which equals `apply --afgs1` with the payloads put in output order, and
// `params extract --size --pix-fmt` + `apply -p` gives the same pictures.
class Afgs1InH26x : public ::testing::TestWithParam<StreamCodec> {};

TEST_P(Afgs1InH26x, DecodeEqualsApplyWithThePayloadsInOutputOrder) {
    const bool hevc = GetParam() == StreamCodec::kH265;
    if (std::system(hevc ? "command -v x265 >/dev/null 2>&1" : "command -v x264 >/dev/null 2>&1") != 0)
        FAIL() << "the encoder is not installed (tools/install-deps installs x264 and x265)";
    const fs::path dir = fresh_test_dir(hevc ? "afgs1-h265" : "afgs1-h264");
    constexpr int w = 160, h = 128, frames = 8;
    write_synthetic_y4m(dir / "src.y4m", w, h, frames, 8);
    ASSERT_TRUE(run_or_fail(
        hevc ? "x265 --log-level error --preset ultrafast --bframes 3 --keyint 8 --min-keyint 8 --no-scenecut "
               "--no-open-gop --input " + q(dir / "src.y4m") + " -o " + q(dir / "raw.es")
             : "x264 --quiet --preset ultrafast --bframes 2 --keyint 8 --min-keyint 8 --no-scenecut -o " +
                   q(dir / "raw.es") + " " + q(dir / "src.y4m") + " 2>/dev/null"));
    // access unit k (decode order): one set for the picture, with av1_params_for(k); unit 3: none
    std::vector<std::vector<uint8_t>> payloads;
    for (int k = 0; k < frames; k++) {
        if (k == 3) {
            payloads.emplace_back();
            continue;
        }
        Afgs1Payload pl;
        Afgs1ParamSet set;
        set.params = av1_params_for(k);
        set.target = target(w, h, 8);
        pl.sets = {set};
        payloads.push_back(write_afgs1(pl));
    }
    const auto stream = insert_sei(read_bytes(dir / "raw.es"), GetParam(), [&](int au) {
        AccessUnitSei s;
        if (au < frames && !payloads[std::size_t(au)].empty())
            s.prefix = {SeiMessage{kSeiPayloadT35, payloads[std::size_t(au)]}};
        return s;
    });
    const fs::path coded = dir / (hevc ? "afgs1.hevc" : "afgs1.264");
    write_bytes(coded, stream);
    const StreamScan scan = scan_stream(stream.data(), stream.size(), GetParam());
    const auto order = units_in_output_order(scan);
    ASSERT_EQ(order.size(), std::size_t(frames));
    bool reordered = false;
    for (int k = 0; k < frames; k++) {
        const int au = order[std::size_t(k)]->index;
        reordered |= au != k;
        if (!payloads[std::size_t(au)].empty())
            write_bytes(dir / ("afgs1_" + std::to_string(k) + ".bin"), payloads[std::size_t(au)]);
    }
    ASSERT_TRUE(reordered) << "the stream has no B-frames: decode order would equal output order";

    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(coded) + " -o " + q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(coded) + " -o " + q(dir / "clean.yuv")));
    const std::string picture = " --size " + std::to_string(w) + "x" + std::to_string(h) + " --pix-fmt yuv420p ";
    ASSERT_TRUE(run_or_fail(tool() + " apply -q" + picture + "-i " + q(dir / "clean.yuv") + " --afgs1 " +
                            q(dir / "afgs1_%d.bin") + " -o " + q(dir / "applied.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " params extract -q" + picture + q(coded) + " -o " + q(dir / "p.json")));
    ASSERT_TRUE(run_or_fail(tool() + " apply -q" + picture + "-i " + q(dir / "clean.yuv") + " -p " + q(dir / "p.json") +
                            " -o " + q(dir / "extracted.yuv")));
    // inspect gives each payload's set as read in decode order
    const auto inspected = run_shell(tool() + " inspect " + q(coded) + " 2>&1");
    ASSERT_TRUE(inspected.clean_success()) << inspected.output;
    std::size_t sets = 0;
    for (std::size_t at = 0; (at = inspected.output.find("AFGS1: 1 set(s); #0 160x128 4:2:0 8-bit, seed", at)) !=
                             std::string::npos;
         at++)
        sets++;
    EXPECT_EQ(sets, std::size_t(frames - 1)) << inspected.output;
    const auto decoded = read_bytes(dir / "decoded.yuv"), clean = read_bytes(dir / "clean.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(frames * w * h * 3 / 2));
    EXPECT_TRUE(decoded == read_bytes(dir / "applied.yuv")) << "decode and apply --afgs1 differ";
    EXPECT_TRUE(decoded == read_bytes(dir / "extracted.yuv")) << "decode and the extracted parameters differ";
    // the picture of unit 3 has no grain, every other one has
    const std::size_t fb = std::size_t(w) * h * 3 / 2;
    for (int k = 0; k < frames; k++) {
        const bool same = std::equal(decoded.begin() + long(fb * k), decoded.begin() + long(fb * (k + 1)),
                                     clean.begin() + long(fb * k));
        EXPECT_EQ(same, order[std::size_t(k)]->index == 3) << "picture " << k;
    }
    fs::remove_all(dir);
}

// An H.265 access unit with both an FGC SEI and an AFGS1 payload: the FGC SEI (the codec's own
// grain, which libavcodec exports for the picture) wins in `decode`, and `params extract`
// writes the FGC SEI with a warning that the AFGS1 payloads are left out.
TEST(Afgs1InH26xWithFgcSei, TheFgcSeiWins) {
    const fs::path dir = fresh_test_dir("afgs1-and-fgc");
    constexpr int w = 160, h = 128, frames = 8;
    const std::vector<uint8_t> plain = encode_synthetic_clip(dir, StreamCodec::kH265, w, h, frames, 8);
    ASSERT_FALSE(plain.empty());
    const std::vector<uint8_t> fgc = with_fgc_sei_per_access_unit(plain, StreamCodec::kH265);
    const std::vector<uint8_t> both = insert_sei(fgc, StreamCodec::kH265, [&](int au) {
        Afgs1Payload pl;
        Afgs1ParamSet set;
        set.params = av1_params_for(au);
        set.target = target(w, h, 8);
        pl.sets = {set};
        AccessUnitSei s;
        s.prefix = {SeiMessage{kSeiPayloadT35, write_afgs1(pl)}};
        return s;
    });
    write_bytes(dir / "fgc.hevc", fgc);
    write_bytes(dir / "both.hevc", both);
    const StreamScan scan = scan_stream(both.data(), both.size(), StreamCodec::kH265);
    for (const AccessUnit& au : scan.units) {
        EXPECT_EQ(au.fgc.size(), 1u) << "unit " << au.index;
        EXPECT_EQ(au.t35.size(), 1u) << "unit " << au.index;
    }
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "both.hevc") + " -o " + q(dir / "both.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "fgc.hevc") + " -o " + q(dir / "fgc.yuv")));
    const std::vector<uint8_t> decoded = read_bytes(dir / "both.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(frames * w * h * 3 / 2));
    EXPECT_TRUE(decoded == read_bytes(dir / "fgc.yuv")) << "the AFGS1 payloads changed decode's pictures";
    const auto extract = run_shell(tool() + " params extract " + q(dir / "both.hevc") + " -o " + q(dir / "p.json") +
                                   " 2>&1");
    ASSERT_TRUE(extract.clean_success()) << extract.output;
    EXPECT_NE(extract.output.find("also carries AFGS1 payloads"), std::string::npos) << extract.output;
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Codecs, Afgs1InH26x, ::testing::Values(StreamCodec::kH265, StreamCodec::kH264),
                         [](const auto& info) { return info.param == StreamCodec::kH265 ? "h265" : "h264"; });

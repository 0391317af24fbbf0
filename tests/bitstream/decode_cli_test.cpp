// `filmgrain decode` end to end: AV1 streams from `aomenc --film-grain-test=N` against the
// dav1d command's own grain (bit-exact), and an x265 stream carrying FGC SEI against
// `filmgrain apply` with the parameters `filmgrain params extract` finds.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "bitstream/metadata_insertion.hpp"
#include "bitstream/stream_scan.hpp"
#include "conformance_case.hpp"
#include "metadata/fgc_sei.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

struct Av1Case {
    int film_grain_test;
    int bit_depth;
};

class DecodeAv1 : public ::testing::TestWithParam<Av1Case> {};

}  // namespace

TEST_P(DecodeAv1, BitExactWithDav1dGrain) {
    const Av1Case c = GetParam();
    const fs::path dir =
        fresh_test_dir("decode-av1-" + std::to_string(c.film_grain_test) + "-" + std::to_string(c.bit_depth));
    write_synthetic_y4m(dir / "src.y4m", 96, 64, 4, c.bit_depth);
    const std::string depth = c.bit_depth > 8 ? " --bit-depth=10 --input-bit-depth=10" : "";
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=4 --cpu-used=6" + depth + " --film-grain-test=" +
                            std::to_string(c.film_grain_test) + " -o " + q(dir / "g.ivf") + " " + q(dir / "src.y4m")));
    ASSERT_TRUE(run_or_fail("dav1d --quiet -i " + q(dir / "g.ivf") + " -o " + q(dir / "dav1d.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "g.ivf") + " -o " + q(dir / "ours.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "g.ivf") + " -o " + q(dir / "clean.yuv")));
    // one decoder thread and one synthesis thread (the benchmark's setting) give the same pictures
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --threads 1 " + q(dir / "g.ivf") + " -o " + q(dir / "ours1.yuv")));
    const auto ref = read_bytes(dir / "dav1d.yuv"), ours = read_bytes(dir / "ours.yuv"), clean = read_bytes(dir / "clean.yuv");
    EXPECT_TRUE(read_bytes(dir / "ours1.yuv") == ours) << "--threads 1 changes the output";
    const std::size_t frame_bytes = std::size_t(96 * 64 * 3 / 2) * (c.bit_depth > 8 ? 2 : 1);
    ASSERT_EQ(ref.size(), 4 * frame_bytes);
    ASSERT_EQ(ours.size(), ref.size());
    for (std::size_t f = 0; f < 4; f++)
        EXPECT_TRUE(std::equal(ref.begin() + long(f * frame_bytes), ref.begin() + long((f + 1) * frame_bytes),
                               ours.begin() + long(f * frame_bytes)))
            << "frame " << f << " differs from dav1d";
    // the grain is really there: without it the pictures differ
    EXPECT_NE(clean, ref);
    // Y4M output carries the same pictures, with and without grain (the pictures without
    // grain are written straight from the decoder's strided planes)
    for (const char* mode : {"", " --no-grain"}) {
        ASSERT_TRUE(run_or_fail(tool() + " decode -q" + mode + " " + q(dir / "g.ivf") + " -o " + q(dir / "out.y4m")));
        const auto y4m = read_bytes(dir / "out.y4m");
        const auto& raw = *mode ? clean : ours;
        auto at = std::find(y4m.begin(), y4m.end(), uint8_t('\n'));
        ASSERT_NE(at, y4m.end());
        std::size_t pos = std::size_t(at - y4m.begin()) + 1;
        for (std::size_t f = 0; f < 4; f++) {
            ASSERT_LE(pos + 6 + frame_bytes, y4m.size()) << "frame " << f << mode;
            EXPECT_EQ(std::string(y4m.begin() + long(pos), y4m.begin() + long(pos + 6)), "FRAME\n");
            EXPECT_TRUE(std::equal(y4m.begin() + long(pos + 6), y4m.begin() + long(pos + 6 + frame_bytes),
                                   raw.begin() + long(f * frame_bytes)))
                << "Y4M frame " << f << mode;
            pos += 6 + frame_bytes;
        }
        EXPECT_EQ(pos, y4m.size());
    }
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(AomencFilmGrainTests, DecodeAv1,
                         ::testing::Values(Av1Case{1, 8}, Av1Case{6, 8}, Av1Case{10, 8}, Av1Case{16, 8},
                                           Av1Case{1, 10}, Av1Case{3, 10}, Av1Case{10, 10}, Av1Case{15, 10}),
                         [](const auto& info) {
                             return "test" + std::to_string(info.param.film_grain_test) + "_" +
                                    std::to_string(info.param.bit_depth) + "bit";
                         });

TEST(DecodeH265, EqualsApplyWithExtractedParams) {
    const fs::path dir = fresh_test_dir("decode-h265");
    const auto raw = encode_synthetic_clip(dir, StreamCodec::kH265, 160, 128, 12, 8);
    ASSERT_FALSE(raw.empty());
    // a different FGC SEI in every access unit, so a picture matched with the wrong SEI or
    // seeded with the wrong POC shows
    write_bytes(dir / "fgc.hevc", with_fgc_sei_per_access_unit(raw, StreamCodec::kH265));
    for (const char* flavour : {"rdd5", "vtm"}) {
        SCOPED_TRACE(flavour);
        const std::string f = std::string(" --flavour ") + flavour + " ";
        ASSERT_TRUE(run_or_fail(tool() + " decode -q" + f + q(dir / "fgc.hevc") + " -o " + q(dir / "decoded.yuv")));
        ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "fgc.hevc") + " -o " + q(dir / "clean.yuv")));
        ASSERT_TRUE(run_or_fail(tool() + " decode -q --threads 1" + f + q(dir / "fgc.hevc") + " -o " +
                                q(dir / "decoded1.yuv")));
        ASSERT_TRUE(run_or_fail(tool() + " decode -q --threads 1 --no-grain " + q(dir / "fgc.hevc") + " -o " +
                                q(dir / "clean1.yuv")));
        ASSERT_TRUE(run_or_fail(tool() + " params extract -q " + q(dir / "fgc.hevc") + " -o " + q(dir / "p.json")));
        ASSERT_TRUE(run_or_fail(tool() + " apply -q" + f + "--size 160x128 --pix-fmt yuv420p -i " + q(dir / "clean.yuv") +
                                " -p " + q(dir / "p.json") + " -o " + q(dir / "applied.yuv")));
        const auto decoded = read_bytes(dir / "decoded.yuv"), applied = read_bytes(dir / "applied.yuv"),
                   clean = read_bytes(dir / "clean.yuv");
        ASSERT_EQ(decoded.size(), std::size_t(12 * 160 * 128 * 3 / 2));
        EXPECT_TRUE(decoded == applied) << "decode and apply differ";
        EXPECT_TRUE(read_bytes(dir / "decoded1.yuv") == decoded) << "--threads 1 changes the output";
        EXPECT_TRUE(read_bytes(dir / "clean1.yuv") == clean) << "--threads 1 changes the decoded pictures";
        EXPECT_NE(decoded, clean);
    }
    fs::remove_all(dir);
}

// H.264: FFmpeg exports the seed as POC + (idr_pic_id << 5), RDD 5's pic_offset; two IDR
// pictures (x264 numbers them 0 and 1) make the idr_pic_id term count. vtm seeds from the
// POC alone and would see FFmpeg's idr_pic_id term (see cmd_decode.cpp), so rdd5 is the
// flavour compared.
TEST(DecodeH264, Rdd5EqualsApplyWithExtractedParamsAcrossTwoIdrs) {
    const fs::path dir = fresh_test_dir("decode-h264");
    const auto raw = encode_synthetic_clip(dir, StreamCodec::kH264, 160, 128, 12, 8);
    ASSERT_FALSE(raw.empty());
    write_bytes(dir / "fgc.264", with_fgc_sei_per_access_unit(raw, StreamCodec::kH264));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --flavour rdd5 " + q(dir / "fgc.264") + " -o " + q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "fgc.264") + " -o " + q(dir / "clean.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " params extract -q " + q(dir / "fgc.264") + " -o " + q(dir / "p.json")));
    ASSERT_TRUE(run_or_fail(tool() + " apply -q --flavour rdd5 --size 160x128 --pix-fmt yuv420p -i " + q(dir / "clean.yuv") +
                            " -p " + q(dir / "p.json") + " -o " + q(dir / "applied.yuv")));
    const std::string params = [&] {
        const auto b = read_bytes(dir / "p.json");
        return std::string(b.begin(), b.end());
    }();
    EXPECT_NE(params.find("\"idr_pic_id\": 1"), std::string::npos) << "the stream should hold a second IDR";
    const auto decoded = read_bytes(dir / "decoded.yuv"), applied = read_bytes(dir / "applied.yuv"),
               clean = read_bytes(dir / "clean.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(12 * 160 * 128 * 3 / 2));
    EXPECT_TRUE(decoded == applied) << "decode and apply differ";
    EXPECT_NE(decoded, clean);
    fs::remove_all(dir);
}

TEST(DecodeCli, MissingInputIsAnErrorWithoutOutput) {
    const fs::path dir = fresh_test_dir("decode-missing");
    std::string log;
    const int rc = run_command(tool() + " decode " + q(dir / "nope.ivf") + " -o " + q(dir / "out.yuv") + " 2>&1", &log);
    EXPECT_NE(rc, 0);
    EXPECT_NE(log.find("nope.ivf"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
    fs::remove_all(dir);
}

// `decode --first-frame F --frames N` (a distributed range) decodes from the random access
// point before F instead of the stream's start, and gives the full decode's pictures F..F+N-1
// byte for byte: H.265 and H.264 with B-frames (x265 IDR every 8, x264 every 6) and a new
// FGC SEI in every access unit; AV1 with a key frame every 6. An FGC SEI that persists into
// the IDR (libavcodec keeps it) makes the range decode from the start.
namespace {

void expect_ranges_equal_full_decode(const fs::path& dir, const fs::path& stream, std::size_t frame_bytes, int frames,
                                     const std::vector<std::pair<int, int>>& ranges_and_restart) {
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --threads 1 " + q(stream) + " -o " + q(dir / "full.yuv")));
    const auto full = read_bytes(dir / "full.yuv");
    ASSERT_EQ(full.size(), std::size_t(frames) * frame_bytes);
    for (const auto& [first, restart] : ranges_and_restart) {
        SCOPED_TRACE("first frame " + std::to_string(first));
        ASSERT_TRUE(run_or_fail("(" + tool() + " decode --threads 1 --first-frame " + std::to_string(first) +
                                " --frames 5 " + q(stream) + " -o " + q(dir / "part.yuv") + " 2> " + q(dir / "log.txt") + ")"));
        const auto part = read_bytes(dir / "part.yuv");
        const std::size_t n = std::min<std::size_t>(5, std::size_t(frames - first));
        ASSERT_EQ(part.size(), n * frame_bytes);
        EXPECT_TRUE(std::equal(part.begin(), part.end(), full.begin() + long(first * frame_bytes)));
        const auto log = read_bytes(dir / "log.txt");
        const std::string text(log.begin(), log.end());
        if (restart > 0)
            EXPECT_NE(text.find("decoding from access unit " + std::to_string(restart) + " "), std::string::npos) << text;
        else
            EXPECT_EQ(text.find("decoding from access unit"), std::string::npos) << text;
    }
}

}  // namespace

TEST(DecodeRanges, StartAtTheRandomAccessPointBeforeThem) {
    const fs::path dir = fresh_test_dir("decode-ranges");
    const std::size_t frame_bytes = 160 * 128 * 3 / 2;
    {
        SCOPED_TRACE("h265");
        const auto raw = encode_synthetic_clip(dir, StreamCodec::kH265, 160, 128, 24, 8);
        ASSERT_FALSE(raw.empty());
        write_bytes(dir / "fgc.hevc", with_fgc_sei_per_access_unit(raw, StreamCodec::kH265));
        expect_ranges_equal_full_decode(dir, dir / "fgc.hevc", frame_bytes, 24, {{3, 0}, {8, 8}, {13, 8}, {22, 16}});
        // one persistent SEI before the first picture only: in force at every IDR
        FgcParams p = fgc_params_for(0);
        p.film_grain_characteristics_persistence_flag = true;
        write_bytes(dir / "persistent.hevc", insert_sei(raw, StreamCodec::kH265, [&](int au) {
                        AccessUnitSei s;
                        if (au == 0) s.prefix = {SeiMessage{kSeiPayloadFgc, write_fgc_sei_payload(p, FgcCodec::kHevc)}};
                        return s;
                    }));
        expect_ranges_equal_full_decode(dir, dir / "persistent.hevc", frame_bytes, 24, {{13, 0}});
    }
    {
        SCOPED_TRACE("h264");
        const auto raw = encode_synthetic_clip(dir, StreamCodec::kH264, 160, 128, 24, 8);
        ASSERT_FALSE(raw.empty());
        write_bytes(dir / "fgc.264", with_fgc_sei_per_access_unit(raw, StreamCodec::kH264));
        expect_ranges_equal_full_decode(dir, dir / "fgc.264", frame_bytes, 24, {{6, 6}, {17, 12}});
    }
    {
        SCOPED_TRACE("av1");
        write_synthetic_y4m(dir / "src.y4m", 160, 128, 16, 8);
        ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=16 --cpu-used=8 --kf-min-dist=6 --kf-max-dist=6 "
                                "--film-grain-test=3 -o " + q(dir / "g.ivf") + " " + q(dir / "src.y4m")));
        expect_ranges_equal_full_decode(dir, dir / "g.ivf", frame_bytes, 16, {{4, 0}, {6, 6}, {14, 12}});
    }
    fs::remove_all(dir);
}

// The GStreamer elements in the pipelines users run (README, "In GStreamer"): gst-launch-1.0
// with the build tree's plugin (GST_PLUGIN_PATH, set by CTest), on streams the test makes
// with x265, x264 and aomenc and the project's metadata writers, against `filmgrain decode`
// and `filmgrain apply` byte for byte.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "bitstream/metadata_insertion.hpp"
#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_sei.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

// Sizes are multiples of 8: GStreamer's raw I420 rows are padded to 4 bytes (chroma too), and
// filesink writes buffers as they are, so only such sizes compare with a packed .yuv file.
constexpr int kWidth = 160, kHeight = 128, kFrames = 12;

// -f: a crash in an element ends the process (gst-launch otherwise spins waiting for a
// debugger); -q leaves out the state messages, not the warnings and errors the elements post,
// which `verbose` keeps in the log.
// With FILMGRAIN_GST_LAUNCH_PRELOAD set (CTest's asan_ubsan.gst_malformed_pipelines, whose
// GST_PLUGIN_PATH names the plugin built with ASan/UBSan), the GStreamer tools run with those
// runtimes preloaded: a program built without them cannot load such a plugin otherwise.
std::string gst_tool(const char* name) {
    const char* preload = std::getenv("FILMGRAIN_GST_LAUNCH_PRELOAD");
    return (preload && *preload ? "LD_PRELOAD=" + q(preload) + " " : std::string()) + name;
}

std::string gst_launch(const std::string& pipeline, const fs::path& log, bool verbose = false) {
    return gst_tool("gst-launch-1.0") + " -f " + (verbose ? "" : "-q ") + pipeline + " > " + q(log) + " 2>&1";
}

std::string text_of(const fs::path& p) {
    const auto b = read_bytes(p);
    return std::string(b.begin(), b.end());
}

// x265 with B-frames (decode order differs from output order) and a different FGC SEI in
// every access unit: a picture matched with the wrong SEI or seeded with the wrong POC shows.
fs::path make_h265_fgc_stream(const fs::path& dir, int bit_depth) {
    const auto raw = encode_synthetic_clip(dir, StreamCodec::kH265, kWidth, kHeight, kFrames, bit_depth);
    EXPECT_FALSE(raw.empty());
    write_bytes(dir / "fgc.hevc", with_fgc_sei_per_access_unit(raw, StreamCodec::kH265));
    return dir / "fgc.hevc";
}

struct H265Case {
    int bit_depth;
    const char* flavour;
};

class GstH265Fgc : public ::testing::TestWithParam<H265Case> {};

}  // namespace

TEST(GstInspect, ListsBothElementsAndTheirProperties) {
    const fs::path dir = fresh_test_dir("gst-inspect");
    ASSERT_TRUE(run_or_fail("gst-inspect-1.0 --plugin filmgrain > " + q(dir / "plugin.txt") + " 2>&1"));
    const std::string plugin = text_of(dir / "plugin.txt");
    EXPECT_NE(plugin.find("filmgrainparse"), std::string::npos) << plugin;
    EXPECT_NE(plugin.find("filmgrain:"), std::string::npos) << plugin;
    ASSERT_TRUE(run_or_fail("gst-inspect-1.0 filmgrain > " + q(dir / "filter.txt") + " 2>&1"));
    const std::string filter = text_of(dir / "filter.txt");
    for (const char* property : {"params", "afgs1", "sei", "sei-codec", "flavour", "threads", "on-invalid",
                                 "persistence", "enabled"}) {
        const std::size_t at = filter.find(std::string("\n  ") + property + " ");
        ASSERT_NE(at, std::string::npos) << property << " missing:\n" << filter;
        // a description follows the name on the same line
        const std::size_t colon = filter.find(':', at), eol = filter.find('\n', at + 1);
        EXPECT_LT(colon, eol) << property;
        EXPECT_GT(eol - colon, 20u) << property << " has no description";
    }
    for (const char* format : {"I420", "I420_10LE", "I420_12LE", "Y42B", "I422_10LE", "Y444", "Y444_10LE", "GRAY8",
                               "GRAY16_LE"})
        EXPECT_NE(filter.find(format), std::string::npos) << format;
    ASSERT_TRUE(run_or_fail("gst-inspect-1.0 filmgrainparse > " + q(dir / "parse.txt") + " 2>&1"));
    const std::string parse = text_of(dir / "parse.txt");
    EXPECT_NE(parse.find("strip-fgc-sei"), std::string::npos) << parse;
    EXPECT_NE(parse.find("video/x-h265"), std::string::npos);
    EXPECT_NE(parse.find("video/x-av1"), std::string::npos);
    fs::remove_all(dir);
}

TEST_P(GstH265Fgc, EqualsDecodeWithAvdecAndLibde265) {
    const H265Case c = GetParam();
    const fs::path dir = fresh_test_dir(std::string("gst-h265-") + c.flavour + std::to_string(c.bit_depth));
    const fs::path s = make_h265_fgc_stream(dir, c.bit_depth);
    const std::string f = std::string(" --flavour ") + c.flavour + " ";
    ASSERT_TRUE(run_or_fail(tool() + " decode -q" + f + q(s) + " --format yuv -o " + q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(s) + " --format yuv -o " + q(dir / "clean.yuv")));
    const auto decoded = read_bytes(dir / "decoded.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(kFrames * kWidth * kHeight * 3 / 2 * (c.bit_depth > 8 ? 2 : 1)));
    ASSERT_NE(decoded, read_bytes(dir / "clean.yuv"));
    // Debian 12's libde265dec crashes on 10-bit streams by itself (without these elements)
    std::vector<const char*> decoders = {"avdec_h265"};
    if (c.bit_depth == 8) decoders.push_back("libde265dec");
    for (const char* decoder : decoders) {
        SCOPED_TRACE(decoder);
        const fs::path out = dir / (std::string(decoder) + ".yuv");
        ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(s) + " ! h265parse ! filmgrainparse ! " + decoder +
                                               " ! filmgrain flavour=" + c.flavour + " ! filesink location=" + q(out),
                                           dir / "log.txt")));
        EXPECT_TRUE(read_bytes(out) == decoded) << "the pipeline differs from `filmgrain decode`";
    }
    // Without taking the FGC SEI out, avdec_h265 (libavcodec) adds its own grain first.
    ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(s) +
                                           " ! h265parse ! filmgrainparse strip-fgc-sei=false ! avdec_h265 ! "
                                           "filesink location=" + q(dir / "libav_grain.yuv"),
                                       dir / "log.txt")));
    EXPECT_NE(read_bytes(dir / "libav_grain.yuv"), read_bytes(dir / "clean.yuv"));
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(X265BFrames, GstH265Fgc,
                         ::testing::Values(H265Case{8, "rdd5"}, H265Case{8, "vtm"}, H265Case{10, "rdd5"},
                                           H265Case{10, "vtm"}),
                         [](const auto& info) {
                             return std::string(info.param.flavour) + "_" + std::to_string(info.param.bit_depth) + "bit";
                         });

// H.264, two IDRs (x264 numbers them idr_pic_id 0 and 1): rdd5's seed takes the idr_pic_id
// term (`filmgrain decode` has it from FFmpeg's exported seed, the element from the meta).
TEST(GstH264Fgc, Rdd5EqualsDecodeAcrossTwoIdrs) {
    const fs::path dir = fresh_test_dir("gst-h264");
    const auto raw = encode_synthetic_clip(dir, StreamCodec::kH264, kWidth, kHeight, kFrames, 8);
    ASSERT_FALSE(raw.empty());
    write_bytes(dir / "fgc.264", with_fgc_sei_per_access_unit(raw, StreamCodec::kH264));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --flavour rdd5 " + q(dir / "fgc.264") + " --format yuv -o " +
                            q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(dir / "fgc.264") +
                                           " ! h264parse ! filmgrainparse ! avdec_h264 ! filmgrain ! filesink location=" +
                                           q(dir / "gst.yuv"),
                                       dir / "log.txt")));
    const auto decoded = read_bytes(dir / "decoded.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(kFrames * kWidth * kHeight * 3 / 2));
    EXPECT_TRUE(read_bytes(dir / "gst.yuv") == decoded);
    fs::remove_all(dir);
}

namespace {

// Per temporal unit: a set for the picture and one for a half-size picture (to be ignored),
// a reseed of the stored set (update_grain_flag = 0) in unit 3, no payload in unit 4.
std::vector<uint8_t> afgs1_payload_for(int k, int bit_depth) {
    if (k == 4) return {};
    auto target = [&](int w, int h) {
        Afgs1SetTarget t;
        t.apply_horz_resolution = w;
        t.apply_vert_resolution = h;
        t.video_signal_characteristics_flag = 1;
        t.bit_depth_minus8 = bit_depth - 8;
        return t;
    };
    Afgs1Payload pl;
    if (k == 3) {
        Afgs1ParamSet reseed;
        reseed.params = av1_params_for(2);
        reseed.params.update_grain = 0;
        reseed.params.grain_seed = 4321;
        reseed.target = target(kWidth, kHeight);
        pl.sets = {reseed};
    } else {
        Afgs1ParamSet full, half;
        full.params = av1_params_for(k);
        full.target = target(kWidth, kHeight);
        half.film_grain_param_set_idx = 1;
        half.params = av1_params_for(k + 10);
        half.target = target(kWidth / 2, kHeight / 2);
        pl.sets = {half, full};
    }
    return write_afgs1(pl);
}

}  // namespace

// AV1 with AFGS1 in metadata OBUs and no frame-header grain (aomenc, then the project's
// metadata insertion): av1dec leaves the pictures clean, filmgrain adds the grain.
TEST(GstAv1Afgs1, EqualsDecode) {
    for (int bit_depth : {8, 10}) {
        SCOPED_TRACE(bit_depth);
        const fs::path dir = fresh_test_dir("gst-av1-afgs1-" + std::to_string(bit_depth));
        write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, 6, bit_depth);
        const std::string depth = bit_depth > 8 ? " --bit-depth=10 --input-bit-depth=10" : "";
        ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=6 --cpu-used=6" + depth + " -o " + q(dir / "raw.ivf") +
                                " " + q(dir / "src.y4m")));
        write_bytes(dir / "afgs1.ivf", insert_av1_t35(read_bytes(dir / "raw.ivf"), [&](int tu) {
                        std::vector<std::vector<uint8_t>> out;
                        if (auto p = afgs1_payload_for(tu, bit_depth); !p.empty()) out.push_back(p);
                        return out;
                    }));
        ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "afgs1.ivf") + " --format yuv -o " +
                                q(dir / "decoded.yuv")));
        ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "afgs1.ivf") + " --format yuv -o " +
                                q(dir / "clean.yuv")));
        ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(dir / "afgs1.ivf") +
                                               " ! ivfparse ! av1parse ! filmgrainparse ! av1dec ! filmgrain ! "
                                               "filesink location=" + q(dir / "gst.yuv"),
                                           dir / "log.txt")));
        const auto decoded = read_bytes(dir / "decoded.yuv"), clean = read_bytes(dir / "clean.yuv");
        const std::size_t frame = std::size_t(kWidth * kHeight * 3 / 2 * (bit_depth > 8 ? 2 : 1));
        ASSERT_EQ(decoded.size(), 6 * frame);
        EXPECT_TRUE(read_bytes(dir / "gst.yuv") == decoded);
        // grain on every picture but unit 4's, which carries no payload
        for (std::size_t k = 0; k < 6; k++)
            EXPECT_EQ(std::equal(decoded.begin() + long(k * frame), decoded.begin() + long((k + 1) * frame),
                                 clean.begin() + long(k * frame)),
                      k == 4)
                << "frame " << k;
        fs::remove_all(dir);
    }
}

// Pictures that simply get no grain are not errors, even with on-invalid=error (the default):
// a set with apply_grain_flag = 0, and a payload whose only set is for a larger picture (a
// smaller one would be chosen: the largest set not exceeding the picture).
TEST(GstAv1Afgs1, PicturesWithoutGrainAreNotInvalid) {
    const fs::path dir = fresh_test_dir("gst-av1-afgs1-nograin");
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, 4, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=4 --cpu-used=6 -o " + q(dir / "raw.ivf") + " " +
                            q(dir / "src.y4m")));
    write_bytes(dir / "s.ivf", insert_av1_t35(read_bytes(dir / "raw.ivf"), [&](int tu) {
                    Afgs1ParamSet set;
                    set.params = av1_params_for(tu);
                    set.target.apply_horz_resolution = kWidth;
                    set.target.apply_vert_resolution = kHeight;
                    if (tu == 1) set.params.apply_grain = 0;
                    if (tu == 2) {
                        set.target.apply_horz_resolution = kWidth * 2;
                        set.target.apply_vert_resolution = kHeight * 2;
                    }
                    Afgs1Payload pl;
                    pl.sets = {set};
                    return std::vector<std::vector<uint8_t>>{write_afgs1(pl)};
                }));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(dir / "s.ivf") + " --format yuv -o " + q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(tool() + " decode -q --no-grain " + q(dir / "s.ivf") + " --format yuv -o " +
                            q(dir / "clean.yuv")));
    ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(dir / "s.ivf") +
                                           " ! ivfparse ! av1parse ! filmgrainparse ! av1dec ! filmgrain on-invalid=error ! "
                                           "filesink location=" + q(dir / "gst.yuv"),
                                       dir / "log.txt")));
    const auto decoded = read_bytes(dir / "decoded.yuv"), clean = read_bytes(dir / "clean.yuv");
    const std::size_t frame = std::size_t(kWidth * kHeight * 3 / 2);
    ASSERT_EQ(decoded.size(), 4 * frame);
    EXPECT_TRUE(read_bytes(dir / "gst.yuv") == decoded);
    for (std::size_t k = 0; k < 4; k++)
        EXPECT_EQ(std::equal(decoded.begin() + long(k * frame), decoded.begin() + long((k + 1) * frame),
                             clean.begin() + long(k * frame)),
                  k == 1 || k == 2)
            << "frame " << k;
    fs::remove_all(dir);
}

// H.265 with AFGS1 in T.35 SEI and B-frames: the conformance case made with FFmpeg 7.1.
TEST(GstH265Afgs1, ConformanceBFramesCaseEqualsDecode) {
    const fs::path dir = fresh_test_dir("gst-h265-afgs1");
    const fs::path s = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance/afgs1-352x288-420p8-bframes/stream.hevc";
    ASSERT_TRUE(run_or_fail(tool() + " decode -q " + q(s) + " --format yuv -o " + q(dir / "decoded.yuv")));
    ASSERT_TRUE(run_or_fail(gst_launch("filesrc location=" + q(s) +
                                           " ! h265parse ! filmgrainparse ! avdec_h265 ! filmgrain ! filesink location=" +
                                           q(dir / "gst.yuv"),
                                       dir / "log.txt")));
    const auto decoded = read_bytes(dir / "decoded.yuv");
    ASSERT_EQ(decoded.size(), std::size_t(8 * 352 * 288 * 3 / 2));
    EXPECT_TRUE(read_bytes(dir / "gst.yuv") == decoded);
    fs::remove_all(dir);
}

// Static parameters: videotestsrc's frames, grain from a parameter file; picture k since the
// stream start has POC k, as `filmgrain apply` numbers frames.
TEST(GstStaticParams, EqualsApplyOnTheSameFrames) {
    const fs::path dir = fresh_test_dir("gst-static");
    // an FGC SEI payload file: the element tells the form from the name, as params convert does
    const fs::path fgc = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance/rdd5_352x288_420p10/frame0.fgc.bin";
    ASSERT_TRUE(fs::exists(fgc));
    const std::string src = "videotestsrc num-buffers=5 pattern=ball ! video/x-raw,format=I420_10LE,width=" +
                            std::to_string(kWidth) + ",height=" + std::to_string(kHeight);
    ASSERT_TRUE(run_or_fail(gst_launch(src + " ! filesink location=" + q(dir / "clean.yuv"), dir / "log.txt")));
    for (const char* flavour : {"rdd5", "vtm"}) {
        SCOPED_TRACE(flavour);
        ASSERT_TRUE(run_or_fail(gst_launch(src + " ! filmgrain flavour=" + flavour + " params=" + q(fgc) +
                                               " ! filesink location=" + q(dir / "gst.yuv"),
                                           dir / "log.txt")));
        ASSERT_TRUE(run_or_fail(tool() + " apply -q --flavour " + flavour + " --size " + std::to_string(kWidth) + "x" +
                                std::to_string(kHeight) + " --pix-fmt yuv420p10le -i " + q(dir / "clean.yuv") +
                                " -p " + q(fgc) + " -o " + q(dir / "applied.yuv")));
        EXPECT_TRUE(read_bytes(dir / "gst.yuv") == read_bytes(dir / "applied.yuv"));
        EXPECT_NE(read_bytes(dir / "gst.yuv"), read_bytes(dir / "clean.yuv"));
    }
    fs::remove_all(dir);
}

// The form, `filmgrain params=P.json`: JSON parameter files written by `filmgrain params
// convert`, of both models (FGC from the conformance payload, AV1 from a libaom grain table).
// The FGC file gives the pictures the payload gives (the element reads every form the same way).
TEST(GstStaticParams, JsonParameterFileEqualsApply) {
    const fs::path dir = fresh_test_dir("gst-static-json");
    const fs::path fgc = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance/rdd5_352x288_420p10/frame0.fgc.bin";
    ASSERT_TRUE(run_or_fail(tool() + " params convert -q " + q(fgc) + " -o " + q(dir / "fgc.json")));
    write_bytes(dir / "grain.tbl", [] {
        const std::string t =
            "filmgrn1\n"
            "E 0 9223372036854775807 1 46083 1\n"
            "\tp 3 8 0 9 0 1 144 224 437 42 74 494\n"
            "\tsY 14  6 0 18 196 21 140 42 233 55 0 87 0 124 0 128 30 129 0 183 0 184 0 189 0 221 60 228 99\n"
            "\tsCb 2 196 54 213 0\n"
            "\tsCr 4 79 108 100 33 184 50 245 71\n"
            "\tcY -20 9 8 16 33 -25 -6 29 -7 38 -22 1 -25 40 6 -30 4 23 -25 34 -16 -24 26 -23\n"
            "\tcCb 18 -27 37 37 11 19 32 33 12 16 22 1 33 0 38 27 -10 -18 -12 38 12 -37 25 18 25\n"
            "\tcCr 6 -35 -1 -20 33 -8 -5 -30 20 25 -10 0 4 6 -7 8 11 -2 3 0 5 -9 10 1 30\n";
        return std::vector<uint8_t>(t.begin(), t.end());
    }());
    ASSERT_TRUE(run_or_fail(tool() + " params convert -q " + q(dir / "grain.tbl") + " --to json -o " +
                            q(dir / "av1.json")));
    for (const char* json : {"fgc.json", "av1.json"}) {
        const std::string text = text_of(dir / json);
        ASSERT_TRUE(!text.empty() && text.front() == '{') << json << ": " << text.substr(0, 80);
    }
    const std::string size = std::to_string(kWidth) + "x" + std::to_string(kHeight);
    const std::string src = "videotestsrc num-buffers=5 pattern=ball ! video/x-raw,format=I420_10LE,width=" +
                            std::to_string(kWidth) + ",height=" + std::to_string(kHeight);
    ASSERT_TRUE(run_or_fail(gst_launch(src + " ! filesink location=" + q(dir / "clean.yuv"), dir / "log.txt")));
    const auto clean = read_bytes(dir / "clean.yuv");
    ASSERT_EQ(clean.size(), std::size_t(5 * kWidth * kHeight * 3 / 2 * 2));
    for (const char* json : {"fgc.json", "av1.json"}) {
        SCOPED_TRACE(json);
        const fs::path gst = dir / (std::string(json) + ".gst.yuv"), applied = dir / (std::string(json) + ".apply.yuv");
        ASSERT_TRUE(run_or_fail(gst_launch(src + " ! filmgrain params=" + q(dir / json) + " ! filesink location=" + q(gst),
                                           dir / "log.txt")));
        ASSERT_TRUE(run_or_fail(tool() + " apply -q --size " + size + " --pix-fmt yuv420p10le -i " +
                                q(dir / "clean.yuv") + " -p " + q(dir / json) + " -o " + q(applied)));
        const auto out = read_bytes(gst);
        EXPECT_EQ(out.size(), clean.size());
        EXPECT_TRUE(out == read_bytes(applied)) << "the pipeline differs from `filmgrain apply`";
        EXPECT_NE(out, clean);
    }
    ASSERT_TRUE(run_or_fail(gst_launch(src + " ! filmgrain params=" + q(fgc) + " ! filesink location=" +
                                           q(dir / "payload.gst.yuv"),
                                       dir / "log.txt")));
    EXPECT_TRUE(read_bytes(dir / "payload.gst.yuv") == read_bytes(dir / "fgc.json.gst.yuv"));
    fs::remove_all(dir);
}

namespace {

// An FGC SEI with a comp_model_value far outside what RDD 5 allows: parsable, invalid.
std::vector<uint8_t> invalid_fgc_payload() {
    FgcParams p = fgc_params_for(0);
    for (auto& c : p.comp)
        if (c.comp_model_present_flag && !c.intervals.empty()) c.intervals[0].comp_model_value[0] = 5000;
    return write_fgc_sei_payload(p, FgcCodec::kHevc);
}

// The syntax element the library's parser names when `parse` meets the end of a cut payload
// ("payload truncated while reading <field> (at bit n ...)"): what the element must name too.
template <class Parse>
std::string truncated_field(Parse&& parse) {
    try {
        parse();
    } catch (const Error& e) {
        const std::string m = e.what(), marker = "while reading ";
        const std::size_t at = m.find(marker), end = m.find(" (at bit");
        if (at != std::string::npos && end != std::string::npos && end > at)
            return m.substr(at + marker.size(), end - at - marker.size());
        ADD_FAILURE() << "no field in: " << m;
        return m;
    }
    ADD_FAILURE() << "the cut payload parsed";
    return "?";
}

// The plugin gst-launch loads is the one in GST_PLUGIN_PATH (under asan_ubsan.* the
// sanitized build), and nothing a sanitizer reports is in the pipeline's log.
void expect_plugin_from_plugin_path(const fs::path& dir) {
    const char* path = std::getenv("GST_PLUGIN_PATH");
    if (!path || !*path) return;
    ASSERT_TRUE(run_or_fail(gst_tool("gst-inspect-1.0") + " filmgrain > " + q(dir / "inspect.txt") + " 2>&1"));
    const std::string inspect = text_of(dir / "inspect.txt");
    const std::size_t at = inspect.find("Filename");
    ASSERT_NE(at, std::string::npos) << inspect;
    const std::string line = inspect.substr(at, inspect.find('\n', at) - at);
    const std::string first_dir = std::string(path).substr(0, std::string(path).find(':'));
    EXPECT_NE(line.find(fs::path(first_dir).lexically_normal().string() + "/"), std::string::npos) << line;
}

// What the filmgrain element itself posted (`kind`: WARNING or ERROR), from gst-launch's log:
// filmgrainparse warns about a damaged unit too, and that must not stand in for the filter's
// message.
std::string filter_messages(const std::string& log, const std::string& kind) {
    const std::string prefix = kind + ": from element /GstPipeline:pipeline0/GstFilmGrain:filmgrain0: ";
    std::string out;
    for (std::size_t at = log.find(prefix); at != std::string::npos; at = log.find(prefix, at + 1))
        out += log.substr(at + prefix.size(), log.find('\n', at) - at - prefix.size()) + "\n";
    return out;
}

void expect_no_sanitizer_report(const std::string& log) {
    for (const char* report : {"AddressSanitizer", "LeakSanitizer", "runtime error:"})
        EXPECT_EQ(log.find(report), std::string::npos) << log;
}

}  // namespace

// Malformed metadata in the stream: passthrough keeps the pipeline running and warns naming the
// field; error stops it with a message naming the field. CTest also runs these pipelines with
// the plugin built with ASan/UBSan (asan_ubsan.gst_malformed_pipelines).
TEST(GstMalformed, FgcSeiWarnsOrStopsNamingTheField) {
    const fs::path dir = fresh_test_dir("gst-malformed-fgc");
    expect_plugin_from_plugin_path(dir);
    const auto raw = encode_synthetic_clip(dir, StreamCodec::kH265, kWidth, kHeight, 6, 8);
    ASSERT_FALSE(raw.empty());
    const auto bad = invalid_fgc_payload();
    auto cut = write_fgc_sei_payload(fgc_params_for(1), FgcCodec::kHevc);
    cut.resize(3);
    const std::string cut_field = truncated_field([&] { parse_fgc_sei_payload(cut, FgcCodec::kHevc); });
    // `bad.hevc`: the truncated SEI in unit 1, the invalid one in unit 3, valid ones elsewhere;
    // `cut.hevc` and `invalid.hevc` hold one of the two each, for the error runs (B-frames put
    // pictures out of decode order: with both, either may come first)
    for (const char* name : {"bad", "cut", "invalid"})
        write_bytes(dir / (std::string(name) + ".hevc"),
                    with_fgc_sei_per_access_unit(raw, StreamCodec::kH265, [&](int au) {
                        if (au == 1 && std::string(name) != "invalid") return cut;
                        if (au == 3 && std::string(name) != "cut") return bad;
                        return write_fgc_sei_payload(fgc_params_for(au), FgcCodec::kHevc);
                    }));
    const auto pipeline = [&](const char* stream) {
        return "filesrc location=" + q(dir / (std::string(stream) + ".hevc")) +
               " ! h265parse ! filmgrainparse ! avdec_h265 ! filmgrain on-invalid=";
    };
    const int rc_pass = std::system(
        gst_launch(pipeline("bad") + "passthrough ! filesink location=" + q(dir / "pass.yuv"), dir / "pass.txt", true)
            .c_str());
    const std::string pass_log = text_of(dir / "pass.txt");
    EXPECT_EQ(rc_pass, 0) << pass_log;
    // each bad payload warned about, naming its field (the invalid one its value and range too)
    const std::string warnings = filter_messages(pass_log, "WARNING");
    EXPECT_NE(warnings.find("comp_model_value[0][0][0] = 5000"), std::string::npos) << pass_log;
    EXPECT_NE(warnings.find("allowed 0..255"), std::string::npos) << pass_log;
    EXPECT_NE(warnings.find(cut_field), std::string::npos) << cut_field << " not named:\n" << pass_log;
    expect_no_sanitizer_report(pass_log);
    EXPECT_EQ(read_bytes(dir / "pass.yuv").size(), std::size_t(6 * kWidth * kHeight * 3 / 2));
    for (const auto& [stream, field] : {std::pair<std::string, std::string>{"cut", cut_field},
                                        std::pair<std::string, std::string>{"invalid", "comp_model_value[0][0][0] = 5000"}}) {
        SCOPED_TRACE(stream);
        const fs::path log = dir / ("err-" + stream + ".txt");
        const int rc_error = std::system(
            gst_launch(pipeline(stream.c_str()) + "error ! filesink location=" + q(dir / "err.yuv"), log, true).c_str());
        const std::string err_log = text_of(log);
        EXPECT_NE(rc_error, 0) << err_log;
        EXPECT_NE(filter_messages(err_log, "ERROR").find(field), std::string::npos) << field << " not named:\n" << err_log;
        expect_no_sanitizer_report(err_log);
    }
    fs::remove_all(dir);
}

TEST(GstMalformed, Afgs1PayloadWarnsOrStopsNamingTheField) {
    const fs::path dir = fresh_test_dir("gst-malformed-afgs1");
    expect_plugin_from_plugin_path(dir);
    write_synthetic_y4m(dir / "src.y4m", kWidth, kHeight, 4, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=4 --cpu-used=6 -o " + q(dir / "raw.ivf") + " " +
                            q(dir / "src.y4m")));
    std::vector<uint8_t> cut = afgs1_payload_for(2, 8);
    cut.resize(6);  // cut inside the first set
    const std::string cut_field = truncated_field([&] { Afgs1Reader().receive(cut); });
    write_bytes(dir / "bad.ivf", insert_av1_t35(read_bytes(dir / "raw.ivf"), [&](int tu) {
                    return std::vector<std::vector<uint8_t>>{tu == 2 ? cut : afgs1_payload_for(tu == 4 ? 0 : tu, 8)};
                }));
    const std::string pipeline = "filesrc location=" + q(dir / "bad.ivf") +
                                 " ! ivfparse ! av1parse ! filmgrainparse ! av1dec ! filmgrain on-invalid=";
    const int rc_pass = std::system(
        gst_launch(pipeline + "passthrough ! filesink location=" + q(dir / "pass.yuv"), dir / "pass.txt", true).c_str());
    const std::string pass_log = text_of(dir / "pass.txt");
    EXPECT_EQ(rc_pass, 0) << pass_log;
    const std::string warnings = filter_messages(pass_log, "WARNING");
    EXPECT_NE(warnings.find("AFGS1 payload"), std::string::npos) << pass_log;
    EXPECT_NE(warnings.find(cut_field), std::string::npos) << cut_field << " not named:\n" << pass_log;
    expect_no_sanitizer_report(pass_log);
    EXPECT_EQ(read_bytes(dir / "pass.yuv").size(), std::size_t(4 * kWidth * kHeight * 3 / 2));
    const int rc_error = std::system(
        gst_launch(pipeline + "error ! filesink location=" + q(dir / "err.yuv"), dir / "err.txt", true).c_str());
    const std::string err_log = text_of(dir / "err.txt");
    EXPECT_NE(rc_error, 0) << err_log;
    const std::string errors = filter_messages(err_log, "ERROR");
    EXPECT_NE(errors.find("AFGS1 payload"), std::string::npos) << err_log;
    EXPECT_NE(errors.find(cut_field), std::string::npos) << cut_field << " not named:\n" << err_log;
    expect_no_sanitizer_report(err_log);
    fs::remove_all(dir);
}

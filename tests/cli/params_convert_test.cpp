// `filmgrain params convert` round trips and `filmgrain apply --afgs1`: AV1 parameters as
// JSON, a libaom grain table and AFGS1 payloads (with and without the T.35 header), and FGC
// parameters as JSON and SEI payloads, all give the same output picture for picture; the
// parameters read back equal those written. A damaged AFGS1 payload is an error naming the
// file and the element, with no output left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "conformance_case.hpp"
#include "metadata/av1_params_json.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 176, kH = 144, kFrames = 3;

// Three frames: distinct sets, then the second set again with only a new seed (which the
// AFGS1 writer sends as update_grain_flag = 0).
const char* const kAv1Json = R"({"frames": [
 {"av1": {"apply_grain": 1, "grain_seed": 1234, "update_grain": 1, "num_y_points": 2,
  "point_y_value": [0, 255], "point_y_scaling": [60, 90], "chroma_scaling_from_luma": 0,
  "num_cb_points": 1, "point_cb_value": [128], "point_cb_scaling": [40],
  "num_cr_points": 2, "point_cr_value": [0, 255], "point_cr_scaling": [30, 50],
  "grain_scaling_minus_8": 2, "ar_coeff_lag": 2,
  "ar_coeffs_y_plus_128": [130, 125, 131, 127, 122, 133, 129, 126, 135, 120, 128, 140],
  "ar_coeffs_cb_plus_128": [127, 129, 126, 130, 125, 131, 128, 128, 124, 132, 129, 127, 140],
  "ar_coeffs_cr_plus_128": [129, 127, 130, 126, 131, 125, 128, 128, 132, 124, 127, 129, 118],
  "ar_coeff_shift_minus_6": 1, "grain_scale_shift": 0,
  "cb_mult": 140, "cb_luma_mult": 180, "cb_offset": 260, "cr_mult": 120, "cr_luma_mult": 200, "cr_offset": 250,
  "overlap_flag": 1, "clip_to_restricted_range": 0}},
 {"av1": {"apply_grain": 1, "grain_seed": 777, "update_grain": 1, "num_y_points": 3,
  "point_y_value": [0, 100, 255], "point_y_scaling": [20, 100, 40], "chroma_scaling_from_luma": 1,
  "num_cb_points": 0, "num_cr_points": 0, "grain_scaling_minus_8": 0, "ar_coeff_lag": 1,
  "ar_coeffs_y_plus_128": [140, 110, 135, 150], "ar_coeffs_cb_plus_128": [120, 130, 125, 128, 140],
  "ar_coeffs_cr_plus_128": [136, 126, 131, 128, 116], "ar_coeff_shift_minus_6": 0, "grain_scale_shift": 1,
  "overlap_flag": 0, "clip_to_restricted_range": 0}},
 {"av1": {"apply_grain": 1, "grain_seed": 4242, "update_grain": 1, "num_y_points": 3,
  "point_y_value": [0, 100, 255], "point_y_scaling": [20, 100, 40], "chroma_scaling_from_luma": 1,
  "num_cb_points": 0, "num_cr_points": 0, "grain_scaling_minus_8": 0, "ar_coeff_lag": 1,
  "ar_coeffs_y_plus_128": [140, 110, 135, 150], "ar_coeffs_cb_plus_128": [120, 130, 125, 128, 140],
  "ar_coeffs_cr_plus_128": [136, 126, 131, 128, 116], "ar_coeff_shift_minus_6": 0, "grain_scale_shift": 1,
  "overlap_flag": 0, "clip_to_restricted_range": 0}}
]})";

const char* const kFgcJson = R"({"frames": [
 {"fgc": {"film_grain_model_id": 0, "log2_scale_factor": 5, "comp_model_present_flag": [1, 1, 0],
  "num_intensity_intervals_minus1": [1, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0, 128], [0], []], "intensity_interval_upper_bound": [[127, 255], [255], []],
  "comp_model_value": [[[100, 8, 8], [80, 10, 10]], [[40]], []], "film_grain_characteristics_persistence_flag": 1}},
 {},
 {"fgc": {"film_grain_model_id": 0, "log2_scale_factor": 4, "comp_model_present_flag": [1, 0, 1],
  "num_intensity_intervals_minus1": [0, 0, 0], "num_model_values_minus1": [2, 0, 0],
  "intensity_interval_lower_bound": [[0], [], [0]], "intensity_interval_upper_bound": [[255], [], [255]],
  "comp_model_value": [[[120, 6, 12]], [], [[60]]], "film_grain_characteristics_persistence_flag": 1}}
]})";

class ParamsConvertCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() / ("filmgrain-convert-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
        // three yuv420p frames with gradients, so the grain's intensity dependence shows
        std::string frames;
        for (int k = 0; k < kFrames; k++) {
            for (int y = 0; y < kH; y++)
                for (int x = 0; x < kW; x++) frames += char(16 + (x + 2 * y + 9 * k) % 220);
            for (int c = 0; c < 2; c++)
                for (int y = 0; y < kH / 2; y++)
                    for (int x = 0; x < kW / 2; x++) frames += char(96 + (3 * x + y * (c + 1) + k) % 64);
        }
        std::ofstream(dir / "in.yuv", std::ios::binary) << frames;
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string p(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
    }
    std::string read(const std::string& name) const {
        std::ifstream f(dir / name, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    }
    int tool(const std::string& args, std::string* log = nullptr) {
        return run_command(std::string("'") + FILMGRAIN_TOOL_PATH + "' " + args, log);
    }
    // `apply` of the three frames with `params`, into `out`; its output.
    std::string apply(const std::string& params, const std::string& out) {
        std::string log;
        EXPECT_EQ(tool("apply -q -i " + p("in.yuv") + " -o " + p(out) + " --size 176x144 --pix-fmt yuv420p " + params,
                       &log),
                  0)
            << log;
        return read(out);
    }
    void convert(const std::string& args) {
        std::string log;
        ASSERT_EQ(tool("params convert -q " + args, &log), 0) << log;
    }
    std::vector<Av1FrameParams> av1_frames(const std::string& name) const {
        const std::string text = read(name);
        return av1_frame_params_from_json(nlohmann::json::parse(text));
    }
    fs::path dir;
};

}  // namespace

TEST_F(ParamsConvertCli, Av1JsonTableAndAfgs1RoundTripsApplyIdentically) {
    write("p.json", kAv1Json);
    const std::string want = apply("--params " + p("p.json"), "json.yuv");
    ASSERT_EQ(want.size(), std::size_t(kFrames * kW * kH * 3 / 2));
    EXPECT_NE(want, read("in.yuv"));

    // JSON -> table -> JSON
    convert(p("p.json") + " -o " + p("p.tbl"));
    EXPECT_EQ(read("p.tbl").rfind("filmgrn1", 0), 0u);
    EXPECT_EQ(apply("--params " + p("p.tbl"), "tbl.yuv"), want);
    convert(p("p.tbl") + " -o " + p("from_tbl.json") + " --frames 3");
    EXPECT_EQ(apply("--params " + p("from_tbl.json"), "from_tbl.yuv"), want);

    // JSON -> AFGS1 payloads (one per frame) -> JSON
    convert(p("p.json") + " -o " + p("a%d.bin") + " --size 176x144 --pix-fmt yuv420p");
    for (int k = 0; k < kFrames; k++) ASSERT_TRUE(fs::exists(dir / ("a" + std::to_string(k) + ".bin"))) << k;
    // the third frame repeats the second's set with a new seed: a short update_grain_flag = 0 set
    EXPECT_LT(read("a2.bin").size(), read("a1.bin").size() / 2);
    EXPECT_EQ(apply("--afgs1 " + p("a%d.bin"), "afgs1.yuv"), want);
    EXPECT_EQ(apply("--afgs1 " + p("a0.bin") + " " + p("a1.bin") + " " + p("a2.bin"), "afgs1_list.yuv"), want);
    convert(p("a%d.bin") + " -o " + p("from_afgs1.json") + " --size 176x144 --pix-fmt yuv420p");
    EXPECT_EQ(apply("--params " + p("from_afgs1.json"), "from_afgs1.yuv"), want);

    // the parameters read back are those written
    const auto orig = av1_frames("p.json"), via_table = av1_frames("from_tbl.json"), via_afgs1 = av1_frames("from_afgs1.json");
    ASSERT_EQ(via_table.size(), orig.size());
    ASSERT_EQ(via_afgs1.size(), orig.size());
    for (std::size_t k = 0; k < orig.size(); k++) {
        EXPECT_EQ(via_table[k].grain, orig[k].grain) << "frame " << k;
        EXPECT_EQ(via_afgs1[k].grain, orig[k].grain) << "frame " << k;
    }
}

TEST_F(ParamsConvertCli, Afgs1PayloadsWithAndWithoutT35HeaderApplyIdentically) {
    write("p.json", kAv1Json);
    convert(p("p.json") + " -o " + p("a%d.bin") + " --size 176x144 --pix-fmt yuv420p");
    for (int k = 0; k < kFrames; k++) {
        const std::string b = read("a" + std::to_string(k) + ".bin");
        ASSERT_GE(b.size(), 5u);
        EXPECT_EQ(b.substr(0, 4), std::string("\xB5\x58\x90\x01", 4));
        write("bare" + std::to_string(k) + ".bin", b.substr(4));
    }
    EXPECT_EQ(apply("--afgs1 " + p("bare%d.bin"), "bare.yuv"), apply("--afgs1 " + p("a%d.bin"), "t35.yuv"));
    // a missing payload file: that picture gets no grain
    fs::remove(dir / "bare1.bin");
    const std::string gap = apply("--afgs1 " + p("bare%d.bin"), "gap.yuv");
    const std::size_t frame = std::size_t(kW * kH * 3 / 2);
    EXPECT_EQ(gap.substr(frame, frame), read("in.yuv").substr(frame, frame));
    EXPECT_NE(gap.substr(0, frame), read("in.yuv").substr(0, frame));
}

TEST_F(ParamsConvertCli, DamagedAfgs1PayloadFailsNamingFileAndElement) {
    write("p.json", kAv1Json);
    convert(p("p.json") + " -o " + p("a%d.bin") + " --size 176x144 --pix-fmt yuv420p");
    const std::string b = read("a1.bin");
    write("a1.bin", b.substr(0, b.size() / 2));
    std::string log;
    EXPECT_NE(tool("apply -i " + p("in.yuv") + " -o " + p("out.yuv") + " --size 176x144 --pix-fmt yuv420p --afgs1 " +
                       p("a%d.bin"),
                   &log),
              0);
    EXPECT_NE(log.find("a1.bin"), std::string::npos) << log;
    EXPECT_NE(log.find("truncated"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(dir / "out.yuv"));
}

TEST_F(ParamsConvertCli, FgcJsonAndSeiRoundTripApplyIdentically) {
    write("f.json", kFgcJson);
    const std::string want = apply("--params " + p("f.json"), "json.yuv");
    EXPECT_NE(want, read("in.yuv"));
    // frame 1 carries no SEI: the pattern's missing file, as the JSON's empty entry
    convert(p("f.json") + " -o " + p("s%d.sei") + " --sei-codec hevc");
    ASSERT_TRUE(fs::exists(dir / "s0.sei"));
    ASSERT_TRUE(fs::exists(dir / "s1.sei"));
    fs::rename(dir / "s1.sei", dir / "s2.sei");
    EXPECT_EQ(apply("--sei " + p("s%d.sei"), "sei.yuv"), want);
    fs::rename(dir / "s2.sei", dir / "s1.sei");
    convert(p("s%d.sei") + " -o " + p("back.json") + " --sei-codec hevc");
    // the SEIs come back in order; with frame 1's own entry between them they apply as before
    nlohmann::json back = nlohmann::json::parse(read("back.json"));
    ASSERT_EQ(back.at("frames").size(), 2u);
    nlohmann::json spaced = {{"frames", {back["frames"][0], nlohmann::json::object(), back["frames"][1]}}};
    write("spaced.json", spaced.dump());
    EXPECT_EQ(apply("--params " + p("spaced.json"), "back.yuv"), want);
    // FGC parameters have no AV1 form
    std::string log;
    EXPECT_NE(tool("params convert " + p("f.json") + " -o " + p("x.tbl"), &log), 0);
    EXPECT_FALSE(fs::exists(dir / "x.tbl"));
}

// Output into a pipe (or a device such as /dev/null) goes straight into it: a temporary
// renamed over the path would replace the pipe with a plain file, its reader would get
// nothing, and /dev/null would stop being a device. Both the frame writer (`apply`) and the
// text writer (`params convert`).
TEST_F(ParamsConvertCli, OutputIntoAPipeReachesItsReaderAndLeavesAPipe) {
    write("p.json", kAv1Json);
    const std::string want = apply("--params " + p("p.json"), "file.yuv");
    auto through_pipe = [&](const std::string& args, const std::string& name) {
        int status;
        bool still_fifo;
        std::string log;
        const std::string got = read_through_fifo((dir / name).string(),
                                                  std::string("'") + FILMGRAIN_TOOL_PATH + "' " + args + " -o " + p(name),
                                                  &status, &still_fifo, &log);
        EXPECT_EQ(status, 0) << log;
        EXPECT_TRUE(still_fifo) << args;
        return got;
    };
    // (sizes and a flag, not the bytes: a failure would print whole frames)
    const std::string frames =
        through_pipe("apply -q -i " + p("in.yuv") + " --size 176x144 --pix-fmt yuv420p --params " + p("p.json"),
                     "pipe.yuv");
    EXPECT_EQ(frames.size(), want.size());
    EXPECT_TRUE(frames == want);
    convert(p("p.json") + " -o " + p("p.tbl"));
    const std::string table = through_pipe("params convert -q " + p("p.json"), "pipe.tbl");
    EXPECT_EQ(table.size(), read("p.tbl").size());
    EXPECT_TRUE(table == read("p.tbl"));
    for (const auto& e : fs::directory_iterator(dir)) {
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
        EXPECT_EQ(e.path().filename().string().find(".filmgrain-partial"), std::string::npos) << e.path();
    }
}

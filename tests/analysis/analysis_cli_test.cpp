// `filmgrain analyze` and `filmgrain preset` as users call them: outputs usable by `apply`,
// the report with its images, errors that leave no output behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "io/video_file.hpp"
#include "io/xz_file.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/params_file.hpp"
#include "synthetic_content.hpp"

namespace filmgrain {
namespace {

namespace fs = std::filesystem;
using test_support::run_command;

std::string tool() { return FILMGRAIN_TOOL_PATH; }

fs::path scratch(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("filmgrain_analysis_cli_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// A short grainy Y4M clip (FGC grain, 8-bit 4:2:0) and its clean original; `steps`: the
// grain alternates between weak and strong every 32 intensity values.
void write_clip(const fs::path& grainy, const fs::path& clean_path, int frames, bool steps = false) {
    const PixelFormat fmt{ChromaFormat::k420, 8};
    FrameBuffer clean = analysis_test::make_clean_picture(256, 256, fmt);
    VideoInfo info;
    info.width = 256;
    info.height = 256;
    info.format = fmt;
    VideoWriter wg(grainy.string(), info, true), wc(clean_path.string(), info, true);
    FgcParams p;
    p.log2_scale_factor = 5;
    FgcIntensityInterval iv;
    iv.intensity_interval_upper_bound = 255;
    iv.comp_model_value = {150, 8, 8, 0, 0, 0};
    p.comp[0] = {true, 2, {iv}};
    if (steps) {
        p.comp[0].intervals.clear();
        for (int k = 0; k < 8; k++) {
            iv.intensity_interval_lower_bound = 32 * k;
            iv.intensity_interval_upper_bound = 32 * k + 31;
            iv.comp_model_value = {k % 2 ? 220 : 40, 8, 8, 0, 0, 0};
            p.comp[0].intervals.push_back(iv);
        }
    }
    FgcStreamSynthesis s(FgcOptions{});
    for (int k = 0; k < frames; k++) {
        FrameBuffer g = clean;
        s.receive_sei(p);
        s.apply(clean.view(), g.view(), FgcPictureIds{k, 0});
        wg.write(g);
        wc.write(clean);
    }
    wg.commit();
    wc.commit();
}

TEST(AnalysisCli, FgcOutputsFeedApplyAndReportHasImages) {
    const fs::path d = scratch("fgc");
    write_clip(d / "grainy.y4m", d / "clean.y4m", 6);
    std::string log;
    ASSERT_EQ(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --model fgc -o " + (d / "p.json").string() +
                              " --sei " + (d / "p.bin").string() + " --report " + (d / "r" / "report.html").string() + " -q",
                          &log),
              0)
        << log;
    const ParamsFile pf = load_params_file((d / "p.json").string());
    ASSERT_TRUE(pf.has_fgc());
    EXPECT_TRUE(pf.frames[0].fgc->comp[0].comp_model_present_flag);
    std::ifstream sei(d / "p.bin", std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(sei)), std::istreambuf_iterator<char>());
    const FgcParams from_sei = parse_fgc_sei_payload(bytes, FgcCodec::kHevc);
    EXPECT_EQ(from_sei.comp[0].intervals.size(), pf.frames[0].fgc->comp[0].intervals.size());
    for (const char* f : {"report.html", "report-scaling.png", "report-spectrum.png", "report-crop.png"})
        EXPECT_GT(fs::file_size(d / "r" / f), 100u) << f;
    // PNG signature, then IHDR: the scaling plot is 720 wide, 300 high per plane (three here),
    // 8-bit RGB (colour type 2)
    {
        std::ifstream png(d / "r" / "report-scaling.png", std::ios::binary);
        std::string head(26, '\0');
        png.read(head.data(), 26);
        EXPECT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
        EXPECT_EQ(head.substr(12, 4), "IHDR");
        auto be32 = [&](int at) {
            return (uint32_t(uint8_t(head[at])) << 24) | (uint32_t(uint8_t(head[at + 1])) << 16) |
                   (uint32_t(uint8_t(head[at + 2])) << 8) | uint8_t(head[at + 3]);
        };
        EXPECT_EQ(be32(16), 720u);
        EXPECT_EQ(be32(20), 900u);
        EXPECT_EQ(int(head[24]), 8);
        EXPECT_EQ(int(head[25]), 2);
    }
    std::ifstream html(d / "r" / "report.html");
    const std::string text((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("report-scaling.png"), std::string::npos);
    EXPECT_EQ(run_command(tool() + " apply -i " + (d / "clean.y4m").string() + " -o " + (d / "re.y4m").string() +
                              " --params " + (d / "p.json").string() + " -q",
                          &log),
              0)
        << log;
    fs::remove_all(d);
}

TEST(AnalysisCli, Av1JsonAndTableFeedApply) {
    const fs::path d = scratch("av1");
    write_clip(d / "grainy.y4m", d / "clean.y4m", 4);
    std::string log;
    ASSERT_EQ(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --denoised " + (d / "clean.y4m").string() +
                              " --model av1 -o " + (d / "p.json").string() + " --table " + (d / "p.tbl").string() +
                              " --afgs1 " + (d / "p.afgs1").string() + " -q",
                          &log),
              0)
        << log;
    const AomGrainTable t = read_aom_grain_table((d / "p.tbl").string());
    ASSERT_EQ(t.entries.size(), 4u);
    EXPECT_EQ(t.entries[0].params.apply_grain, 1);
    // The AFGS1 payload carries the first picture's estimated set, for the input's format.
    Afgs1Reader reader;
    const Afgs1Payload pl = reader.receive(read_whole_file((d / "p.afgs1").string()));
    ASSERT_EQ(pl.sets.size(), 1u);
    Av1FilmGrainParams want = t.entries[0].params, got = pl.sets[0].params;
    want.update_grain = got.update_grain = 1;
    EXPECT_EQ(av1_params_to_json(got), av1_params_to_json(want));
    for (const char* p : {"p.json", "p.tbl"})
        EXPECT_EQ(run_command(tool() + " apply -i " + (d / "clean.y4m").string() + " -o " + (d / "re.y4m").string() +
                                  " --params " + (d / p).string() + " -q",
                              &log),
                  0)
            << p << ": " << log;
    fs::remove_all(d);
}

TEST(AnalysisCli, BadArgumentsLeaveNoOutput) {
    const fs::path d = scratch("err");
    write_clip(d / "grainy.y4m", d / "clean.y4m", 2);
    std::string log;
    EXPECT_NE(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --model xyz -o " + (d / "p.json").string(), &log), 0);
    EXPECT_NE(log.find("--model"), std::string::npos) << log;
    EXPECT_NE(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --model fgc --table t.tbl -o " + (d / "p.json").string(), &log), 0);
    EXPECT_NE(run_command(tool() + " analyze " + (d / "missing.y4m").string() + " --model fgc -o " + (d / "p.json").string(), &log), 0);
    EXPECT_FALSE(fs::exists(d / "p.json"));
    EXPECT_NE(run_command(tool() + " preset --photon-noise 0 --model av1 --size 64x64 -o " + (d / "q.json").string(), &log), 0);
    EXPECT_NE(log.find("ISO"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(d / "q.json"));
    fs::remove_all(d);
}

// The accuracy check: a component whose fit misses its measured levels by more than
// --max-error is refused, named with its band, the miss and the limit, and nothing is
// written; --force writes it.
TEST(AnalysisCli, AccuracyCheckRefusesUnlessForced) {
    const fs::path d = scratch("accuracy");
    write_clip(d / "grainy.y4m", d / "clean.y4m", 4, true);
    // AV1's 14 points cannot follow eight plateaus
    const std::string base = tool() + " analyze " + (d / "grainy.y4m").string() + " --denoised " + (d / "clean.y4m").string() +
                             " --model av1 --max-error 0.05 -o " + (d / "p.json").string() + " --table " +
                             (d / "t.tbl").string();
    std::string log;
    EXPECT_NE(run_command(base, &log), 0);
    EXPECT_NE(log.find("Y: the fitted levels miss the measured grain level by"), std::string::npos) << log;
    EXPECT_NE(log.find("--max-error"), std::string::npos) << log;
    EXPECT_NE(log.find("--force"), std::string::npos) << log;
    EXPECT_FALSE(fs::exists(d / "p.json"));
    EXPECT_FALSE(fs::exists(d / "t.tbl"));
    EXPECT_EQ(run_command(base + " --force", &log), 0) << log;
    EXPECT_NE(log.find("written despite failing its accuracy check (--force)"), std::string::npos) << log;
    EXPECT_TRUE(fs::exists(d / "p.json"));
    // the default check passes this clip
    fs::remove(d / "p.json");
    EXPECT_EQ(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --model fgc -o " + (d / "p.json").string(), &log), 0)
        << log;
    EXPECT_NE(run_command(tool() + " analyze " + (d / "grainy.y4m").string() + " --model fgc --max-error 0 -o " + (d / "q.json").string(), &log), 0);
    EXPECT_NE(log.find("--max-error"), std::string::npos) << log;
    fs::remove_all(d);
}

TEST(AnalysisCli, PhotonNoisePresetsApply) {
    const fs::path d = scratch("preset");
    write_clip(d / "grainy.y4m", d / "clean.y4m", 2);
    std::string log;
    for (const char* tf : {"sdr", "pq", "hlg"})
        for (const char* model : {"fgc", "av1"}) {
            const std::string out = (d / (std::string(model) + "-" + tf + ".json")).string();
            ASSERT_EQ(run_command(tool() + " preset --photon-noise 3200 --model " + model + " --transfer " + tf +
                                      " --size 256x256 --pix-fmt yuv420p --frames 2 -o " + out,
                                  &log),
                      0)
                << log;
            EXPECT_EQ(run_command(tool() + " apply -i " + (d / "clean.y4m").string() + " -o " + (d / "re.y4m").string() +
                                      " --params " + out + " -q",
                                  &log),
                      0)
                << model << " " << tf << ": " << log;
        }
    fs::remove_all(d);
}

}  // namespace
}  // namespace filmgrain

// Differential test against libaom: random valid grain tables (fixed seeds) are
// given to `aomenc --film-grain-table` for a small lossless clip, `aomdec` decodes
// with grain applied, and our synthesis of the same parameters on the clean clip
// (= the encoder input, since the coding is lossless) must match bit for bit.
//
// Seeds: libaom's encoder takes random_seed from the table only at timestamp 0
// (aom_film_grain_table_lookup keeps the running seed for any other time), and
// after every shown or showable frame it advances the running seed by 3381,
// replacing 0 by 7391 (encoder.c). With --lag-in-frames=0 every frame is shown
// once, so frame k's grain_seed is that sequence's k-th value; we reproduce it
// instead of parsing the frame headers out of the IVF file.
//
// Each encode carries two table entries (frames 0-1 and 2-3), so 36 encodes test
// 72 parameter sets over 8/10/12 bits x 4:2:0/4:2:2/4:4:4/monochrome, lags 0-3
// and every shift. Every third case also goes through the tool: the table is
// written by `filmgrain params convert` from JSON, encoded, and `filmgrain apply
// --params` of that table must equal aomdec's first frame.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <unistd.h>

#include "av1/av1_picture_synthesis.hpp"
#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "io/video_file.hpp"
#include "io/xz_file.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"

using namespace filmgrain;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 64, kHeight = 48, kFrames = 4;
constexpr int64_t kTicksPerFrame = 400000;  // 10 MHz ticks at 25 fps

struct Format {
    ChromaFormat chroma;
    int bit_depth;
};

const Format kFormats[] = {
    {ChromaFormat::k420, 8},  {ChromaFormat::k422, 8},  {ChromaFormat::k444, 8},  {ChromaFormat::k400, 8},
    {ChromaFormat::k420, 10}, {ChromaFormat::k422, 10}, {ChromaFormat::k444, 10}, {ChromaFormat::k400, 10},
    {ChromaFormat::k420, 12}, {ChromaFormat::k422, 12}, {ChromaFormat::k444, 12}, {ChromaFormat::k400, 12},
};

// A random parameter set that AV1 can signal for the format (6.8.20 constraints).
Av1FilmGrainParams random_params(std::mt19937& rng, ChromaFormat chroma, int lag) {
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.update_grain = 1;
    p.grain_seed = r(0, 65535);
    auto points = [&](int max_points, int* count, int* values, int* scalings) {
        *count = r(1, max_points);
        int v = r(0, 40);
        for (int i = 0; i < *count; ++i) {
            values[i] = v;
            scalings[i] = r(0, 255);
            v += r(1, 60);
            if (v > 255) {
                *count = i + 1;
                break;
            }
        }
    };
    if (r(0, 5)) points(14, &p.num_y_points, p.point_y_value.data(), p.point_y_scaling.data());
    const bool mono = chroma == ChromaFormat::k400;
    if (!mono) {
        p.chroma_scaling_from_luma = r(0, 3) == 0;
        const bool chroma_points = !p.chroma_scaling_from_luma && !(chroma == ChromaFormat::k420 && !p.num_y_points);
        if (chroma_points) {
            const bool both = chroma == ChromaFormat::k420 || r(0, 2);
            const int which = r(0, 1);
            if (both || which == 0) points(10, &p.num_cb_points, p.point_cb_value.data(), p.point_cb_scaling.data());
            if (both || which == 1) points(10, &p.num_cr_points, p.point_cr_value.data(), p.point_cr_scaling.data());
        }
    }
    p.grain_scaling_minus_8 = r(0, 3);
    p.ar_coeff_lag = lag;
    auto coeff = [&] { return r(0, 4) == 0 ? r(0, 255) : 128 + r(-40, 40); };
    for (int i = 0; i < p.num_pos_luma(); ++i) p.ar_coeffs_y_plus_128[i] = p.num_y_points ? coeff() : 128;
    const bool cb = p.chroma_scaling_from_luma || p.num_cb_points, cr = p.chroma_scaling_from_luma || p.num_cr_points;
    for (int i = 0; i < p.num_pos_chroma(); ++i) {
        p.ar_coeffs_cb_plus_128[i] = cb ? coeff() : 128;
        p.ar_coeffs_cr_plus_128[i] = cr ? coeff() : 128;
    }
    p.ar_coeff_shift_minus_6 = r(0, 3);
    p.grain_scale_shift = r(0, 3);
    if (p.num_cb_points) {
        p.cb_mult = r(0, 255);
        p.cb_luma_mult = r(0, 255);
        p.cb_offset = r(0, 511);
    }
    if (p.num_cr_points) {
        p.cr_mult = r(0, 255);
        p.cr_luma_mult = r(0, 255);
        p.cr_offset = r(0, 511);
    }
    p.overlap_flag = r(0, 1);
    p.clip_to_restricted_range = 0;  // grain tables cannot carry it
    return p;
}

// Smooth content with some texture, different per frame and plane, over the full range.
std::vector<FrameBuffer> make_clip(std::mt19937& rng, const Format& f) {
    // aomenc takes monochrome input as 4:2:0 with --monochrome.
    const PixelFormat pf{f.chroma == ChromaFormat::k400 ? ChromaFormat::k420 : f.chroma, f.bit_depth};
    const int max = (1 << f.bit_depth) - 1;
    std::vector<FrameBuffer> clip;
    for (int k = 0; k < kFrames; ++k) {
        FrameBuffer fb(kWidth, kHeight, pf);
        FrameView v = fb.view();
        for (int p = 0; p < v.plane_count(); ++p) {
            const PlaneView& pl = v.planes[p];
            for (int y = 0; y < pl.height; ++y)
                for (int x = 0; x < pl.width; ++x) {
                    int s = (x * max) / pl.width / 2 + (y * max) / pl.height / 2 + int(rng() % 9) - 4 + k * 3 + p * 17;
                    if (f.chroma == ChromaFormat::k400 && p > 0) s = 1 << (f.bit_depth - 1);
                    s = std::clamp(s, 0, max);
                    if (f.bit_depth > 8) pl.row<uint16_t>(y)[x] = uint16_t(s);
                    else pl.row<uint8_t>(y)[x] = uint8_t(s);
                }
        }
        clip.push_back(std::move(fb));
    }
    return clip;
}

void write_y4m(const std::string& path, const std::vector<FrameBuffer>& clip, int frames) {
    VideoInfo info;
    info.width = kWidth;
    info.height = kHeight;
    info.format = clip[0].format();
    info.y4m = true;
    VideoWriter w(path, info, true);
    for (int k = 0; k < frames; ++k) w.write(clip[std::size_t(k)]);
    w.commit();
}

std::string encode_command(const Format& f, const std::string& table, const std::string& in, const std::string& out,
                           int frames) {
    int profile = 0;
    if (f.chroma == ChromaFormat::k444) profile = 1;
    if (f.chroma == ChromaFormat::k422 || f.bit_depth == 12) profile = 2;
    std::string cmd = "aomenc --limit=" + std::to_string(frames) +
                      " --passes=1 --lossless=1 --cpu-used=6 --lag-in-frames=0 --profile=" + std::to_string(profile) +
                      " --bit-depth=" + std::to_string(f.bit_depth) +
                      " --input-bit-depth=" + std::to_string(f.bit_depth) + " --film-grain-table=" + table;
    if (f.chroma == ChromaFormat::k400) cmd += " --monochrome";
    return cmd + " -o " + out + " " + in;
}

uint16_t next_seed(uint16_t s) {
    s = uint16_t(s + 3381);
    return s == 0 ? 7391 : s;
}

// Our output for one frame: the clean frame (luma only for monochrome) with grain.
FrameBuffer synthesize(const FrameBuffer& clean, const Format& f, const Av1FilmGrainParams& p) {
    FrameBuffer in = clean;
    FrameView src = in.view();
    if (f.chroma == ChromaFormat::k400) src.format = ChromaFormat::k400;
    FrameBuffer out(kWidth, kHeight, clean.format());
    FrameView dst = out.view();
    dst.format = src.format;
    av1::apply_film_grain(p, src, dst, 2);
    return out;
}

// Compares the decoded frame with ours; monochrome compares luma only.
std::string compare(const std::vector<uint8_t>& decoded, std::size_t offset, const FrameBuffer& ours, const Format& f) {
    const std::size_t bytes = f.chroma == ChromaFormat::k400 ? ours.plane_bytes(0) : ours.byte_size();
    if (decoded.size() < offset + bytes) return "decoded output too short";
    const int bps = f.bit_depth > 8 ? 2 : 1;
    for (std::size_t i = 0; i < bytes; i += std::size_t(bps)) {
        const int a = bps == 2 ? decoded[offset + i] | decoded[offset + i + 1] << 8 : decoded[offset + i];
        const int b = bps == 2 ? ours.bytes()[i] | ours.bytes()[i + 1] << 8 : ours.bytes()[i];
        if (a != b) {
            int plane = 0;
            while (plane < 2 && i >= ours.plane_offset(plane + 1)) ++plane;
            const std::size_t in_plane = (i - ours.plane_offset(plane)) / std::size_t(bps);
            const int pw = plane_width(ours.format().chroma, plane, kWidth);
            return "plane " + std::to_string(plane) + " (" + std::to_string(in_plane % std::size_t(pw)) + ", " +
                   std::to_string(in_plane / std::size_t(pw)) + "): aomdec " + std::to_string(a) + ", ours " +
                   std::to_string(b);
        }
    }
    return "";
}

class AomDifferential : public ::testing::TestWithParam<int> {};

}  // namespace

TEST_P(AomDifferential, AomdecMatchesOurSynthesis) {
    const int index = GetParam();
    const Format f = kFormats[index % 12];
    std::mt19937 rng(1000u + unsigned(index));
    const fs::path dir = fs::temp_directory_path() / ("filmgrain_aomdiff_" + std::to_string(::getpid()) + "_" +
                                                      std::to_string(index));
    fs::create_directories(dir);
    const std::vector<FrameBuffer> clip = make_clip(rng, f);
    write_y4m((dir / "clean.y4m").string(), clip, kFrames);

    // Two entries with different lags; together the cases cover every lag per format.
    AomGrainTable table;
    for (int e = 0; e < 2; ++e) {
        AomGrainTableEntry entry;
        entry.start_time = e * 2 * kTicksPerFrame;
        entry.end_time = e == 0 ? 2 * kTicksPerFrame : 1000 * kTicksPerFrame;
        entry.params = random_params(rng, f.chroma, (index / 12 + 2 * e + index) % 4);
        table.entries.push_back(entry);
    }
    const std::string tbl = (dir / "grain.tbl").string();
    write_aom_grain_table(table, tbl);

    std::string log;
    const std::string ivf = (dir / "grain.ivf").string(), yuv = (dir / "aomdec.yuv").string();
    ASSERT_EQ(filmgrain::test_support::run_command(encode_command(f, tbl, (dir / "clean.y4m").string(), ivf, kFrames), &log), 0) << log;
    ASSERT_EQ(filmgrain::test_support::run_command("aomdec --rawvideo -o " + yuv + " " + ivf, &log), 0) << log;
    const std::vector<uint8_t> decoded = read_whole_file(yuv);
    // aomdec writes every plane of the coded format (monochrome: its own layout; luma first).
    const std::size_t frame_bytes = decoded.size() / kFrames;
    ASSERT_EQ(frame_bytes * kFrames, decoded.size());

    uint16_t seed = uint16_t(table.entries[0].params.grain_seed);
    for (int k = 0; k < kFrames; ++k) {
        Av1FilmGrainParams p = table.resolved_params(*table.find_index(k * kTicksPerFrame));
        p.grain_seed = seed;
        const FrameBuffer ours = synthesize(clip[std::size_t(k)], f, p);
        EXPECT_EQ(compare(decoded, frame_bytes * std::size_t(k), ours, f), "")
            << "case " << index << " (" << pix_fmt_name({f.chroma, f.bit_depth}) << ", lag " << p.ar_coeff_lag
            << ", seed " << seed << ") frame " << k;
        seed = next_seed(seed);
    }

    // Through the tool: the table written by `params convert`, applied by `apply --params`.
    if (index % 3 == 0 && f.chroma != ChromaFormat::k400) {
        Av1FrameParams fp;
        fp.grain = table.entries[1].params;
        const std::string json = (dir / "one.json").string();
        std::ofstream(json) << av1_frame_params_to_json({fp}).dump();
        const std::string tool = FILMGRAIN_TOOL_PATH;
        const std::string tool_tbl = (dir / "tool.tbl").string();
        ASSERT_EQ(filmgrain::test_support::run_command(tool + " params convert " + json + " -o " + tool_tbl, &log), 0) << log;
        write_y4m((dir / "one.y4m").string(), clip, 1);
        const std::string ivf1 = (dir / "tool.ivf").string(), yuv1 = (dir / "tool_aomdec.yuv").string();
        ASSERT_EQ(filmgrain::test_support::run_command(encode_command(f, tool_tbl, (dir / "one.y4m").string(), ivf1, 1), &log), 0)
            << "aomenc rejected our table: " << log;
        ASSERT_EQ(filmgrain::test_support::run_command("aomdec --rawvideo -o " + yuv1 + " " + ivf1, &log), 0) << log;
        const std::string ours = (dir / "tool_ours.yuv").string();
        ASSERT_EQ(filmgrain::test_support::run_command(tool + " apply -q --params " + tool_tbl + " -i " + (dir / "one.y4m").string() +
                                           " -o " + ours,
                                       &log),
                  0)
            << log;
        EXPECT_EQ(read_whole_file(yuv1), read_whole_file(ours)) << "case " << index << ": tool vs aomdec";
    }
    fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(RandomTables, AomDifferential, ::testing::Range(0, 36));

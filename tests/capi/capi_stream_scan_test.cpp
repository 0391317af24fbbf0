// The stream scanner of libfilmgrain (fg_stream_scan_*): film grain metadata of coded streams
// through the shared library, on the goldens' own streams. The H.265 streams carry an FGC
// SEI in every access unit and B-frames, so output order differs from decode order; the AV1
// stream carries frame-header grain whose values the case records.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <filmgrain/filmgrain.h>

#include "conformance_case.hpp"
#include "io/xz_file.hpp"
#include "metadata/json_access.hpp"

namespace fs = std::filesystem;
using namespace filmgrain::test_support;
using filmgrain::read_json_file;
using filmgrain::read_whole_file;

namespace {

std::vector<uint8_t> stream_of(const ConformanceCase& c, const char* file) {
    return read_whole_file((fs::path(c.dir) / file).string());
}

struct ScanDeleter {
    void operator()(fg_stream_scan* s) const { fg_stream_scan_destroy(s); }
};
using ScanPtr = std::unique_ptr<fg_stream_scan, ScanDeleter>;

ScanPtr scan_of(const std::vector<uint8_t>& bytes, int codec) {
    fg_stream_scan* s = nullptr;
    char message[256] = "";
    EXPECT_EQ(fg_stream_scan_create(bytes.data(), bytes.size(), codec, &s, message, sizeof message), FG_OK)
        << message;
    return ScanPtr(s);
}

}  // namespace

TEST(CapiStreamScan, FgcSeiOfEveryHevcAccessUnitInOutputOrder) {
    int cases = 0, reordered = 0;
    for (const std::string& name : list_cases("ffmpeg71-")) {
        cases++;
        const ConformanceCase c = load_case_description(name);
        const nlohmann::json sei = read_json_file((fs::path(c.dir) / "fgc.json").string());
        ScanPtr scan = scan_of(stream_of(c, "stream.hevc"), FG_STREAM_H265);
        ASSERT_TRUE(scan) << name;
        const int frames = c.frames;
        ASSERT_EQ(fg_stream_scan_unit_count(scan.get()), frames) << name;
        EXPECT_EQ(fg_stream_scan_stream_warning_count(scan.get()), 0) << name;
        bool in_decode_order = true;
        for (int k = 0; k < frames; k++) {
            fg_stream_unit u{};
            ASSERT_EQ(fg_stream_scan_unit(scan.get(), k, &u), FG_OK);
            EXPECT_TRUE(u.has_poc);
            EXPECT_EQ(u.poc, k) << name << ": output order is POC order (one sequence)";
            EXPECT_EQ(u.sequence, 0);
            EXPECT_TRUE(u.output);
            EXPECT_EQ(u.warning_count, 0) << name << " unit " << k << ": " << fg_stream_scan_warning(scan.get(), k, 0);
            in_decode_order &= u.decode_index == k;
            ASSERT_EQ(u.fgc_count, 1) << name << " unit " << k;
            EXPECT_EQ(u.t35_count, 0);
            EXPECT_FALSE(u.has_av1_grain);
            const uint8_t* payload = nullptr;
            size_t size = 0;
            ASSERT_EQ(fg_stream_scan_fgc_payload(scan.get(), k, 0, &payload, &size), FG_OK);
            fg_fgc_params p;
            fg_fgc_params_init(&p);
            char message[256] = "";
            ASSERT_EQ(fg_fgc_params_from_sei(payload, size, FG_CODEC_HEVC, &p, message, sizeof message), FG_OK)
                << message;
            // the SEI the stream maker wrote from fgc.json
            EXPECT_EQ(p.log2_scale_factor, sei.at("log2_scale_factor").get<long long>());
            for (std::size_t comp = 0; comp < 3; comp++) {
                EXPECT_EQ(p.comp_model_present_flag[comp], sei.at("comp_model_present_flag").at(comp).get<long long>());
                if (!p.comp_model_present_flag[comp]) continue;
                EXPECT_EQ(p.num_intensity_intervals_minus1[comp],
                          sei.at("num_intensity_intervals_minus1").at(comp).get<long long>());
                EXPECT_EQ(p.comp_model_value[comp][0][0], sei.at("comp_model_value").at(comp).at(0).at(0).get<long long>());
            }
        }
        reordered += !in_decode_order;
    }
    EXPECT_EQ(cases, 10);
    EXPECT_GT(reordered, 0) << "B-frames: some stream's output order differs from its decode order";
}

TEST(CapiStreamScan, Av1FrameHeaderGrainAsTheCaseRecordsIt) {
    const ConformanceCase c = load_case_description("av1_tv16_176x144_420p8");
    ScanPtr scan = scan_of(stream_of(c, "stream.ivf"), FG_STREAM_AV1);
    ASSERT_TRUE(scan);
    const int frames = c.frames;
    ASSERT_EQ(fg_stream_scan_unit_count(scan.get()), frames);
    for (int k = 0; k < frames; k++) {
        fg_stream_unit u{};
        ASSERT_EQ(fg_stream_scan_unit(scan.get(), k, &u), FG_OK);
        EXPECT_EQ(u.decode_index, k);
        ASSERT_TRUE(u.has_av1_grain);
        fg_av1_grain g;
        fg_av1_grain_init(&g);
        ASSERT_EQ(fg_stream_scan_av1_grain(scan.get(), k, &g), FG_OK);
        const nlohmann::json& want = c.frame_info(k).at("params").at("av1");
        EXPECT_EQ(g.apply_grain, want.at("apply_grain").get<long long>()) << "frame " << k;
        if (!g.apply_grain) continue;
        EXPECT_EQ(int(g.seed), want.at("grain_seed").get<long long>()) << "frame " << k;
        ASSERT_EQ(g.num_y_points, want.at("num_y_points").get<long long>());
        for (int i = 0; i < g.num_y_points; i++) {
            EXPECT_EQ(g.y_points[i][0], want.at("point_y_value").at(std::size_t(i)).get<long long>());
            EXPECT_EQ(g.y_points[i][1], want.at("point_y_scaling").at(std::size_t(i)).get<long long>());
        }
        // and it is what a context takes
        fg_context* ctx = nullptr;
        fg_options o;
        fg_options_init(&o);
        ASSERT_EQ(fg_context_create(&o, &ctx, nullptr, 0), FG_OK);
        EXPECT_EQ(fg_context_push_av1_grain(ctx, &g), FG_OK) << fg_last_error(ctx);
        fg_context_destroy(ctx);
    }
}

TEST(CapiStreamScan, BadArgumentsNameTheFieldAndItsRange) {
    const std::vector<uint8_t> bytes = stream_of(load_case_description("ffmpeg71-352x288-420p8-nmv1"), "stream.hevc");
    fg_stream_scan* s = reinterpret_cast<fg_stream_scan*>(1);
    char message[256] = "";
    EXPECT_EQ(fg_stream_scan_create(bytes.data(), bytes.size(), 7, &s, message, sizeof message),
              FG_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(s, nullptr) << "no scan on failure";
    EXPECT_NE(std::string(message).find("codec = 7"), std::string::npos) << message;
    EXPECT_NE(std::string(message).find("0..3"), std::string::npos) << message;
    EXPECT_EQ(fg_stream_scan_create(nullptr, 10, FG_STREAM_H265, &s, message, sizeof message),
              FG_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(fg_stream_scan_create(bytes.data(), bytes.size(), FG_STREAM_H265, nullptr, nullptr, 0),
              FG_ERROR_INVALID_ARGUMENT);

    ScanPtr scan = scan_of(bytes, FG_STREAM_H265);
    ASSERT_TRUE(scan);
    const int n = fg_stream_scan_unit_count(scan.get());
    fg_stream_unit u{};
    EXPECT_EQ(fg_stream_scan_unit(scan.get(), n, &u), FG_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(fg_stream_scan_last_error(scan.get())).find("unit = " + std::to_string(n)), std::string::npos)
        << fg_stream_scan_last_error(scan.get());
    EXPECT_NE(std::string(fg_stream_scan_last_error(scan.get())).find("0.." + std::to_string(n - 1)), std::string::npos);
    EXPECT_EQ(fg_stream_scan_unit(scan.get(), -1, &u), FG_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(fg_stream_scan_unit(nullptr, 0, &u), FG_ERROR_INVALID_ARGUMENT);
    const uint8_t* p = nullptr;
    size_t size = 0;
    EXPECT_EQ(fg_stream_scan_fgc_payload(scan.get(), 0, 1, &p, &size), FG_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(fg_stream_scan_t35_payload(scan.get(), 0, 0, &p, &size), FG_ERROR_INVALID_ARGUMENT);
    fg_av1_grain g;
    fg_av1_grain_init(&g);
    EXPECT_EQ(fg_stream_scan_av1_grain(scan.get(), 0, &g), FG_ERROR_INVALID_ARGUMENT) << "an HEVC unit has none";
    EXPECT_NE(std::string(fg_stream_scan_last_error(scan.get())).find("no AV1 frame-header film grain"), std::string::npos);
    ASSERT_EQ(fg_stream_scan_unit(scan.get(), 0, &u), FG_OK);
    EXPECT_STREQ(fg_stream_scan_last_error(scan.get()), "") << "a success clears it";
    EXPECT_EQ(fg_stream_scan_warning(scan.get(), 0, 0), nullptr);
    EXPECT_EQ(fg_stream_scan_warning(scan.get(), n + 3, 0), nullptr);
    EXPECT_EQ(fg_stream_scan_unit_count(nullptr), 0);
    fg_stream_scan_destroy(nullptr);
}

TEST(CapiStreamScan, DamagedStreamsGiveWarningsNotCrashes) {
    const std::vector<uint8_t> bytes = stream_of(load_case_description("ffmpeg71-350x198-420p8"), "stream.hevc");
    ASSERT_GT(bytes.size(), 200u);
    // cut inside the stream: the units before the cut are still found
    for (std::size_t cut : {std::size_t(7), bytes.size() / 3, bytes.size() - 5}) {
        const std::vector<uint8_t> part(bytes.begin(), bytes.begin() + std::ptrdiff_t(cut));
        ScanPtr scan = scan_of(part, FG_STREAM_H265);
        ASSERT_TRUE(scan) << "cut at " << cut;
        const int units = fg_stream_scan_unit_count(scan.get());
        EXPECT_LE(units, 6);
        if (cut > bytes.size() / 2) EXPECT_GE(units, 5) << "the units before the cut at " << cut;
    }
    // every byte flipped in turn over the parameter sets and first SEI
    for (std::size_t at = 0; at < 160; at++) {
        std::vector<uint8_t> bad = bytes;
        bad[at] ^= 0xA5;
        fg_stream_scan* s = nullptr;
        const fg_status st = fg_stream_scan_create(bad.data(), bad.size(), FG_STREAM_H265, &s, nullptr, 0);
        EXPECT_TRUE(st == FG_OK || st == FG_ERROR_MALFORMED_PAYLOAD) << "byte " << at << ": " << fg_status_name(st);
        fg_stream_scan_destroy(s);
    }
    // not a stream at all
    const std::vector<uint8_t> zeros(4096, 0);
    ScanPtr scan = scan_of(zeros, FG_STREAM_AV1);
    ASSERT_TRUE(scan);
    EXPECT_GT(fg_stream_scan_stream_warning_count(scan.get()) + fg_stream_scan_unit_count(scan.get()), 0);
    EXPECT_EQ(fg_stream_scan_unit_count(scan.get()), 0);
    ASSERT_EQ(fg_stream_scan_stream_warning_count(scan.get()), 1);
    EXPECT_NE(std::string(fg_stream_scan_warning(scan.get(), -1, 0)).find("temporal delimiter"), std::string::npos)
        << fg_stream_scan_warning(scan.get(), -1, 0);
}

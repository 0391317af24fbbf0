// Conformance through the C API (libfilmgrain.so): the vtm/rdd5 cases decoder style (each
// access unit's SEI payload pushed with its picture ids one picture ahead of output, so the
// SEI has to wait for its picture), the vfgs cases with equal input and output bit depth,
// and every AV1 case with its case.json parameters handed over as fg_av1_params. Each
// output frame's MD5 must equal the golden.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <optional>

#include <filmgrain/filmgrain.h>

#include "afgs1_case.hpp"
#include "conformance_case.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"
#include "metadata/av1_params_json.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> cases_with(std::initializer_list<const char*> prefixes) {
    std::vector<std::string> out;
    for (const char* p : prefixes) {
        auto v = list_cases(p);
        out.insert(out.end(), v.begin(), v.end());
    }
    return out;
}

fg_frame to_c_frame(FrameBuffer& b) {
    FrameView v = b.view();
    fg_frame f{};
    for (int p = 0; p < v.plane_count(); p++) {
        f.planes[p] = v.planes[p].data;
        f.strides[p] = v.planes[p].stride;
    }
    f.width = v.width;
    f.height = v.height;
    f.bit_depth = v.bit_depth;
    f.chroma_format = static_cast<int>(v.format);
    return f;
}

struct Context {
    fg_context* ctx = nullptr;
    explicit Context(const fg_options& o) {
        char msg[512] = "";
        EXPECT_EQ(fg_context_create(&o, &ctx, msg, sizeof msg), FG_OK) << msg;
    }
    ~Context() { fg_context_destroy(ctx); }
};

// Applies grain to frame k of the case out of place and returns the MD5.
std::string apply_frame(const ConformanceCase& c, fg_context* ctx, int k, const fg_picture_ids* ids) {
    FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
    fg_frame src = to_c_frame(in), dst = to_c_frame(out);
    fg_frame_info info;
    fg_frame_info_init(&info);
    if (ids) info.ids = *ids;
    const fg_status st = fg_context_apply(ctx, &src, &dst, ids ? &info : nullptr);
    EXPECT_EQ(st, FG_OK) << c.name << " frame " << k << ": " << fg_last_error(ctx);
    return md5_hex(out.bytes(), out.byte_size());
}

class CapiFgcConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(CapiFgcConformance, SeiPayloadsWithPictureIds) {
    const ConformanceCase c = load_case(GetParam());
    const fg_codec codec = c.json.at("codec") == "h264" ? FG_CODEC_AVC : FG_CODEC_HEVC;
    fg_options o;
    fg_options_init(&o);
    o.flavour = c.json.at("family") == "vtm" ? FG_FLAVOUR_VTM : FG_FLAVOUR_RDD5;
    o.passthrough_invalid = 1;  // the references output the clean picture
    Context ctx(o);
    ASSERT_NE(ctx.ctx, nullptr);
    auto ids_of = [&](int k) {
        const auto& fi = c.frame_info(k);
        fg_picture_ids ids{fi.at("poc").get<int>(), fi.at("idr_pic_id").is_null() ? 0 : fi.at("idr_pic_id").get<int>()};
        return ids;
    };
    auto push = [&](int k) {
        if (k >= c.frames || !c.frame_info(k).at("sei_present").get<bool>()) return;
        const std::vector<uint8_t> payload =
            read_whole_file((fs::path(c.dir) / ("frame" + std::to_string(k) + ".fgc.bin")).string());
        const fg_picture_ids ids = ids_of(k);
        ASSERT_EQ(fg_context_push_fgc_sei(ctx.ctx, payload.data(), payload.size(), codec, &ids), FG_OK)
            << fg_last_error(ctx.ctx);
    };
    push(0);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        push(k + 1);  // decoded ahead of the picture being output
        const fg_picture_ids ids = ids_of(k);
        if (apply_frame(c, ctx.ctx, k, &ids) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << c.name << " frame " << k << " differs from expected_md5";
        }
    }
    EXPECT_EQ(mismatches, 0);
}

INSTANTIATE_TEST_SUITE_P(Cases, CapiFgcConformance, ::testing::ValuesIn(cases_with({"vtm_", "rdd5_"})),
                         [](const auto& info) { return info.param; });

class CapiVfgsConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(CapiVfgsConformance, SeiPayloadsInOutputOrder) {
    const ConformanceCase c = load_case(GetParam());
    fg_options o;
    fg_options_init(&o);
    o.flavour = FG_FLAVOUR_VFGS;
    if (!c.json.at("seed").is_null()) {
        o.vfgs_has_seed = 1;
        o.vfgs_seed = c.json.at("seed").get<uint32_t>();
    }
    o.vfgs_gain_percent = c.json.value("vfgs_gain_percent", 100);
    Context ctx(o);
    ASSERT_NE(ctx.ctx, nullptr);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        char name[32];
        std::snprintf(name, sizeof name, "fgc_%04d.bin", c.frame_info(k).at("poc").get<int>());
        const fs::path bin = fs::path(c.dir) / name;
        if (fs::exists(bin)) {
            const std::vector<uint8_t> payload = read_whole_file(bin.string());
            ASSERT_EQ(fg_context_push_fgc_sei(ctx.ctx, payload.data(), payload.size(), FG_CODEC_HEVC, nullptr), FG_OK)
                << fg_last_error(ctx.ctx);
        }
        if (apply_frame(c, ctx.ctx, k, nullptr) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << c.name << " frame " << k << " differs from expected_md5";
        }
    }
    EXPECT_EQ(mismatches, 0);
}

std::vector<std::string> vfgs_same_depth_cases() {
    std::vector<std::string> out;
    for (const std::string& n : list_cases("vfgs-")) {
        const ConformanceCase c = load_case(n);
        if (c.output_format.bit_depth == c.format.bit_depth) out.push_back(n);
    }
    return out;
}

INSTANTIATE_TEST_SUITE_P(Cases, CapiVfgsConformance, ::testing::ValuesIn(vfgs_same_depth_cases()),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& ch : n)
                                 if (ch == '-') ch = '_';
                             return n;
                         });

fg_av1_params to_c_params(const Av1FilmGrainParams& p, int matrix_coefficients) {
    fg_av1_params c;
    fg_av1_params_init(&c);
    c.apply_grain = p.apply_grain;
    c.grain_seed = p.grain_seed;
    c.update_grain = 1;  // case.json holds the effective parameters
    c.num_y_points = p.num_y_points;
    for (int i = 0; i < 14; i++) {
        c.point_y_value[i] = p.point_y_value[i];
        c.point_y_scaling[i] = p.point_y_scaling[i];
    }
    c.chroma_scaling_from_luma = p.chroma_scaling_from_luma;
    c.num_cb_points = p.num_cb_points;
    c.num_cr_points = p.num_cr_points;
    for (int i = 0; i < 10; i++) {
        c.point_cb_value[i] = p.point_cb_value[i];
        c.point_cb_scaling[i] = p.point_cb_scaling[i];
        c.point_cr_value[i] = p.point_cr_value[i];
        c.point_cr_scaling[i] = p.point_cr_scaling[i];
    }
    c.grain_scaling_minus_8 = p.grain_scaling_minus_8;
    c.ar_coeff_lag = p.ar_coeff_lag;
    for (int i = 0; i < 24; i++) c.ar_coeffs_y_plus_128[i] = p.ar_coeffs_y_plus_128[i];
    for (int i = 0; i < 25; i++) {
        c.ar_coeffs_cb_plus_128[i] = p.ar_coeffs_cb_plus_128[i];
        c.ar_coeffs_cr_plus_128[i] = p.ar_coeffs_cr_plus_128[i];
    }
    c.ar_coeff_shift_minus_6 = p.ar_coeff_shift_minus_6;
    c.grain_scale_shift = p.grain_scale_shift;
    c.cb_mult = p.cb_mult;
    c.cb_luma_mult = p.cb_luma_mult;
    c.cb_offset = p.cb_offset;
    c.cr_mult = p.cr_mult;
    c.cr_luma_mult = p.cr_luma_mult;
    c.cr_offset = p.cr_offset;
    c.overlap_flag = p.overlap_flag;
    c.clip_to_restricted_range = p.clip_to_restricted_range;
    c.matrix_coefficients = matrix_coefficients;
    return c;
}

class CapiAv1Conformance : public ::testing::TestWithParam<std::string> {};

// Frame 0 is refreshed into slot 0; later frames that repeat frame 0's parameters are
// signalled as update_grain = 0 from slot 0 with their own seed, as an encoder may.
TEST_P(CapiAv1Conformance, FrameHeadersThroughReferenceSlots) {
    const ConformanceCase c = load_case(GetParam());
    const std::vector<Av1FrameParams> params = av1_frame_params_from_json(c.json);
    ASSERT_EQ(static_cast<int>(params.size()), c.frames);
    fg_options o;
    fg_options_init(&o);
    Context ctx(o);
    ASSERT_NE(ctx.ctx, nullptr);
    int mismatches = 0, loaded = 0;
    for (int k = 0; k < c.frames; k++) {
        const int mc = c.frame_info(k).at("params").value("matrix_coefficients", 2);
        Av1FilmGrainParams p = params[std::size_t(k)].grain;
        fg_av1_params cp = to_c_params(p, mc);
        Av1FilmGrainParams same_but_seed = params[0].grain;
        same_but_seed.grain_seed = p.grain_seed;
        if (k > 0 && p.apply_grain && params[0].grain.apply_grain && same_but_seed == p) {
            fg_av1_params_init(&cp);
            cp.apply_grain = 1;
            cp.update_grain = 0;
            cp.film_grain_params_ref_idx = 0;
            cp.grain_seed = p.grain_seed;
            cp.matrix_coefficients = mc;
            loaded++;
        }
        ASSERT_EQ(fg_context_push_av1_params(ctx.ctx, &cp, k == 0 ? 0x01u : 0u), FG_OK) << fg_last_error(ctx.ctx);
        if (apply_frame(c, ctx.ctx, k, nullptr) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << c.name << " frame " << k << " differs from expected_md5";
        }
    }
    EXPECT_EQ(mismatches, 0);
    RecordProperty("frames_loaded_from_slot", loaded);
}

INSTANTIATE_TEST_SUITE_P(Cases, CapiAv1Conformance, ::testing::ValuesIn(list_cases("av1_")),
                         [](const auto& info) { return info.param; });

// The afgs1 family through libfilmgrain.so: each picture's T.35 payload (when its access unit
// had one) with fg_context_push_afgs1_t35, then fg_context_apply.
class CapiAfgs1Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(CapiAfgs1Conformance, T35PayloadsPerPicture) {
    const ConformanceCase c = load_case(GetParam());
    fg_options o;
    fg_options_init(&o);
    Context ctx(o);
    ASSERT_NE(ctx.ctx, nullptr);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        if (const auto payload = afgs1_payload(c, k))
            ASSERT_EQ(fg_context_push_afgs1_t35(ctx.ctx, payload->data(), payload->size()), FG_OK)
                << c.name << " frame " << k << ": " << fg_last_error(ctx.ctx);
        if (apply_frame(c, ctx.ctx, k, nullptr) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << c.name << " frame " << k << " differs from expected_md5";
        }
    }
    EXPECT_EQ(mismatches, 0);
}

// The case's coded H.265 stream (AFGS1 in T.35 SEI, B-frames) read by the library's scanner
// instead of the case's per-picture files: each unit in output order hands over its payload
// resolved in decode order (fg_stream_scan_afgs1_payload), and every picture must give its
// golden. The raw T.35 bytes are given too and must be the case's file for that picture.
TEST(CapiAfgs1Stream, HevcSeiScannedAndAppliedInOutputOrderGivesEveryGolden) {
    const ConformanceCase c = load_case("afgs1-352x288-420p8-bframes");
    const std::vector<uint8_t> stream = read_whole_file((fs::path(c.dir) / "stream.hevc").string());
    fg_stream_scan* scan = nullptr;
    char message[256] = "";
    ASSERT_EQ(fg_stream_scan_create(stream.data(), stream.size(), FG_STREAM_H265, &scan, message, sizeof message),
              FG_OK)
        << message;
    ASSERT_EQ(fg_stream_scan_unit_count(scan), c.frames);
    fg_options o;
    fg_options_init(&o);
    Context ctx(o);
    ASSERT_NE(ctx.ctx, nullptr);
    int reordered = 0, with_payload = 0;
    for (int k = 0; k < c.frames; k++) {
        SCOPED_TRACE("output picture " + std::to_string(k));
        fg_stream_unit u{};
        ASSERT_EQ(fg_stream_scan_unit(scan, k, &u), FG_OK);
        reordered += u.decode_index != k;
        const uint8_t* data = nullptr;
        size_t size = 0;
        ASSERT_EQ(fg_stream_scan_afgs1_payload(scan, k, &data, &size), FG_OK) << fg_stream_scan_last_error(scan);
        const auto file = afgs1_payload(c, k);
        ASSERT_EQ(size > 0, file.has_value());
        if (size) {
            with_payload++;
            const uint8_t* raw = nullptr;
            size_t raw_size = 0;
            ASSERT_EQ(fg_stream_scan_t35_payload(scan, k, 0, &raw, &raw_size), FG_OK);
            EXPECT_TRUE(std::vector<uint8_t>(raw, raw + raw_size) == *file) << "T.35 bytes differ from the case's file";
            ASSERT_EQ(fg_context_push_afgs1_t35(ctx.ctx, data, size), FG_OK) << fg_last_error(ctx.ctx);
        }
        EXPECT_EQ(apply_frame(c, ctx.ctx, k, nullptr), c.expected_md5(k));
    }
    EXPECT_GT(reordered, 0) << "B-frames: decode order differs from output order";
    EXPECT_EQ(with_payload, c.frames);
    // A unit index out of range names the argument and its range; NULL outputs are refused.
    const uint8_t* data = nullptr;
    size_t size = 0;
    EXPECT_EQ(fg_stream_scan_afgs1_payload(scan, c.frames, &data, &size), FG_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(fg_stream_scan_last_error(scan)).find("unit = " + std::to_string(c.frames)),
              std::string::npos)
        << fg_stream_scan_last_error(scan);
    EXPECT_EQ(fg_stream_scan_afgs1_payload(scan, 0, nullptr, &size), FG_ERROR_INVALID_ARGUMENT);
    fg_stream_scan_destroy(scan);
}

INSTANTIATE_TEST_SUITE_P(Cases, CapiAfgs1Conformance, ::testing::ValuesIn(list_cases("afgs1-")),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (auto& ch : n)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return n;
                         });

}  // namespace

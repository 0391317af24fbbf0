// The C++ API (filmgrain.hpp) through libfilmgrain.so: errors cross the library boundary
// as filmgrain::Error with their code, and Session gives the C API's samples.
#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <filmgrain/filmgrain.h>
#include <filmgrain/filmgrain.hpp>

#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/json_access.hpp"
#include "metadata/params_file.hpp"

using namespace filmgrain;

namespace {

const char* const kSei =
    "{\"film_grain_model_id\": 0, \"log2_scale_factor\": 5, \"comp_model_present_flag\": [1, 1, 0],"
    " \"num_intensity_intervals_minus1\": [0, 0, 0], \"num_model_values_minus1\": [2, 0, 0],"
    " \"intensity_interval_lower_bound\": [[0], [0], []], \"intensity_interval_upper_bound\": [[255], [255], []],"
    " \"comp_model_value\": [[[100, 8, 8]], [[40]], []]}";

// What an application that keeps parameter sets as JSON does: the tool-side reader
// (src/metadata, not in libfilmgrain) gives a typed set, which goes to the session.
void push_json(Session& s, const std::string& text, FgcCodec codec = FgcCodec::kHevc,
               std::optional<FgcPictureIds> picture = std::nullopt) {
    const nlohmann::json j =
        parse_json_document(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "JSON parameters");
    const ParamsFile f = parse_params_json(j);
    if (f.frames.at(0).fgc) {
        s.receive_fgc_params(*f.frames[0].fgc, codec, picture);
        return;
    }
    const std::vector<Av1FrameParams> av1 = av1_frame_params_from_json(j);
    s.receive_av1_params(av1.at(0).grain, 0, av1[0].color ? av1[0].color->matrix_coefficients : 2);
}

FrameBuffer test_picture() {
    FrameBuffer b(160, 128, PixelFormat{ChromaFormat::k420, 10});
    for (std::size_t i = 0; i < b.byte_size(); i += 2) {
        const uint16_t v = static_cast<uint16_t>(64 + (i * 7) % 800);
        std::memcpy(b.bytes() + i, &v, 2);
    }
    return b;
}

TEST(CppFacade, OptionErrorsAreThrownWithTheirCode) {
    SessionOptions o;
    o.threads = -2;
    try {
        Session ctx(o);
        FAIL() << "no exception";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
        EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
    }
}

TEST(CppFacade, ParameterErrorsNameTheField) {
    Session ctx;
    try {
        FgcParams p;
        p.log2_scale_factor = 40;
        ctx.receive_fgc_params(p, FgcCodec::kHevc);
        // checked with the picture, as an SEI's values are (passthrough_invalid applies)
        FrameBuffer a = test_picture();
        ctx.apply(a.view(), a.view());
        FAIL() << "no exception";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
        EXPECT_NE(std::string(e.what()).find("log2_scale_factor"), std::string::npos) << e.what();
    }
    EXPECT_THROW(ctx.receive_afgs1_t35(nullptr, 0), Error);
}

TEST(CppFacade, SameSamplesAsTheCApi) {
    FrameBuffer a = test_picture(), b = test_picture();
    const std::string clean = md5_hex(a.bytes(), a.byte_size());

    Session cpp;
    push_json(cpp, kSei);
    FrameInfo info;
    info.ids.poc = 6;
    const ApplyResult r = cpp.apply(a.view(), a.view(), &info);
    EXPECT_TRUE(r.grain_applied);

    fg_context* c = nullptr;
    ASSERT_EQ(fg_context_create(nullptr, &c, nullptr, 0), FG_OK);
    const std::vector<uint8_t> sei = write_fgc_sei_payload(
        *parse_params_json(parse_json_document(reinterpret_cast<const uint8_t*>(kSei), std::strlen(kSei), "kSei"))
             .frames.at(0)
             .fgc,
        FgcCodec::kHevc);
    ASSERT_EQ(fg_context_push_fgc_sei(c, sei.data(), sei.size(), FG_CODEC_HEVC, nullptr), FG_OK);
    const FrameView v = b.view();
    fg_frame f{};
    for (int p = 0; p < 3; p++) {
        f.planes[p] = v.planes[p].data;
        f.strides[p] = v.planes[p].stride;
    }
    f.width = v.width;
    f.height = v.height;
    f.bit_depth = v.bit_depth;
    f.chroma_format = FG_CHROMA_420;
    fg_frame_info ci;
    fg_frame_info_init(&ci);
    ci.ids.poc = 6;
    ASSERT_EQ(fg_context_apply(c, &f, nullptr, &ci), FG_OK) << fg_last_error(c);
    fg_context_destroy(c);

    EXPECT_NE(md5_hex(a.bytes(), a.byte_size()), clean);
    EXPECT_EQ(md5_hex(a.bytes(), a.byte_size()), md5_hex(b.bytes(), b.byte_size()));
}

TEST(CppFacade, MovedContextKeepsItsState) {
    FrameBuffer a = test_picture(), b = test_picture();
    Session first;
    push_json(first, kSei);
    Session moved = std::move(first);
    EXPECT_TRUE(moved.apply(a.view(), a.view()).grain_applied);
    Session fresh;
    push_json(fresh, kSei);
    fresh.apply(b.view(), b.view());
    EXPECT_EQ(md5_hex(a.bytes(), a.byte_size()), md5_hex(b.bytes(), b.byte_size()));
}

}  // namespace

namespace {

// Each frame's parameter set of a conformance case, handed over as JSON text as an
// application would read it from a file: the goldens must come out.
void run_case_through_json(const std::string& name) {
    const filmgrain::test_support::ConformanceCase c = filmgrain::test_support::load_case(name);
    SessionOptions o;
    o.flavour = c.json.at("family") == "vtm" ? FgcFlavour::kVtm : FgcFlavour::kRdd5;
    o.passthrough_invalid = true;
    Session ctx(o);
    const bool av1 = c.json.at("family") == "av1";
    for (int k = 0; k < c.frames; k++) {
        const auto& fi = c.frame_info(k);
        FrameInfo info;
        if (av1) {
            push_json(ctx, fi.at("params").dump());  // {"av1": {...}, "matrix_coefficients": ...}
        } else {
            info.ids.poc = fi.at("poc").get<int>();
            info.ids.idr_pic_id = fi.at("idr_pic_id").is_null() ? 0 : fi.at("idr_pic_id").get<int>();
            if (fi.at("sei_present").get<bool>())
                push_json(ctx, fi.at("params").dump(), c.json.at("codec") == "h264" ? FgcCodec::kAvc : FgcCodec::kHevc,
                          info.ids);
        }
        FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
        ctx.apply(in.view(), out.view(), &info);
        EXPECT_EQ(md5_hex(out.bytes(), out.byte_size()), c.expected_md5(k)) << name << " frame " << k;
    }
}

TEST(CppFacade, JsonParameterSetsReproduceGoldens) {
    for (const char* name : {"av1_tv01_352x288_420p10", "av1_tbl_mono_176x144_gray", "rdd5_352x288_420p8_rand",
                             "rdd5_h264_352x288_420p8_idr", "vtm_352x288_420p8_invalid_mix"})
        run_case_through_json(name);
}

// The same cases' AV1 parameter sets sent as AFGS1 payloads written by the project's
// writer, one per picture (alternately with and without the T.35 header), each set aimed at
// the case's picture: the goldens must come out of receive_afgs1_t35 as they do of the
// frame-header path.
TEST(CppFacade, Afgs1PayloadsReproduceAv1Goldens) {
    for (const char* name : {"av1_tv01_352x288_420p10", "av1_tbl_mono_176x144_gray", "av1_tbl_352x288_422p8"}) {
        const filmgrain::test_support::ConformanceCase c = filmgrain::test_support::load_case(name);
        ASSERT_GT(c.frames, 1) << name;
        Session ctx;
        for (int k = 0; k < c.frames; k++) {
            const std::vector<Av1FrameParams> fp = av1_frame_params_from_json(c.frame_info(k).at("params"));
            ASSERT_EQ(fp.size(), 1u);
            Afgs1ParamSet set;
            set.params = fp[0].grain;
            set.params.update_grain = 1;
            set.params.film_grain_params_ref_idx = 0;
            Afgs1SetTarget& t = set.target;
            t.apply_horz_resolution = c.width;
            t.apply_vert_resolution = c.height;
            t.luma_only_flag = c.format.chroma == ChromaFormat::k400;
            t.subsampling_x = t.luma_only_flag ? 0 : chroma_shift_x(c.format.chroma);
            t.subsampling_y = t.luma_only_flag ? 0 : chroma_shift_y(c.format.chroma);
            t.video_signal_characteristics_flag = 1;
            t.bit_depth_minus8 = c.format.bit_depth - 8;
            const int mc = fp[0].color ? fp[0].color->matrix_coefficients : 2;
            if (mc != 2) {
                t.cicp_info_present_flag = 1;
                t.matrix_coefficients = mc;
            }
            if (t.luma_only_flag) {
                // A luma-only set carries no chroma scaling; the picture has no chroma to take it.
                set.params.num_cb_points = set.params.num_cr_points = 0;
                set.params.chroma_scaling_from_luma = 0;
            }
            Afgs1Payload payload;
            payload.sets.push_back(set);
            Afgs1WriteOptions wo;
            wo.t35_header = k % 2 == 0;
            const std::vector<uint8_t> bytes = write_afgs1(payload, wo);
            ctx.receive_afgs1_t35(bytes.data(), bytes.size());
            FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
            ctx.apply(in.view(), out.view());
            EXPECT_EQ(md5_hex(out.bytes(), out.byte_size()), c.expected_md5(k)) << name << " frame " << k;
        }
    }
}

TEST(CppFacade, DamagedAfgs1PayloadIsAnErrorNamingTheElement) {
    Session ctx;
    const uint8_t other_provider[] = {0xB5, 0x00, 0x31, 0x01, 0x80};
    try {
        ctx.receive_afgs1_t35(other_provider, sizeof other_provider);
        FAIL() << "no exception";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedPayload);
        EXPECT_NE(std::string(e.what()).find("itu_t_t35_terminal_provider_code = 49"), std::string::npos) << e.what();
    }
    FrameBuffer a = test_picture();
    const std::string clean = md5_hex(a.bytes(), a.byte_size());
    const ApplyResult r = ctx.apply(a.view(), a.view());
    EXPECT_FALSE(r.grain_applied);
    EXPECT_EQ(md5_hex(a.bytes(), a.byte_size()), clean);
}

}  // namespace

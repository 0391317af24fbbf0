// VFGS parameter set-up (TR 23002-9 clause 7.5 / Annex B.2.2): value completion,
// 4:2:0 chroma conversion, --gain, LUTs and validation messages.
#include <gtest/gtest.h>

#include <string>

#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

FgcParams base_params(int model = 0) {
    FgcParams p;
    p.film_grain_model_id = model;
    p.log2_scale_factor = 5;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    p.comp[0].intervals.push_back({0, 255, {100, 8, 8, 0, 0, 0}});
    return p;
}

// Runs `f` and returns the Error it throws (fails the test if none).
template <typename F>
Error expect_error(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "no filmgrain::Error thrown";
    return Error(ErrorCode::kOk, "");
}

}  // namespace

TEST(VfgsParameters, ValueCompletion) {
    EXPECT_EQ(complete_model_values({90, 0, 0, 0, 0, 0}, 1, 0, 5), (std::array<int, 6>{90, 8, 8, 0, 0, 0}));
    EXPECT_EQ(complete_model_values({90, 5, 0, 0, 0, 0}, 2, 0, 5), (std::array<int, 6>{90, 5, 5, 0, 0, 0}));
    EXPECT_EQ(complete_model_values({90, 5, 7, 0, 0, 0}, 3, 0, 5), (std::array<int, 6>{90, 5, 7, 0, 0, 0}));
    // Model 1: [4] (aspect) defaults to 1 << log2_scale_factor, everything else to 0.
    EXPECT_EQ(complete_model_values({150, 0, 0, 0, 0, 0}, 1, 1, 5), (std::array<int, 6>{150, 0, 0, 0, 32, 0}));
    EXPECT_EQ(complete_model_values({150, 12, 0, -6, 0, 0}, 4, 1, 6), (std::array<int, 6>{150, 12, 0, -6, 64, 0}));
    EXPECT_EQ(complete_model_values({1, 2, 3, 4, 5, 6}, 6, 1, 5), (std::array<int, 6>{1, 2, 3, 4, 5, 6}));
}

TEST(VfgsParameters, ChromaConversion420) {
    FgcParams p = base_params();
    p.comp[1].comp_model_present_flag = true;
    p.comp[1].num_model_values_minus1 = 2;
    p.comp[1].intervals.push_back({0, 255, {101, 3, 8, 0, 0, 0}});
    p.comp[2].comp_model_present_flag = true;
    p.comp[2].num_model_values_minus1 = 0;  // cut-offs inferred (8, 8) before doubling
    p.comp[2].intervals.push_back({0, 255, {60, 0, 0, 0, 0, 0}});
    const ResolvedParams r = resolve_params(p, ChromaFormat::k420, 100);
    EXPECT_EQ(r.comp[0].intervals[0].value, (std::array<int, 6>{100, 8, 8, 0, 0, 0}));  // luma untouched
    EXPECT_EQ(r.comp[1].intervals[0].value, (std::array<int, 6>{50, 6, 14, 0, 0, 0}));  // 2h, clip(16) = 14, >> 1
    EXPECT_EQ(r.comp[2].intervals[0].value, (std::array<int, 6>{30, 14, 14, 0, 0, 0}));
}

TEST(VfgsParameters, Gain) {
    int L = 5;
    EXPECT_EQ(reduce_gain(150, L), 75);
    EXPECT_EQ(L, 4);
    L = 5;
    EXPECT_EQ(reduce_gain(450, L), 56);  // 225, 112, 56
    EXPECT_EQ(L, 2);
    L = 5;
    EXPECT_EQ(reduce_gain(30, L), 60);
    EXPECT_EQ(L, 6);
    L = 5;
    EXPECT_EQ(reduce_gain(0, L), 0);
    EXPECT_EQ(L, 5);

    FgcParams p = base_params();
    p.comp[0].intervals[0].comp_model_value[0] = 201;
    const ResolvedParams r = resolve_params(p, ChromaFormat::k420, 150);
    EXPECT_EQ(r.log2_scale_factor, 4);
    EXPECT_EQ(r.signalled_log2_scale_factor, 5);
    EXPECT_EQ(r.comp[0].intervals[0].value[0], 201 * 75 / 100);  // 150
    EXPECT_EQ(scale_shift(r, 8), 4 + 6);
    EXPECT_EQ(scale_shift(r, 10), 4 + 6 - 2);
}

TEST(VfgsParameters, LutsScaleHolesAndTemplates) {
    FgcParams p = base_params();
    p.comp[0].intervals = {{10, 19, {30, 4, 4, 0, 0, 0}}, {40, 49, {60, 10, 10, 0, 0, 0}}};
    p.comp[0].num_model_values_minus1 = 2;
    const ResolvedParams r = resolve_params(p, ChromaFormat::k420, 100);
    const auto luts = build_luts(r, select_template_pools(r));
    EXPECT_EQ(luts[0].scale[9], 0);
    EXPECT_EQ(luts[0].scale[10], 30);
    EXPECT_EQ(luts[0].scale[19], 30);
    EXPECT_EQ(luts[0].scale[20], 0);
    EXPECT_EQ(luts[0].scale[45], 60);
    EXPECT_EQ(luts[0].tmpl[0], 0);    // below the first interval: index 0
    EXPECT_EQ(luts[0].tmpl[30], 0);   // hole: template of the nearest lower intensity
    EXPECT_EQ(luts[0].tmpl[40], 1);
    EXPECT_EQ(luts[0].tmpl[255], 1);  // the hole above the last interval too
    // Absent chroma: no grain, template 0.
    EXPECT_EQ(luts[1].scale[100], 0);
    EXPECT_EQ(luts[2].tmpl[100], 0);
}

TEST(VfgsParameters, CrStartsFromCbScale) {
    // VFGS fills Cb and then Cr in one scale buffer: where Cr has no interval it
    // keeps Cb's scale (no golden exercises this; mirrored for exactness).
    FgcParams p = base_params();
    p.comp[1].comp_model_present_flag = true;
    p.comp[1].num_model_values_minus1 = 2;
    p.comp[1].intervals = {{0, 255, {80, 4, 4, 0, 0, 0}}};
    p.comp[2].comp_model_present_flag = true;
    p.comp[2].num_model_values_minus1 = 2;
    p.comp[2].intervals = {{100, 199, {120, 4, 4, 0, 0, 0}}};
    const ResolvedParams r = resolve_params(p, ChromaFormat::k420, 100);
    const auto luts = build_luts(r, select_template_pools(r));
    EXPECT_EQ(luts[1].scale[50], 40);
    EXPECT_EQ(luts[2].scale[150], 60);
    EXPECT_EQ(luts[2].scale[50], 40);
}

TEST(VfgsParameters, ValidationMessagesNameFieldValueAndRange) {
    {
        FgcParams p = base_params();
        p.film_grain_model_id = 2;
        const Error e = expect_error([&] { validate_params(p, 100); });
        EXPECT_EQ(e.code(), ErrorCode::kUnsupported);
        EXPECT_NE(std::string(e.what()).find("film_grain_model_id = 2 is out of range (allowed 0..1)"), std::string::npos)
            << e.what();
    }
    {
        FgcParams p = base_params();
        p.comp[0].intervals[0].comp_model_value[1] = 1;
        const Error e = expect_error([&] { validate_params(p, 100); });
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
        EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][1] = 1 is out of range (allowed 2..14)"),
                  std::string::npos)
            << e.what();
    }
    {
        FgcParams p = base_params();
        p.log2_scale_factor = 1;
        const Error e = expect_error([&] { validate_params(p, 100); });
        EXPECT_NE(std::string(e.what()).find("log2_scale_factor = 1 is out of range (allowed 2..7)"), std::string::npos)
            << e.what();
        // Model 1 allows 3..8, checked after --gain.
        FgcParams q = base_params(1);
        q.log2_scale_factor = 3;
        EXPECT_NO_THROW(validate_params(q, 100));
        const Error e2 = expect_error([&] { validate_params(q, 150); });
        EXPECT_NE(std::string(e2.what()).find("after --gain 150 changed it to 2"), std::string::npos) << e2.what();
    }
    {
        FgcParams p = base_params();
        p.comp[0].intervals[0].intensity_interval_lower_bound = 100;
        p.comp[0].intervals[0].intensity_interval_upper_bound = 50;
        const Error e = expect_error([&] { validate_params(p, 100); });
        EXPECT_NE(std::string(e.what()).find("intensity_interval_upper_bound[0][0] = 50 is out of range (allowed 100..255)"),
                  std::string::npos)
            << e.what();
    }
    {
        FgcParams p = base_params();
        p.blending_mode_id = 1;
        EXPECT_EQ(expect_error([&] { validate_params(p, 100); }).code(), ErrorCode::kUnsupported);
    }
    {
        FgcParams p = base_params(1);
        p.comp[1].comp_model_present_flag = true;
        p.comp[1].intervals.push_back({0, 255, {10, 0, 0, 0, 0, 0}});
        EXPECT_EQ(expect_error([&] { validate_params(p, 100); }).code(), ErrorCode::kUnsupported);
    }
    {
        // Chroma grain outside 4:2:0, scales above 255, AR weights out of +-2^(bd-1).
        FgcParams p = base_params();
        p.comp[2].comp_model_present_flag = true;
        p.comp[2].intervals.push_back({0, 255, {10, 8, 8, 0, 0, 0}});
        EXPECT_NO_THROW(validate_params_for_format(p, ChromaFormat::k420, 8));
        EXPECT_EQ(expect_error([&] { validate_params_for_format(p, ChromaFormat::k422, 8); }).code(),
                  ErrorCode::kUnsupported);
        FgcParams q = base_params();
        q.comp[0].intervals[0].comp_model_value[0] = 256;
        const Error e8 = expect_error([&] { validate_params_for_format(q, ChromaFormat::k420, 8); });
        EXPECT_EQ(e8.code(), ErrorCode::kInvalidParams);
        EXPECT_NE(std::string(e8.what()).find("comp_model_value[0][0][0] = 256 is out of range (allowed 0..255)"),
                  std::string::npos);
        EXPECT_EQ(expect_error([&] { validate_params_for_format(q, ChromaFormat::k420, 10); }).code(),
                  ErrorCode::kUnsupported);
        FgcParams a = base_params(1);
        a.comp[0].num_model_values_minus1 = 1;
        a.comp[0].intervals[0].comp_model_value = {100, -129, 0, 0, 0, 0};
        const Error ea = expect_error([&] { validate_params_for_format(a, ChromaFormat::k420, 8); });
        EXPECT_NE(std::string(ea.what()).find("comp_model_value[0][0][1] = -129 is out of range (allowed -128..127)"),
                  std::string::npos)
            << ea.what();
        EXPECT_NO_THROW(validate_params_for_format(a, ChromaFormat::k420, 10));
    }
}

TEST(VfgsParameters, InterpolationRamps) {
    FgcParams p = base_params();
    p.comp[0].intervals = {{0, 99, {60, 2, 2, 0, 0, 0}}, {100, 255, {60, 14, 14, 0, 0, 0}}};
    const ResolvedParams r = resolve_params(p, ChromaFormat::k420, 100);
    auto luts = build_luts(r, select_template_pools(r));
    add_interpolation_ramps(r, luts);
    EXPECT_EQ(luts[0].frac[91], 0);
    EXPECT_EQ(luts[0].frac[92], 0);   // ramp start: weight 0.5/16 rounds to 0
    EXPECT_EQ(luts[0].frac[100], 8);  // half way at the boundary
    EXPECT_EQ(luts[0].frac[107], 15);
    EXPECT_EQ(luts[0].frac[108], 0);  // past the ramp: the new template alone
    EXPECT_EQ(luts[0].tmpl[99], 0);
    EXPECT_EQ(luts[0].tmpl_next[99], 1);
    EXPECT_EQ(luts[0].tmpl[108], 1);
    for (int i = 92; i < 107; ++i) EXPECT_LE(luts[0].frac[i], luts[0].frac[i + 1]);
}

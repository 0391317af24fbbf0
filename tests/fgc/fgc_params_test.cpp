// FGC parameters: SEI payload syntax, JSON form, and validation/resolution per flavour.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "error_message.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/error.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/fgc_sei.hpp"

using namespace filmgrain;
using namespace filmgrain::fgc;

namespace {

using filmgrain::test_support::error_of;
FgcParams simple(int nmv = 3) {
    FgcParams p;
    p.log2_scale_factor = 4;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = nmv - 1;
        p.comp[c].intervals = {{0, 100, {60, 4, 6}}, {101, 255, {90, 7, 5}}};
    }
    return p;
}

FgcParams random_params(std::mt19937& rng, FgcCodec codec) {
    FgcParams p;
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    p.film_grain_characteristics_cancel_flag = r(0, 9) == 0;
    if (p.film_grain_characteristics_cancel_flag) return p;
    p.film_grain_model_id = r(0, 1);
    p.separate_colour_description_present_flag = r(0, 3) == 0;
    if (p.separate_colour_description_present_flag) {
        p.film_grain_bit_depth_luma_minus8 = r(0, 7);
        p.film_grain_bit_depth_chroma_minus8 = r(0, 7);
        p.film_grain_full_range_flag = r(0, 1);
        p.film_grain_colour_primaries = r(0, 255);
        p.film_grain_transfer_characteristics = r(0, 255);
        p.film_grain_matrix_coeffs = r(0, 255);
    }
    p.blending_mode_id = r(0, 1);
    p.log2_scale_factor = r(0, 15);
    for (int c = 0; c < 3; c++) {
        auto& m = p.comp[c];
        m.comp_model_present_flag = r(0, 1);
        if (!m.comp_model_present_flag) continue;
        m.num_model_values_minus1 = r(0, 5);
        m.intervals.resize(r(1, 8));
        // values up to +-5000 within what the SEI lets each one carry (the picture bit depth
        // unknown: 16 bits unless the SEI signals its own)
        const int bd = film_grain_bit_depth(p, c, 0);
        for (auto& iv : m.intervals) {
            iv.intensity_interval_lower_bound = r(0, 255);
            iv.intensity_interval_upper_bound = r(0, 255);
            for (int j = 0; j <= m.num_model_values_minus1; j++) {
                const ValueRange range = comp_model_value_range(p.film_grain_model_id, j, bd);
                iv.comp_model_value[j] = r(int(std::max<long long>(range.lo, -5000)), int(std::min<long long>(range.hi, 5000)));
            }
        }
    }
    if (codec == FgcCodec::kAvc) {
        p.film_grain_characteristics_repetition_period = r(0, 16384);
        p.film_grain_characteristics_persistence_flag = p.film_grain_characteristics_repetition_period != 0;
    } else {
        p.film_grain_characteristics_persistence_flag = r(0, 1);
        p.film_grain_characteristics_repetition_period = p.film_grain_characteristics_persistence_flag;
    }
    return p;
}
}  // namespace

TEST(FgcSei, RandomRoundTripsThroughPayloadAndJson) {
    std::mt19937 rng(2024);
    for (FgcCodec codec : {FgcCodec::kAvc, FgcCodec::kHevc, FgcCodec::kVvc})
        for (int i = 0; i < 300; i++) {
            const FgcParams p = random_params(rng, codec);
            const auto bytes = write_fgc_sei_payload(p, codec);
            const FgcParams back = parse_fgc_sei_payload(bytes, codec);
            EXPECT_EQ(fgc_params_to_json(back), fgc_params_to_json(p));
            EXPECT_EQ(fgc_params_to_json(fgc_params_from_json(fgc_params_to_json(p))), fgc_params_to_json(p));
        }
}

TEST(FgcSei, RandomSetsPassTheSyntaxCheck) {
    std::mt19937 rng(99);
    for (int i = 0; i < 300; i++) EXPECT_NO_THROW(check_fgc_syntax_ranges(random_params(rng, FgcCodec::kHevc)));
}

TEST(FgcSei, EveryTruncationIsAnErrorNamingAField) {
    std::mt19937 rng(7);
    for (int i = 0; i < 50; i++) {
        FgcParams p = random_params(rng, FgcCodec::kHevc);
        if (p.film_grain_characteristics_cancel_flag) continue;
        const auto bytes = write_fgc_sei_payload(p, FgcCodec::kHevc);
        for (std::size_t n = 0; n < bytes.size(); n++) {
            const std::string msg = error_of([&] { parse_fgc_sei_payload(bytes.data(), n, FgcCodec::kHevc); });
            EXPECT_NE(msg.find("truncated while reading"), std::string::npos) << n << ": " << msg;
        }
    }
}

TEST(FgcSei, WrongCodecVariantIsDetected) {
    FgcParams p = simple();
    p.film_grain_characteristics_repetition_period = 300;
    const auto avc = write_fgc_sei_payload(p, FgcCodec::kAvc);
    EXPECT_NE(error_of([&] { parse_fgc_sei_payload(avc, FgcCodec::kHevc); }).find("unexpected bits"), std::string::npos);
    EXPECT_EQ(error_of([] { parse_fgc_codec("mpeg2"); }).find("allowed avc, hevc, vvc") != std::string::npos, true);
}

TEST(FgcResolve, DefaultsAreInferredFromFewerModelValues) {
    PictureFormat f{ChromaFormat::k444, 8, 352, 288};
    FgcParams one = simple(1);
    auto r1 = resolve_fgc_params(one, FgcFlavour::kRdd5, f);
    EXPECT_EQ(r1.comp[0].intervals[0].cutoff_h, 8);
    EXPECT_EQ(r1.comp[0].intervals[0].cutoff_v, 8);
    auto r2 = resolve_fgc_params(simple(2), FgcFlavour::kRdd5, f);
    EXPECT_EQ(r2.comp[0].intervals[0].cutoff_h, 4);
    EXPECT_EQ(r2.comp[0].intervals[0].cutoff_v, 4);
    EXPECT_EQ(r2.comp[0].interval_of_intensity[100], 0);
    EXPECT_EQ(r2.comp[0].interval_of_intensity[101], 1);
}

TEST(FgcResolve, ChromaConversionOfTheReferences) {
    FgcParams p = simple();
    auto r420 = resolve_fgc_params(p, FgcFlavour::kVtm, {ChromaFormat::k420, 8, 352, 288});
    EXPECT_EQ(r420.comp[0].intervals[0].scale, 60);
    EXPECT_EQ(r420.comp[1].intervals[0].scale, 30);
    EXPECT_EQ(r420.comp[1].intervals[0].cutoff_h, 8);
    EXPECT_EQ(r420.comp[1].intervals[0].cutoff_v, 12);
    EXPECT_EQ(r420.comp[1].intervals[1].cutoff_h, 14);  // 7 << 1 clipped
    auto r422 = resolve_fgc_params(p, FgcFlavour::kVtm, {ChromaFormat::k422, 8, 352, 288});
    EXPECT_EQ(r422.comp[1].intervals[0].scale, (60 * 181) >> 8);
    EXPECT_EQ(r422.comp[1].intervals[0].cutoff_h, 8);
    EXPECT_EQ(r422.comp[1].intervals[0].cutoff_v, 6);
    auto r444 = resolve_fgc_params(p, FgcFlavour::kVtm, {ChromaFormat::k444, 8, 352, 288});
    EXPECT_EQ(r444.comp[2].intervals[1].scale, 90);
    EXPECT_EQ(r444.comp[2].intervals[1].cutoff_h, 7);
    auto r400 = resolve_fgc_params(p, FgcFlavour::kVtm, {ChromaFormat::k400, 8, 352, 288});
    EXPECT_FALSE(r400.comp[1].present);
}

TEST(FgcResolve, InvalidSetsNameElementValueAndRange) {
    PictureFormat f{ChromaFormat::k420, 8, 352, 288};
    auto expect = [&](FgcParams p, FgcFlavour fl, const char* what, PictureFormat fmt) {
        const std::string m = error_of([&] { resolve_fgc_params(p, fl, fmt); });
        EXPECT_NE(m.find(what), std::string::npos) << m;
        EXPECT_NE(m.find("allowed"), std::string::npos) << m;
    };
    FgcParams p = simple();
    p.log2_scale_factor = 8;
    expect(p, FgcFlavour::kVtm, "log2_scale_factor = 8", f);
    p = simple();
    p.film_grain_model_id = 1;
    expect(p, FgcFlavour::kRdd5, "film_grain_model_id = 1", f);
    p = simple();
    p.blending_mode_id = 1;
    expect(p, FgcFlavour::kVtm, "blending_mode_id = 1", f);
    p = simple();
    p.comp[0].intervals[0].comp_model_value[1] = 15;
    expect(p, FgcFlavour::kVtm, "comp_model_value[0][0][1] = 15", f);
    p = simple();
    p.comp[0].intervals[1].comp_model_value[0] = 256;
    expect(p, FgcFlavour::kRdd5, "comp_model_value[0][1][0] = 256", f);
    p.comp[0].intervals[1].comp_model_value[0] = 1020;  // fine at 10 bit
    EXPECT_NO_THROW(resolve_fgc_params(p, FgcFlavour::kRdd5, {ChromaFormat::k420, 10, 352, 288}));
    p = simple();
    p.comp[0].intervals[1].intensity_interval_lower_bound = 90;
    expect(p, FgcFlavour::kVtm, "overlaps", f);
    p = simple();
    p.comp[0].intervals.clear();
    for (int i = 0; i < 11; i++) p.comp[0].intervals.push_back({i * 20, i * 20 + 10, {50, 2 + i, 3}});
    expect(p, FgcFlavour::kVtm, "distinct (horizontal, vertical) cut-off pairs", f);
    expect(simple(), FgcFlavour::kVtm, "picture width = 100", {ChromaFormat::k420, 8, 100, 288});
    expect(simple(), FgcFlavour::kVtm, "picture height = 4328", {ChromaFormat::k420, 8, 352, 4328});
    EXPECT_NO_THROW(resolve_fgc_params(simple(), FgcFlavour::kRdd5, {ChromaFormat::k420, 8, 97, 61}));
}

TEST(FgcResolve, CancelNeedsNothingElse) {
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = true;
    p.log2_scale_factor = 99;
    EXPECT_TRUE(resolve_fgc_params(p, FgcFlavour::kVtm, {ChromaFormat::k420, 8, 352, 288}).cancelled);
}

TEST(FgcJson, BadValuesNameTheKey) {
    nlohmann::json j = fgc_params_to_json(simple());
    j["log2_scale_factor"] = "five";
    EXPECT_NE(error_of([&] { fgc_params_from_json(j); }).find("log2_scale_factor"), std::string::npos);
    j = fgc_params_to_json(simple());
    j["intensity_interval_upper_bound"][1][0] = 300;
    EXPECT_NE(error_of([&] { fgc_params_from_json(j); }).find("intensity_interval_upper_bound[1][0] = 300"),
              std::string::npos);
    j = fgc_params_to_json(simple());
    j["comp_model_value"][2].erase(1);
    EXPECT_NE(error_of([&] { fgc_params_from_json(j); }).find("comp_model_value[2]"), std::string::npos);
}

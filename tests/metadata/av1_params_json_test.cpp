// AV1 film grain parameters <-> JSON (case.json `params.av1` key names).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "filmgrain/error.hpp"
#include "metadata/av1_params_json.hpp"

using namespace filmgrain;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

json sample() {
    return json::parse(R"({
      "apply_grain": 1, "grain_seed": 1234, "update_grain": 1,
      "num_y_points": 2, "point_y_value": [10, 200], "point_y_scaling": [30, 60],
      "chroma_scaling_from_luma": 0,
      "num_cb_points": 1, "point_cb_value": [128], "point_cb_scaling": [40],
      "num_cr_points": 0, "point_cr_value": [], "point_cr_scaling": [],
      "grain_scaling_minus_8": 2, "ar_coeff_lag": 1,
      "ar_coeffs_y_plus_128": [120, 130, 140, 150],
      "ar_coeffs_cb_plus_128": [100, 110, 120, 130, 200],
      "ar_coeffs_cr_plus_128": [],
      "ar_coeff_shift_minus_6": 3, "grain_scale_shift": 1,
      "cb_mult": 130, "cb_luma_mult": 190, "cb_offset": 300,
      "cr_mult": null, "cr_luma_mult": null, "cr_offset": null,
      "overlap_flag": 1, "clip_to_restricted_range": 1})");
}

std::string error_of(const json& j) {
    try {
        av1_params_from_json(j);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedPayload);
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Av1ParamsJson, ReadsRawValues) {
    const auto p = av1_params_from_json(sample());
    EXPECT_EQ(p.grain_seed, 1234);
    EXPECT_EQ(p.num_y_points, 2);
    EXPECT_EQ(p.point_y_value[1], 200);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[3], 150);
    EXPECT_EQ(p.ar_coeffs_cb_plus_128[4], 200);
    EXPECT_EQ(p.ar_coeffs_cr_plus_128[0], 128);
    EXPECT_EQ(p.cb_offset, 300);
    EXPECT_EQ(p.cr_mult, 128);  // null -> default
    EXPECT_EQ(p.clip_to_restricted_range, 1);
}

TEST(Av1ParamsJson, RoundTrip) {
    EXPECT_EQ(av1_params_to_json(av1_params_from_json(sample())), sample());
    Av1FilmGrainParams off;
    EXPECT_EQ(av1_params_to_json(off), json({{"apply_grain", 0}}));
    EXPECT_EQ(av1_params_from_json(json({{"apply_grain", 0}})), off);
}

TEST(Av1ParamsJson, RoundTripsEveryConformanceFrame) {
    int frames = 0;
    for (const auto& d : fs::directory_iterator(fs::path(FILMGRAIN_SOURCE_DIR) / "conformance")) {
        if (d.path().filename().string().rfind("av1_", 0) != 0) continue;
        std::ifstream in(d.path() / "case.json");
        const json cj = json::parse(in);
        const auto all = av1_frame_params_from_json(cj);
        ASSERT_EQ(all.size(), cj.at("frames_info").size());
        for (std::size_t k = 0; k < all.size(); ++k) {
            const json& want = cj["frames_info"][k]["params"];
            EXPECT_EQ(av1_params_to_json(all[k].grain), want["av1"]) << d.path() << " frame " << k;
            ASSERT_TRUE(all[k].color.has_value());
            json facts;
            av1_color_info_to_json(*all[k].color, facts);
            for (const char* key : {"bit_depth", "mono_chrome", "subsampling_x", "subsampling_y", "matrix_coefficients"})
                EXPECT_EQ(facts[key], want[key]) << key;
            ++frames;
        }
    }
    EXPECT_GE(frames, 80);
}

TEST(Av1ParamsJson, PerFrameForms) {
    const json single = sample();
    ASSERT_EQ(av1_frame_params_from_json(single).size(), 1u);
    EXPECT_FALSE(av1_frame_params_from_json(single)[0].color.has_value());

    json wrapped = {{"av1", sample()}, {"bit_depth", 10}, {"mono_chrome", 0}, {"subsampling_x", 1},
                    {"subsampling_y", 0}, {"matrix_coefficients", 0}};
    const auto w = av1_frame_params_from_json(wrapped);
    ASSERT_EQ(w.size(), 1u);
    ASSERT_TRUE(w[0].color.has_value());
    EXPECT_EQ(w[0].color->bit_depth, 10);
    EXPECT_EQ(w[0].color->subsampling_y, 0);
    EXPECT_EQ(w[0].color->matrix_coefficients, 0);

    json frames = {{"frames", json::array({json{{"av1", sample()}}, json{{"av1", json{{"apply_grain", 0}}}},
                                           json{{"params", wrapped}}})}};
    const auto f = av1_frame_params_from_json(frames);
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f[0].grain.grain_seed, 1234);
    EXPECT_EQ(f[1].grain.apply_grain, 0);
    EXPECT_EQ(f[2].color->bit_depth, 10);
    // And back.
    EXPECT_EQ(av1_frame_params_from_json(av1_frame_params_to_json(f)), f);
}

TEST(Av1ParamsJson, Errors) {
    auto with = [](const char* key, json v) {
        json j = sample();
        j[key] = v;
        return j;
    };
    auto without = [](const char* key) {
        json j = sample();
        j.erase(key);
        return j;
    };
    EXPECT_NE(error_of(json::array()).find("must be a JSON object"), std::string::npos);
    EXPECT_NE(error_of(without("apply_grain")).find("missing key \"apply_grain\""), std::string::npos);
    EXPECT_NE(error_of(without("grain_seed")).find("missing key \"grain_seed\""), std::string::npos);
    EXPECT_NE(error_of(with("grain_seed", "12")).find("\"grain_seed\" must be an integer"), std::string::npos);
    EXPECT_NE(error_of(with("grain_seed", 1.5)).find("\"grain_seed\" must be an integer"), std::string::npos);
    EXPECT_NE(error_of(with("grain_seed", 1LL << 40)).find("\"grain_seed\" = 1099511627776 is out of range (allowed 0..65535)"), std::string::npos);
    EXPECT_NE(error_of(with("num_y_points", 15)).find("\"num_y_points\" = 15 is out of range (allowed 0..14)"),
              std::string::npos);
    EXPECT_NE(error_of(with("point_y_value", json::array({1, 2, 3}))).find("must have num_y_points = 2 entries"),
              std::string::npos);
    EXPECT_NE(error_of(with("point_y_value", json::array({1, "x"}))).find("\"point_y_value[1]\" must be an integer"),
              std::string::npos);
    EXPECT_NE(error_of(with("point_cb_value", 5)).find("\"point_cb_value\" must be an array"), std::string::npos);
    EXPECT_NE(error_of(with("point_cb_value", json(std::vector<int>(11, 1)))).find("at most 10 allowed"),
              std::string::npos);
    EXPECT_NE(error_of(with("ar_coeff_lag", 4)).find("\"ar_coeff_lag\" = 4 is out of range (allowed 0..3)"),
              std::string::npos);
    EXPECT_NE(error_of(with("ar_coeffs_y_plus_128", json::array({1, 2}))).find("has 2 entries, expected 4"),
              std::string::npos);
    EXPECT_NE(error_of(with("ar_coeffs_cb_plus_128", json::array({1, 2, 3, 4}))).find("has 4 entries, expected 5"),
              std::string::npos);
    EXPECT_NE(error_of(with("cb_mult", json::array())).find("\"cb_mult\" must be an integer"), std::string::npos);
    // Frame-list errors say which frame.
    json frames = {{"frames", json::array({json{{"av1", sample()}}, json{{"av1", json{{"apply_grain", "no"}}}}})}};
    try {
        av1_frame_params_from_json(frames);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("frames[1]"), std::string::npos) << e.what();
    }
    EXPECT_THROW(av1_frame_params_from_json(json::array()), Error);
    EXPECT_THROW(av1_frame_params_from_json(json{{"frames", json::array({3})}}), Error);
}

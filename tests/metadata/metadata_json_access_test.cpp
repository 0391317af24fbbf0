// metadata/json_access: the bounded JSON document parser and the checked integer reads
// every JSON form goes through.
#include "error_message.hpp"
#include "metadata/json_access.hpp"

#include <gtest/gtest.h>

#include <string>

#include "metadata/av1_params_json.hpp"

using namespace filmgrain;
using nlohmann::json;

namespace {

using filmgrain::test_support::error_of;

json parse(const std::string& s) {
    return parse_json_document(reinterpret_cast<const uint8_t*>(s.data()), s.size(), "doc");
}

}  // namespace

TEST(JsonDocument, NestingIsBoundedAtTheLimitExactly) {
    const auto nest = [](int d) { return std::string(std::size_t(d), '[') + std::string(std::size_t(d), ']'); };
    EXPECT_NO_THROW(parse(nest(kMaxJsonDepth)));
    EXPECT_EQ(error_of([&] { parse(nest(kMaxJsonDepth + 1)); }),
              "doc nests JSON objects/arrays deeper than 64 levels (allowed at most 64)");
    // the stack-overflow reproducer of issue 24 (100000 levels) fails fast, without recursion
    EXPECT_NE(error_of([&] { parse("{\"a\": " + nest(100000) + "}"); }).find("deeper than 64"), std::string::npos);
    std::string objects;
    for (int i = 0; i < 100; i++) objects += "{\"a\": ";
    objects += "1" + std::string(100, '}');
    EXPECT_NE(error_of([&] { parse(objects); }).find("deeper than 64"), std::string::npos);
}

TEST(JsonDocument, SizeIsBoundedAndSyntaxErrorsNameTheDocument) {
    const std::string big(kMaxJsonBytes + 1, ' ');
    EXPECT_EQ(error_of([&] { parse(big); }), "doc has 16777217 bytes (allowed at most 16777216 for a JSON document)");
    EXPECT_NE(error_of([] { parse("{\"a\": "); }).find("doc is not valid JSON"), std::string::npos);
}

TEST(JsonInteger, ValuesAreRangeCheckedWithoutWrapping) {
    EXPECT_EQ(json_to_integer(json(5), 0, 10, "v"), 5);
    EXPECT_EQ(json_to_integer(json(true), 0, 1, "v"), 1);
    EXPECT_EQ(json_to_integer(json(7.0), 0, 10, "v"), 7);
    EXPECT_EQ(json_to_integer(json(-3), -5, 5, "v"), -3);
    // 2^64 - 1 used to come out as -1, 2^32 + 5 as 5
    EXPECT_EQ(error_of([] { json_to_integer(json(18446744073709551615ull), -100, 100, "v"); }),
              "v = 18446744073709551615 is out of range (allowed -100..100)");
    EXPECT_EQ(error_of([] { json_to_integer(json(4294967301ll), 0, 255, "v"); }),
              "v = 4294967301 is out of range (allowed 0..255)");
    // a double beyond long long was converted first (undefined behaviour)
    EXPECT_EQ(error_of([] { json_to_integer(json(1e300), 0, 255, "v"); }), "v = 1e+300 is out of range (allowed 0..255)");
    EXPECT_EQ(error_of([] { json_to_integer(json(0.5), 0, 255, "v"); }), "v = 0.5 is not an integer");
    EXPECT_EQ(error_of([] { json_to_integer(json::array({1, 2}), 0, 255, "v"); }), "v = an array of 2 entries is not an integer");
    EXPECT_EQ(error_of([] { json_to_integer(json(std::string(100, 'x')), 0, 255, "v"); }),
              "v = \"" + std::string(40, 'x') + "\"... is not an integer");
}

TEST(JsonInteger, Av1ArraysAndFactsCarryOnlyTheirSyntaxRange) {
    json j = {{"apply_grain", 1},          {"grain_seed", 1},       {"num_y_points", 1},
              {"point_y_value", {0}},      {"point_y_scaling", {4294967301ll}},
              {"grain_scaling_minus_8", 0}, {"ar_coeff_lag", 0},    {"ar_coeff_shift_minus_6", 0},
              {"grain_scale_shift", 0},    {"overlap_flag", 0},     {"clip_to_restricted_range", 0}};
    EXPECT_EQ(error_of([&] { av1_params_from_json(j); }),
              "AV1 params JSON: \"point_y_scaling[0]\" = 4294967301 is out of range (allowed 0..255)");
    j["point_y_scaling"] = {255};
    EXPECT_NO_THROW(av1_params_from_json(j));
    j["grain_seed"] = 65536;
    EXPECT_EQ(error_of([&] { av1_params_from_json(j); }),
              "AV1 params JSON: \"grain_seed\" = 65536 is out of range (allowed 0..65535)");
    EXPECT_NE(error_of([] { av1_color_info_from_json(json{{"bit_depth", 9}}); }).find("allowed 8, 10, 12"), std::string::npos);
    EXPECT_NE(error_of([] { av1_color_info_from_json(json{{"subsampling_x", 0}, {"subsampling_y", 1}}); })
                  .find("subsampling_y"),
              std::string::npos);
    EXPECT_NE(error_of([] { av1_color_info_from_json(json{{"matrix_coefficients", -1}}); }).find("allowed 0..255"),
              std::string::npos);
}

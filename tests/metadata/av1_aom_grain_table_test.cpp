// libaom filmgrn1 grain table reader/writer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "filmgrain/error.hpp"
#include "metadata/aom_grain_table.hpp"

using namespace filmgrain;
namespace fs = std::filesystem;

namespace {

const char* kTable =
    "filmgrn1\n"
    "E 0 400000 1 22463 1\n"
    "\tp 3 8 2 9 1 1 0 0 0 0 0 0\n"
    "\tsY 2  27 108 68 0\n"
    "\tsCb 0\n"
    "\tsCr 1 16 40\n"
    "\tcY 36 8 -32 -23 -28 14 38 1 -16 -31 34 -8 -36 -7 26 -16 15 -19 -16 20 -6 -32 19 -25\n"
    "\tcCb -28 35 -6 -24 9 35 -28 -12 34 -10 -19 -3 -23 9 -27 -24 3 12 2 40 2 30 -10 -38 37\n"
    "\tcCr -5 8 -23 32 -6 -19 24 -8 -13 30 -24 14 29 -16 -24 -24 -11 -8 -37 38 -26 14 27 13 -36\n"
    "E 400000 800000 1 29225 0\n"
    "E 800000 1200000 0 5 1\n"
    "\tp 0 6 0 8 0 0 128 192 256 128 192 256\n"
    "\tsY 0 \n"
    "\tsCb 0\n"
    "\tsCr 0\n"
    "\tcY\n"
    "\tcCb 0\n"
    "\tcCr 0\n";

std::string error_of(const std::string& text) {
    try {
        parse_aom_grain_table(text);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedPayload) << e.what();
        return e.what();
    }
    return "";
}

// Replaces the first occurrence of `from` in kTable.
std::string mutate(const std::string& from, const std::string& to) {
    std::string s = kTable;
    const auto pos = s.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return s.replace(pos, from.size(), to);
}

}  // namespace

TEST(Av1AomGrainTable, ParsesFields) {
    const AomGrainTable t = parse_aom_grain_table(kTable);
    ASSERT_EQ(t.entries.size(), 3u);
    const auto& e = t.entries[0];
    EXPECT_EQ(e.start_time, 0);
    EXPECT_EQ(e.end_time, 400000);
    const auto& p = e.params;
    EXPECT_EQ(p.apply_grain, 1);
    EXPECT_EQ(p.grain_seed, 22463);
    EXPECT_EQ(p.update_grain, 1);
    EXPECT_EQ(p.ar_coeff_lag, 3);
    EXPECT_EQ(p.ar_coeff_shift_minus_6, 2);
    EXPECT_EQ(p.grain_scale_shift, 2);
    EXPECT_EQ(p.grain_scaling_minus_8, 1);
    EXPECT_EQ(p.chroma_scaling_from_luma, 1);
    EXPECT_EQ(p.overlap_flag, 1);
    EXPECT_EQ(p.num_y_points, 2);
    EXPECT_EQ(p.point_y_value[1], 68);
    EXPECT_EQ(p.point_y_scaling[0], 108);
    EXPECT_EQ(p.num_cr_points, 1);
    EXPECT_EQ(p.point_cr_value[0], 16);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[0], 36 + 128);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[23], -25 + 128);
    EXPECT_EQ(p.ar_coeffs_cb_plus_128[24], 37 + 128);
    EXPECT_EQ(p.ar_coeffs_cr_plus_128[0], -5 + 128);
    EXPECT_EQ(p.clip_to_restricted_range, 0);
    EXPECT_EQ(t.entries[1].params.update_grain, 0);
    EXPECT_EQ(t.entries[2].params.apply_grain, 0);
    EXPECT_EQ(t.entries[2].params.cb_luma_mult, 192);
}

TEST(Av1AomGrainTable, FindByTimestamp) {
    const AomGrainTable t = parse_aom_grain_table(kTable);
    EXPECT_EQ(t.find(0), &t.entries[0]);
    EXPECT_EQ(t.find(399999), &t.entries[0]);
    EXPECT_EQ(t.find(400000), &t.entries[1]);
    EXPECT_EQ(t.find(1199999), &t.entries[2]);
    EXPECT_EQ(t.find(1200000), nullptr);
    EXPECT_EQ(t.find(-1), nullptr);
    EXPECT_EQ(t.find_index(800000), std::optional<std::size_t>(2));
}

TEST(Av1AomGrainTable, ResolvesUpdateZero) {
    const AomGrainTable t = parse_aom_grain_table(kTable);
    const auto r = t.resolved_params(1);
    EXPECT_EQ(r.grain_seed, 29225);
    EXPECT_EQ(r.update_grain, 1);
    EXPECT_EQ(r.num_y_points, 2);
    EXPECT_EQ(r.ar_coeff_lag, 3);
    EXPECT_EQ(t.resolved_params(0), t.entries[0].params);
    EXPECT_THROW(t.resolved_params(3), Error);
    const AomGrainTable lone = parse_aom_grain_table("filmgrn1\nE 0 10 1 3 0\n");
    EXPECT_THROW(lone.resolved_params(0), Error);
}

TEST(Av1AomGrainTable, RoundTripIsByteExact) {
    EXPECT_EQ(format_aom_grain_table(parse_aom_grain_table(kTable)), kTable);
    int files = 0;
    for (const auto& d : fs::directory_iterator(fs::path(FILMGRAIN_SOURCE_DIR) / "conformance")) {
        const fs::path tbl = d.path() / "grain.tbl";
        if (d.path().filename().string().rfind("av1_", 0) != 0 || !fs::exists(tbl)) continue;
        std::ifstream in(tbl, std::ios::binary);
        std::stringstream ss;
        ss << in.rdbuf();
        const AomGrainTable t = read_aom_grain_table(tbl.string());
        EXPECT_EQ(format_aom_grain_table(t), ss.str()) << tbl;
        ++files;
    }
    EXPECT_GE(files, 28);
}

TEST(Av1AomGrainTable, WriteAndReadFile) {
    const AomGrainTable t = parse_aom_grain_table(kTable);
    const fs::path path = fs::temp_directory_path() / ("av1_table_test_" + std::to_string(::getpid()) + ".tbl");
    write_aom_grain_table(t, path.string());
    EXPECT_EQ(read_aom_grain_table(path.string()).entries, t.entries);
    fs::remove(path);
    try {
        read_aom_grain_table((fs::temp_directory_path() / "does-not-exist.tbl").string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kIo);
    }
}

TEST(Av1AomGrainTable, ToleratesCrLfAndEmptyTable) {
    std::string crlf;
    for (char c : std::string(kTable)) {
        if (c == '\n') crlf += '\r';
        crlf += c;
    }
    EXPECT_EQ(parse_aom_grain_table(crlf).entries, parse_aom_grain_table(kTable).entries);
    EXPECT_TRUE(parse_aom_grain_table("filmgrn1\n").entries.empty());
}

TEST(Av1AomGrainTable, MalformedInputsNameLineAndField) {
    struct Case {
        std::string text, expected;
    };
    const std::vector<Case> cases = {
        {"", "line 1: missing 'filmgrn1' file magic"},
        {"filmgrn2\n", "line 1: missing 'filmgrn1' file magic"},
        {"filmgrn1 x\n", "line 1: unexpected text after 'filmgrn1'"},
        {"filmgrn1\nX 0 1 1 1 0\n", "line 2: expected 'E' line, got 'X'"},
        {"filmgrn1\nE 0 1 1 1\n", "line 2: 'E' line ends before update_parameters"},
        {"filmgrn1\nE 0 1 1 1 0 7\n", "line 2: unexpected extra value '7' on 'E' line"},
        {"filmgrn1\nE zero 1 1 1 0\n", "line 2: start_time = 'zero' is not an integer"},
        {"filmgrn1\nE 0 99999999999999999999 1 1 0\n", "line 2: end_time = '99999999999999999999' is not an integer"},
        {"filmgrn1\nE 0 1 2 1 0\n", "line 2: apply_grain = 2 is out of range (allowed 0..1)"},
        {"filmgrn1\nE 0 1 1 65536 0\n", "line 2: random_seed = 65536 is out of range (allowed 0..65535)"},
        {"filmgrn1\nE 0 1 1 5 2\n", "line 2: update_parameters = 2 is out of range (allowed 0..1)"},
        {"filmgrn1\nE 0 1 1 1 1\n", "line 3: expected 'p' line, got end of file"},
        {mutate("\tp 3 8", "\tp 4 8"), "line 3: ar_coeff_lag = 4 is out of range (allowed 0..3)"},
        {mutate("\tp 3 8", "\tp 3 5"), "line 3: ar_coeff_shift = 5 is out of range (allowed 6..9)"},
        {mutate("3 8 2 9", "3 8 4 9"), "line 3: grain_scale_shift = 4 is out of range (allowed 0..3)"},
        {mutate("3 8 2 9", "3 8 2 12"), "line 3: scaling_shift = 12 is out of range (allowed 8..11)"},
        {mutate("2 9 1 1 0 0 0", "2 9 1 1 256 0 0"), "line 3: cb_mult = 256 is out of range (allowed 0..255)"},
        {mutate("0 0 0 0 0 0\n\tsY", "0 0 512 0 0 0\n\tsY"), "line 3: cb_offset = 512 is out of range (allowed 0..511)"},
        {mutate("0 0 0 0 0 0\n\tsY", "0 0 0 0 0 -1\n\tsY"), "line 3: cr_offset = -1 is out of range (allowed 0..511)"},
        {mutate("2 9 1 1 0 0 0 0 0 0", "2 9 1 1 0 0 0 0 0"), "line 3: 'p' line ends before cr_offset"},
        {mutate("\tsY 2 ", "\tsY 15 "), "line 4: num_y_points = 15 is out of range (allowed 0..14)"},
        {mutate("\tsY 2  27 108 68 0", "\tsY 2  27 108 68"), "line 4: 'sY' line ends before point_y_scaling[1]"},
        {mutate("\tsY 2  27 108", "\tsY 2  27 300"), "line 4: point_y_scaling[0] = 300 is out of range"},
        {mutate("\tsY 2  27 108 68 0", "\tsY 2  27 108 68 0 1"), "line 4: unexpected extra value '1' on 'sY' line"},
        {mutate("\tsCb 0", "\tsCb 11"), "line 5: num_cb_points = 11 is out of range (allowed 0..10)"},
        {mutate("\tsCr 1 16 40", "\tsCr 1 256 40"), "line 6: point_cr_value[0] = 256 is out of range (allowed 0..255)"},
        {mutate("\tsCb 0\n", ""), "line 5: expected 'sCb' line, got 'sCr'"},
        {mutate("\tcY 36", "\tcY 128"), "line 7: ar_coeffs_y[0] = 128 is out of range (allowed -128..127)"},
        {mutate(" 19 -25\n", " 19\n"), "line 7: 'cY' line ends before ar_coeffs_y[23]"},
        {mutate("-38 37\n", "-38\n"), "line 8: 'cCb' line ends before ar_coeffs_cb[24]"},
        {mutate("13 -36\n", "13 -36 5\n"), "line 9: unexpected extra value '5' on 'cCr' line"},
        {mutate("\tcCr -5", "\tcCx -5"), "line 9: expected 'cCr' line, got 'cCx'"},
        {mutate("E 400000 800000 1 29225 0", "E 400000 800000 1 29225 1"), "line 11: expected 'p' line, got 'E'"},
        {std::string(kTable) + "junk\n", "line 19: expected 'E' line, got 'junk'"},
        {mutate("\tcCb 0\n\tcCr 0\n", "\tcCb 0\n"), "line 18: expected 'cCr' line, got end of file"},
    };
    for (const auto& c : cases) {
        const std::string msg = error_of(c.text);
        EXPECT_NE(msg.find(c.expected), std::string::npos) << "got: '" << msg << "'\nexpected: '" << c.expected << "'";
    }
}

TEST(Av1AomGrainTable, RandomCorruptionNeverCrashes) {
    std::mt19937 rng(12345);
    const std::string base = kTable;
    const char alphabet[] = "0123456789- \t\nEpsYCbrcfilmgrn+x";
    int parsed = 0, rejected = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        std::string s = base;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const std::size_t pos = rng() % (s.size() + 1);
            switch (rng() % 3) {
                case 0:
                    if (pos < s.size()) s.erase(pos, 1 + rng() % 8);
                    break;
                case 1:
                    s.insert(pos, 1, alphabet[rng() % (sizeof(alphabet) - 1)]);
                    break;
                default:
                    if (pos < s.size()) s[pos] = alphabet[rng() % (sizeof(alphabet) - 1)];
            }
        }
        try {
            const AomGrainTable t = parse_aom_grain_table(s);
            ++parsed;
            // Anything accepted must format and re-parse to the same entries.
            EXPECT_EQ(parse_aom_grain_table(format_aom_grain_table(t)).entries, t.entries);
        } catch (const Error& e) {
            ++rejected;
            EXPECT_EQ(e.code(), ErrorCode::kMalformedPayload);
        }
    }
    EXPECT_GT(rejected, 0);
    EXPECT_GT(parsed, 0);
}

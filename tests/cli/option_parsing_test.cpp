// tools/option_parsing: the tool's option values are parsed whole and range-checked.
#include "error_message.hpp"
#include "option_parsing.hpp"

#include <gtest/gtest.h>

#include "filmgrain/error.hpp"

using namespace filmgrain::cli;
using filmgrain::Error;

namespace {

using filmgrain::test_support::error_of;

}  // namespace

TEST(OptionParsing, DecimalNumbersAreWholeAndInRange) {
    EXPECT_EQ(parse_decimal("0", 0, 5, "n"), 0);
    EXPECT_EQ(parse_decimal("00042", 0, 100, "n"), 42);
    EXPECT_EQ(error_of([] { parse_decimal("4294967312", 1, 65536, "W"); }), "W = 4294967312 is out of range (allowed 1..65536)");
    EXPECT_EQ(error_of([] { parse_decimal("99999999999999999999999999", 0, 10, "n"); }),
              "n = 99999999999999999999999999 is out of range (allowed 0..10)");
    for (const char* bad : {"", "-1", "+1", " 1", "1 ", "1e3", "0x10", "1.0"})
        EXPECT_NE(error_of([&] { parse_decimal(bad, 0, 1000, "n"); }).find("is not a whole number"), std::string::npos) << bad;
}

TEST(OptionParsing, PictureSizes) {
    const PictureSize s = parse_picture_size("1920x1080", "--size");
    EXPECT_EQ(s.width, 1920);
    EXPECT_EQ(s.height, 1080);
    EXPECT_EQ(parse_picture_size("65536X1", "--size").width, 65536);
    for (const char* bad : {"16x16x16", "16x", "x16", "16", "16 x16", "-16x16", "0x16", "65537x16", "16x16 "})
        EXPECT_NE(error_of([&] { parse_picture_size(bad, "--size"); }).find("--size"), std::string::npos) << bad;
}

TEST(OptionParsing, FrameRates) {
    EXPECT_EQ(parse_frame_rate("25", "--fps").num, 25);
    EXPECT_EQ(parse_frame_rate("25", "--fps").den, 1);
    EXPECT_EQ(parse_frame_rate("30000/1001", "--fps").den, 1001);
    for (const char* bad : {"1e9", "25/", "/1", "25/0", "0", "2000000", "25.0", "25/1/1", "-25"})
        EXPECT_NE(error_of([&] { parse_frame_rate(bad, "--fps"); }).find("--fps"), std::string::npos) << bad;
}

TEST(OptionParsing, Regions) {
    const Region r = parse_region("1,2,3,4", "--roi");
    EXPECT_EQ(r.x + r.y + r.w + r.h, 10);
    for (const char* bad : {"1,2,3", "1,2,3,4,", "1,2,3,4,5", ",1,2,3", "1,2,0,4", "2147483647,0,1,1", "a,b,c,d"})
        EXPECT_NE(error_of([&] { parse_region(bad, "--roi"); }).find("--roi"), std::string::npos) << bad;
}

TEST(OptionParsing, FilePatternsAndPlainNames) {
    auto p = FilePattern::parse("frame%d.bin");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->name_for(7), "frame7.bin");
    p = FilePattern::parse("dir/f%04d.sei");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->name_for(12), "dir/f0012.sei");
    EXPECT_EQ(p->name_for(123456), "dir/f123456.sei");
    p = FilePattern::parse("100%%/a%u.bin");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->name_for(3), "100%/a3.bin");
    // not patterns: plain files, never formats
    // the width has one or two digits (found by the fuzzer: %96u pads to 96 characters)
    p = FilePattern::parse("a%96u");
    ASSERT_TRUE(p);
    EXPECT_EQ(p->name_for(5), "a" + std::string(95, ' ') + "5");
    for (const char* plain : {"x%n.bin", "strength100%.fgc.bin", "a%s.bin", "a%d%d.bin", "plain.bin", "%", "a%-5d",
                              "a%100d", "a%0123d"})
        EXPECT_FALSE(FilePattern::parse(plain)) << plain;
}

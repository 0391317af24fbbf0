// The reports of `filmgrain verify` from a result built by hand (one bit-exact picture, one
// mismatching with its comparison and hypotheses, one missing): the CI summary line, the text
// report, the JSON a tool reads, the HTML page and the heat map, read back as a viewer would.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "../report/png_read_back.hpp"
#include "error_message.hpp"
#include "filmgrain/error.hpp"
#include "verify/verification_report.hpp"

using namespace filmgrain;
using namespace filmgrain::verify;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 1000, kHeight = 64;  // wider than 960: shown at half size

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("filmgrain-verify-report-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A plane's comparison on the block grid compare_pictures makes; `blocks`: (bx, by, count).
PlaneComparison plane_comparison(int width, int height, int block, std::vector<std::array<int, 3>> blocks) {
    PlaneComparison c;
    c.samples = int64_t(width) * height;
    c.block_width = c.block_height = block;
    c.blocks_x = (width + block - 1) / block;
    c.blocks_y = (height + block - 1) / block;
    c.differing_per_block.assign(std::size_t(c.blocks_x * c.blocks_y), 0);
    for (const auto& [bx, by, count] : blocks) {
        c.differing_per_block[std::size_t(by * c.blocks_x + bx)] = count;
        c.differing += count;
        c.max_abs_difference = 4;
    }
    if (c.differing) c.first = FirstDifference{100, 40, 400, 404};
    return c;
}

// Luma blocks (3, 1) all differing, (5, 0) a quarter, and the last column's 8-sample-wide
// block (31, 0) all of its 256 samples.
PlaneComparison mismatching_luma() { return plane_comparison(kWidth, kHeight, 32, {{3, 1, 1024}, {5, 0, 256}, {31, 0, 256}}); }

StreamDiagnosis diagnosis(const char* id, const char* description, int tried, int exact, int64_t differing,
                          int contradicted) {
    StreamDiagnosis d;
    d.id = id;
    d.description = description;
    d.frames_tried = tried;
    d.frames_exact = exact;
    d.differing = differing;
    d.squared_error = 4.0 * double(differing);
    d.frames_contradicted = contradicted;
    return d;
}

VerificationResult hand_made_result() {
    VerificationResult r;
    r.model = "av1";
    r.reference = "av1 (AV1 7.18.3)";
    r.source_name = "clip <1>.ivf";
    r.decoded_name = "decoded.y4m";
    r.width = kWidth;
    r.height = kHeight;
    r.pix_fmt = "yuv420p10le";
    r.luma_block = 32;

    FrameVerification exact;
    exact.index = 0;
    exact.decoded_index = 0;
    exact.grain_expected = true;
    exact.exact = true;
    exact.comparison = PictureComparison{{plane_comparison(kWidth, kHeight, 32, {}),
                                          plane_comparison(kWidth / 2, kHeight / 2, 16, {}),
                                          plane_comparison(kWidth / 2, kHeight / 2, 16, {})}};

    FrameVerification mismatching;
    mismatching.index = 1;
    mismatching.decoded_index = 1;
    mismatching.grain_expected = true;
    mismatching.comparison = PictureComparison{{mismatching_luma(), plane_comparison(kWidth / 2, kHeight / 2, 16, {{2, 1, 7}}),
                                                plane_comparison(kWidth / 2, kHeight / 2, 16, {})}};
    mismatching.comparison->squared_error = 1543 * 16.0;
    mismatching.hypotheses = {{"av1.no_overlap", "overlap_flag ignored", true, 0, 0},
                              {"av1.no_clipping", "clip_to_restricted_range ignored", false, 40, 160}};

    FrameVerification missing;
    missing.index = 2;
    missing.missing = true;

    r.frames = {exact, mismatching, missing};
    r.diagnosis = {diagnosis("av1.no_overlap", "overlap_flag ignored", 1, 1, 0, 0),
                   diagnosis("av1.no_clipping", "clip_to_restricted_range ignored", 1, 0, 40, 2)};
    return r;
}

// 10-bit luma whose 2x2 boxes are constant, so that the half-size grey is known exactly.
uint8_t expected_grey(int ox, int oy) { return uint8_t(37 + (ox + oy) % 150); }

struct TenBitLuma {
    std::vector<uint16_t> samples = std::vector<uint16_t>(std::size_t(kWidth) * kHeight);
    FrameView view;
    TenBitLuma() {
        for (int y = 0; y < kHeight; y++)
            for (int x = 0; x < kWidth; x++) samples[std::size_t(y * kWidth + x)] = uint16_t(expected_grey(x / 2, y / 2) * 4);
        view.format = ChromaFormat::k400;
        view.bit_depth = 10;
        view.width = kWidth;
        view.height = kHeight;
        view.planes[0] = PlaneView{reinterpret_cast<uint8_t*>(samples.data()), kWidth * 2, kWidth, kHeight};
    }
};

std::array<int, 3> tinted(uint8_t grey, double fraction) {
    const double alpha = 0.25 + 0.75 * fraction;
    return {int(std::lround(grey * (1 - alpha) + 255 * alpha)), int(std::lround(grey * (1 - alpha))),
            int(std::lround(grey * (1 - alpha)))};
}

void expect_pixel(const test_support::DecodedPng& png, int x, int y, std::array<int, 3> rgb) {
    const uint8_t* p = png.at(x, y);
    EXPECT_EQ((std::array<int, 3>{p[0], p[1], p[2]}), rgb) << "pixel " << x << "," << y;
}

TEST(VerificationSummaryLine, CountsAndTheMostLikelyExplanation) {
    EXPECT_EQ(verification_summary_line(hand_made_result()),
              "verify: 3 frames, 1 bit-exact, 1 mismatching, 1 missing; most likely: av1.no_overlap "
              "(overlap_flag ignored) reproduces 1/1 exactly");
}

TEST(VerificationSummaryLine, AllBitExact) {
    VerificationResult r = hand_made_result();
    r.frames.resize(1);
    EXPECT_EQ(verification_summary_line(r), "verify: 1 frame, all bit-exact");
    r.extra_decoded = 2;  // output past the end is no pass
    EXPECT_EQ(verification_summary_line(r), "verify: 1 frame, 1 bit-exact, 0 mismatching, 0 missing, 2 extra decoded pictures");
}

TEST(VerificationSummaryLine, ClosestWhenNoHypothesisReproducesAPicture) {
    VerificationResult r = hand_made_result();
    r.diagnosis.erase(r.diagnosis.begin());
    EXPECT_EQ(verification_summary_line(r),
              "verify: 3 frames, 1 bit-exact, 1 mismatching, 1 missing; closest: av1.no_clipping "
              "(clip_to_restricted_range ignored) reproduces 0/1 exactly, 40 samples still differ (2.6 % of the 1543 "
              "the reference leaves), but would change 2 bit-exact pictures");
}

// A closest mistake that leaves most of the reference's differences explains nothing: a
// decoder whose grain none of the known mistakes describes (Debian 12's FFmpeg 5.1 H.274).
TEST(VerificationSummaryLine, NoKnownMistakeWhenTheClosestLeavesMostDifferences) {
    VerificationResult r = hand_made_result();
    r.diagnosis.erase(r.diagnosis.begin());
    r.diagnosis.front().differing = 1500;
    r.diagnosis.front().frames_contradicted = 0;
    EXPECT_EQ(verification_summary_line(r),
              "verify: 3 frames, 1 bit-exact, 1 mismatching, 1 missing; no known mistake explains it; closest: "
              "av1.no_clipping (clip_to_restricted_range ignored) reproduces 0/1 exactly, 1500 samples still differ "
              "(97.2 % of the 1543 the reference leaves)");
}

std::string text_report(const VerificationResult& r, int max_frames_listed) {
    std::FILE* f = std::tmpfile();
    print_verification_text(f, r, max_frames_listed);
    std::rewind(f);
    std::string text;
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    std::fclose(f);
    return text;
}

TEST(VerificationText, NamesWhereEachPictureDeparts) {
    const std::string text = text_report(hand_made_result(), -1);
    for (const char* line : {"  source     clip <1>.ivf\n", "  size       1000x64 yuv420p10le\n",
                             "  reference  av1 (AV1 7.18.3)\n", "picture 0: bit-exact\n",
                             "picture 1: differs from the reference\n",
                             "  Y   1536 of 64000 samples differ (2.400 %), max |diff| 4\n",
                             "      first at Y x 100 y 40: expected 400, decoded 404\n",
                             "      3 of 64 blocks (32x32) differ; worst block (3, 1) with 1024 differing samples\n",
                             "  Cb  7 of 16000 samples differ", "  Cr  identical\n",
                             "    av1.no_overlap (overlap_flag ignored): reproduces the decoded picture exactly\n",
                             "    av1.no_clipping (clip_to_restricted_range ignored): 40 samples still differ\n",
                             "picture 2: missing from the decoded output\n", "diagnosis over 1 mismatching picture",
                             "  id               exact/tried  contradicted   differing  description\n",
                             "  av1.no_overlap           1/1             0           0  overlap_flag ignored   "
                             "<- most likely explanation\n",
                             "  av1.no_clipping          0/1             2          40  clip_to_restricted_range ignored\n"})
        EXPECT_NE(text.find(line), std::string::npos) << "no \"" << line << "\" in\n" << text;
    // the diagnosis comes after the pictures
    EXPECT_LT(text.find("picture 2: missing"), text.find("diagnosis over"));
}

TEST(VerificationText, ListsAtMostTheGivenNumberOfPictures) {
    const std::string text = text_report(hand_made_result(), 1);
    EXPECT_NE(text.find("picture 1: differs"), std::string::npos) << text;
    EXPECT_EQ(text.find("picture 2: missing"), std::string::npos) << text;
    EXPECT_NE(text.find("... and 1 more mismatching or missing picture not listed"), std::string::npos) << text;
}

TEST(VerificationText, Md5ListRunShowsBothDigests) {
    VerificationResult r = hand_made_result();
    r.frames[1].comparison.reset();
    r.frames[1].expected_md5 = "0123456789abcdef0123456789abcdef";
    r.frames[1].decoded_md5 = "fedcba9876543210fedcba9876543210";
    const std::string text = text_report(r, -1);
    EXPECT_NE(text.find("  expected md5 0123456789abcdef0123456789abcdef\n  decoded md5  fedcba9876543210fedcba9876543210\n"),
              std::string::npos)
        << text;
}

TEST(VerificationJson, HoldsCountsFramesAndPerBlockArrays) {
    const nlohmann::json doc = nlohmann::json::parse(verification_json(hand_made_result()));
    for (const char* key : {"model", "reference", "source", "decoded", "width", "height", "pix_fmt", "luma_block",
                            "frames", "extra_decoded", "diagnosis", "summary"})
        EXPECT_TRUE(doc.contains(key)) << key;
    EXPECT_EQ(doc["source"], "clip <1>.ivf");
    EXPECT_EQ(doc["width"], kWidth);
    EXPECT_EQ(doc["summary"], (nlohmann::json{{"frames", 3}, {"exact", 1}, {"mismatching", 1}, {"missing", 1},
                                              {"all_exact", false}}));
    ASSERT_EQ(doc["frames"].size(), 3u);

    const nlohmann::json& mismatching = doc["frames"][1];
    EXPECT_EQ(mismatching["exact"], false);
    EXPECT_EQ(mismatching["comparison"]["differing"], 1543);
    const nlohmann::json& y = mismatching["comparison"]["planes"][0];
    EXPECT_EQ(y["plane"], "Y");
    EXPECT_EQ(y["differing"], 1536);
    EXPECT_EQ(y["first_difference"], (nlohmann::json{{"x", 100}, {"y", 40}, {"expected", 400}, {"decoded", 404}}));
    EXPECT_EQ(y["blocks_x"], 32);
    EXPECT_EQ(y["blocks_differing"], 3);
    ASSERT_EQ(y["differing_per_block"].size(), 2u);
    ASSERT_EQ(y["differing_per_block"][0].size(), 32u);
    EXPECT_EQ(y["differing_per_block"][1][3], 1024);
    EXPECT_EQ(y["differing_per_block"][0][5], 256);
    EXPECT_EQ(y["differing_per_block"][0][31], 256);
    EXPECT_EQ(y["differing_per_block"][0][0], 0);
    EXPECT_EQ(mismatching["comparison"]["planes"][1]["differing_per_block"][1][2], 7);
    EXPECT_EQ(mismatching["comparison"]["planes"][2]["differing_per_block"], nlohmann::json::array());
    EXPECT_EQ(mismatching["hypotheses"][0]["id"], "av1.no_overlap");
    EXPECT_EQ(mismatching["hypotheses"][1]["differing"], 40);

    EXPECT_EQ(doc["frames"][2]["missing"], true);
    EXPECT_TRUE(doc["frames"][2]["comparison"].is_null());
    EXPECT_EQ(doc["diagnosis"][0], (nlohmann::json{{"id", "av1.no_overlap"}, {"description", "overlap_flag ignored"},
                                                   {"frames_tried", 1}, {"frames_exact", 1},
                                                   {"frames_contradicted", 0}, {"differing", 0}, {"squared_error", 0.0}}));
    EXPECT_EQ(doc["diagnosis"][1]["frames_contradicted"], 2);
}

TEST(HeatMap, GreyLumaAtHalfSizeWithDifferingBlocksTintedAndOutlined) {
    const fs::path dir = fresh_dir("heat") / "maps" / "nested";  // created by the writer
    const HeatMapWriter writer(dir.string());
    const TenBitLuma luma;
    const std::string name = writer.write(1, luma.view, mismatching_luma());
    EXPECT_EQ(name, "frame_000001.png");

    const test_support::DecodedPng png = test_support::read_png((dir / name).string());
    ASSERT_EQ(png.width, 500);
    ASSERT_EQ(png.height, 32);
    // untouched blocks: the luma shifted to 8 bits
    for (auto [x, y] : {std::pair{0, 0}, {200, 10}, {47, 20}, {64, 20}, {499, 31}})
        expect_pixel(png, x, y, {expected_grey(x, y), expected_grey(x, y), expected_grey(x, y)});
    // block (3, 1): luma 96-127 x 32-63, pixels 48-63 x 16-31, every sample differs: opaque red
    expect_pixel(png, 56, 24, {255, 0, 0});
    expect_pixel(png, 49, 30, {255, 0, 0});
    // its outline
    for (auto [x, y] : {std::pair{48, 16}, {63, 24}, {55, 31}}) expect_pixel(png, x, y, {140, 0, 0});
    // block (5, 0): a quarter of its samples differ
    expect_pixel(png, 88, 8, tinted(expected_grey(88, 8), 0.25));
    // block (31, 0) is 8 samples wide: 256 differing samples are all of it
    expect_pixel(png, 497, 5, {255, 0, 0});
    fs::remove_all(dir.parent_path().parent_path());
}

TEST(HeatMap, EightBitLumaAsIsAndAGridThatDoesNotTileIsRefused) {
    const fs::path dir = fresh_dir("heat8");
    std::vector<uint8_t> samples(64 * 40);
    for (std::size_t i = 0; i < samples.size(); i++) samples[i] = uint8_t(i * 13);
    FrameView view;
    view.bit_depth = 8;
    view.width = 64;
    view.height = 40;
    view.planes[0] = PlaneView{samples.data(), 64, 64, 40};
    const HeatMapWriter writer(dir.string());
    const std::string name = writer.write(7, view, plane_comparison(64, 40, 16, {{1, 2, 8}}));
    const test_support::DecodedPng png = test_support::read_png((dir / name).string());
    ASSERT_EQ(png.width, 64);
    ASSERT_EQ(png.height, 40);
    expect_pixel(png, 5, 3, {samples[3 * 64 + 5], samples[3 * 64 + 5], samples[3 * 64 + 5]});
    // block (1, 2) is 16x8 samples at the bottom edge: 8 of 128 differ
    expect_pixel(png, 20, 36, tinted(samples[36 * 64 + 20], 8.0 / 128));

    const std::string message =
        test_support::error_of([&] { writer.write(8, view, plane_comparison(32, 40, 16, {{1, 1, 3}})); });
    EXPECT_NE(message.find("does not tile the 64x40 luma plane"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir / "frame_000008.png"));
    fs::remove_all(dir);
}

TEST(VerificationHtml, SummaryDiagnosisPicturesAndHeatMap) {
    const fs::path dir = fresh_dir("html");
    VerificationResult r = hand_made_result();
    const HeatMapWriter writer((dir / "report heat maps").string());
    const TenBitLuma luma;
    r.frames[1].heat_map = "report heat maps/" + writer.write(1, luma.view, r.frames[1].comparison->planes[0]);
    const fs::path html_path = dir / "report.html";
    write_verification_html(html_path.string(), r);

    const std::string html = read_text(html_path);
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("<img src=\"report%20heat%20maps/frame_000001.png\""), std::string::npos) << html;
    EXPECT_TRUE(fs::exists(dir / "report heat maps" / "frame_000001.png"));
    EXPECT_NE(html.find("clip &lt;1&gt;.ivf"), std::string::npos);
    EXPECT_EQ(html.find("clip <1>.ivf"), std::string::npos);
    EXPECT_NE(html.find("<p class=\"verdict bad\">verify: 3 frames, 1 bit-exact, 1 mismatching, 1 missing; most likely"),
              std::string::npos);
    EXPECT_NE(html.find("<td>av1.no_clipping</td><td>clip_to_restricted_range ignored</td><td class=\"n\">0 / 1</td>"
                        "<td class=\"n\">2</td><td class=\"n\">40</td>"),
              std::string::npos)
        << html;
    EXPECT_NE(html.find("most likely explanation"), std::string::npos);
    // mismatching and missing pictures before the bit-exact ones
    const std::size_t mismatching = html.find(">mismatching<"), missing = html.find(">missing<"),
                      exact = html.find(">bit-exact<");
    ASSERT_NE(exact, std::string::npos);
    EXPECT_LT(mismatching, exact);
    EXPECT_LT(missing, exact);
    EXPECT_NE(html.find("Y (100, 40): 400 &rarr; 404"), std::string::npos);
    EXPECT_NE(html.find("<a href=\"#heat-1\">"), std::string::npos);
    EXPECT_NE(html.find("<h3 id=\"heat-1\">"), std::string::npos);
    // no temporary left beside the page
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
    fs::remove_all(dir);
}

TEST(VerificationHtml, UnwritablePageThrowsIoNamingIt) {
    const fs::path dir = fresh_dir("html-unwritable");
    const fs::path html_path = dir / "missing-directory" / "report.html";
    try {
        write_verification_html(html_path.string(), hand_made_result());
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kIo);
        EXPECT_NE(std::string(e.what()).find(html_path.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(html_path));
    fs::remove_all(dir);
}

}  // namespace

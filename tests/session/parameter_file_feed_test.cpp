// session/parameter_file_feed: what `filmgrain apply` and the GStreamer element's
// properties hand the session per picture.
#include "session/parameter_file_feed.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "metadata/fgc_sei.hpp"

using namespace filmgrain;
using namespace filmgrain::session;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("filmgrain-feed-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

FgcParams luma_grain(int strength) {
    FgcParams p;
    p.log2_scale_factor = 3;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 0;
    p.comp[0].intervals.resize(1);
    p.comp[0].intervals[0].intensity_interval_upper_bound = 255;
    p.comp[0].intervals[0].comp_model_value[0] = strength;
    return p;
}

}  // namespace

TEST(ParameterFileFeed, TellsFormsByContentThenName) {
    const fs::path json = scratch("p.txt"), table = scratch("t.txt"), sei = scratch("x.fgc.bin"), afgs1 = scratch("x.t35"),
                   other = scratch("x.dat");
    write_text(json, "  {\"film_grain_model_id\": 0}");
    write_text(table, "filmgrn1\n");
    write_text(sei, "\x01");
    write_text(afgs1, "\x01");
    write_text(other, "\x01");
    EXPECT_EQ(detect_parameter_form(json.string(), false), ParameterForm::kJson);
    EXPECT_EQ(detect_parameter_form(table.string(), false), ParameterForm::kTable);
    EXPECT_EQ(detect_parameter_form(sei.string(), false), ParameterForm::kSei);
    EXPECT_EQ(detect_parameter_form(afgs1.string(), false), ParameterForm::kAfgs1);
    EXPECT_EQ(detect_parameter_form(other.string(), true), ParameterForm::kSei);
    try {
        detect_parameter_form(other.string(), false);
        FAIL() << "a nameless binary file was taken for a payload";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("x.dat"), std::string::npos) << e.what();
    }
    EXPECT_EQ(parameter_form_from_name("out.tbl", false), ParameterForm::kTable);
    fs::remove_all(json.parent_path());
}

TEST(ParameterFileFeed, SeiPatternGivesEachPictureItsPayloadAndPocK) {
    write_text(scratch("s_0.bin"), [] {
        const auto b = write_fgc_sei_payload(luma_grain(50), FgcCodec::kHevc);
        return std::string(b.begin(), b.end());
    }());
    ParameterFiles files;
    files.sei = {scratch("s_%d.bin").string()};
    ParameterFileFeed feed(files);
    EXPECT_EQ(feed.model(), FeedModel::kFgc);
    Session session;
    for (int k = 0; k < 3; k++) {
        const FrameInfo fi = feed.feed(session, k, 25, 1);
        EXPECT_EQ(fi.ids.poc, k);
        EXPECT_EQ(fi.ids.idr_pic_id, 0);
    }
    // a damaged payload names its file
    write_text(scratch("s_3.bin"), std::string("\x00\x12", 2));
    try {
        feed.feed(session, 3, 25, 1);
        FAIL() << "a truncated payload was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("s_3.bin"), std::string::npos) << e.what();
    }
    fs::remove_all(scratch("").parent_path());
}

TEST(ParameterFileFeed, GrainTablesNeedAFrameRateAndExactlyOneSourceIsGiven) {
    ParameterFiles files;
    files.params = std::string(FILMGRAIN_SOURCE_DIR) + "/conformance/av1_tbl_176x144_420p12/grain.tbl";
    ParameterFileFeed feed(files);
    EXPECT_EQ(feed.model(), FeedModel::kAv1);
    Session session;
    EXPECT_THROW(feed.feed(session, 0, 0, 1), Error);
    EXPECT_NO_THROW(feed.feed(session, 2, 25, 1));
    ParameterFiles none;
    EXPECT_THROW(ParameterFileFeed{none}, Error);
    ParameterFiles two = files;
    two.sei = {"x.sei"};
    EXPECT_THROW(ParameterFileFeed{two}, Error);
    fs::remove_all(scratch("").parent_path());
}

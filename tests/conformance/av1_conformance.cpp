// AV1 film grain conformance: every conformance/av1_* case, with parameters
// taken (a) from case.json params.av1 and (b) from grain.tbl by timestamp
// k * 400000 (10 MHz ticks at 25 fps), each frame's output MD5 compared with
// the golden. When expected.yuv.xz is present, a mismatch reports the first
// differing sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "av1/av1_picture_synthesis.hpp"
#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"

namespace fs = std::filesystem;
using namespace filmgrain;

namespace {

std::vector<std::string> av1_cases() { return test_support::list_cases("av1_"); }

enum class ParamSource { kCaseJson, kGrainTable };

void run_case(const std::string& name, ParamSource source) {
    const test_support::ConformanceCase c = test_support::load_case(name);
    const std::vector<Av1FrameParams> json_params = av1_frame_params_from_json(c.json);
    AomGrainTable table;
    if (source == ParamSource::kGrainTable) table = read_aom_grain_table((fs::path(c.dir) / "grain.tbl").string());

    int mismatches = 0;
    for (int k = 0; k < c.frames; ++k) {
        const auto& fi = c.frame_info(k);
        const int mc = fi.at("params").value("matrix_coefficients", 2);
        Av1FilmGrainParams p;
        if (source == ParamSource::kCaseJson) {
            p = json_params[static_cast<std::size_t>(k)].grain;
        } else {
            const int64_t ts = static_cast<int64_t>(k) * 400000;
            const auto idx = table.find_index(ts);
            ASSERT_TRUE(idx.has_value()) << "no grain.tbl entry for timestamp " << ts;
            p = table.resolved_params(*idx);
            // filmgrn1 cannot carry clip_to_restricted_range (README caveat 6):
            // that one field is a stream fact taken from case.json.
            p.clip_to_restricted_range = json_params[static_cast<std::size_t>(k)].grain.clip_to_restricted_range;
            // Apart from that, the table must describe the same signalled parameters.
            EXPECT_EQ(av1_params_to_json(p), av1_params_to_json(json_params[static_cast<std::size_t>(k)].grain))
                << "frame " << k << ": grain.tbl and case.json disagree";
        }

        const FrameBuffer src = c.input_frame(k);
        FrameBuffer dst(c.width, c.height, c.format);
        av1::apply_film_grain(p, const_cast<FrameBuffer&>(src).view(), dst.view(), mc);

        // The source must be untouched, and in-place must give the same result.
        ASSERT_EQ(0, std::memcmp(src.bytes(), c.input.data() + c.frame_bytes() * static_cast<std::size_t>(k),
                                 c.frame_bytes()));
        FrameBuffer inplace = src;
        av1::apply_film_grain(p, inplace.view(), inplace.view(), mc);
        EXPECT_EQ(md5_hex(inplace.bytes(), inplace.byte_size()), md5_hex(dst.bytes(), dst.byte_size()))
            << "frame " << k << ": in-place differs";

        const std::string why = test_support::describe_mismatch(c, k, dst.bytes(), dst.byte_size());
        if (!why.empty()) {
            ++mismatches;
            ADD_FAILURE() << why;
        }
    }
    EXPECT_EQ(mismatches, 0);
}

class Av1Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Av1Conformance, ParamsFromCaseJson) { run_case(GetParam(), ParamSource::kCaseJson); }
TEST_P(Av1Conformance, ParamsFromGrainTable) { run_case(GetParam(), ParamSource::kGrainTable); }

INSTANTIATE_TEST_SUITE_P(Cases, Av1Conformance, ::testing::ValuesIn(av1_cases()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(Av1ConformanceSet, AllCasesPresent) { EXPECT_EQ(av1_cases().size(), 28u); }

}  // namespace

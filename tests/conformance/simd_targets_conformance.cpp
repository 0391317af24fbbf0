// Every conformance case through the optimized kernels for every vector target this CPU
// runs (each forced in turn), with two stripe threads: the output must stay bit-exact with
// the goldens. (fgc_conformance / av1_conformance cover the default target; this covers the
// others and the threaded path.)
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "afgs1_case.hpp"
#include "av1/av1_picture_synthesis.hpp"
#include "conformance_case.hpp"
#include "core/md5.hpp"
#include "core/simd_targets.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "io/xz_file.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_sei.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

// Returns the number of frames whose MD5 differs from the golden.
int run_fgc_case(const std::string& name) {
    const ConformanceCase c = load_case(name);
    const FgcCodec codec = c.json.at("codec") == "h264" ? FgcCodec::kAvc : FgcCodec::kHevc;
    FgcOptions opt;
    opt.flavour = c.json.at("family") == "vtm" ? FgcFlavour::kVtm : FgcFlavour::kRdd5;
    opt.passthrough_invalid = true;
    opt.threads = 2;
    FgcStreamSynthesis synth(opt);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        const auto& fi = c.frame_info(k);
        if (fi.at("sei_present").get<bool>()) {
            const fs::path bin = fs::path(c.dir) / ("frame" + std::to_string(k) + ".fgc.bin");
            synth.receive_sei(parse_fgc_sei_payload(read_whole_file(bin.string()), codec), codec);
        }
        FgcPictureIds ids;
        ids.poc = fi.at("poc").get<int>();
        ids.idr_pic_id = fi.at("idr_pic_id").is_null() ? 0 : fi.at("idr_pic_id").get<int>();
        FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
        synth.apply(in.view(), out.view(), ids);
        if (md5_hex(out.bytes(), out.byte_size()) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << describe_mismatch(c, k, out.bytes(), out.byte_size());
        }
    }
    return mismatches;
}

int run_av1_case(const std::string& name) {
    const ConformanceCase c = load_case(name);
    const std::vector<Av1FrameParams> params = av1_frame_params_from_json(c.json);
    av1::Av1PictureSynthesis synth(2);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        const int mc = c.frame_info(k).at("params").value("matrix_coefficients", 2);
        FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
        synth.apply(params[std::size_t(k)].grain, in.view(), out.view(), mc);
        if (md5_hex(out.bytes(), out.byte_size()) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << describe_mismatch(c, k, out.bytes(), out.byte_size());
        }
    }
    return mismatches;
}

class ConformancePerTarget : public ::testing::TestWithParam<simd::Target> {
protected:
    void SetUp() override { ASSERT_TRUE(simd::force_target(GetParam().bits)); }
    void TearDown() override { simd::force_target(0); }
};

TEST_P(ConformancePerTarget, FgcCases) {
    auto cases = list_cases("vtm_");
    for (const auto& r : list_cases("rdd5_")) cases.push_back(r);
    ASSERT_FALSE(cases.empty());
    for (const auto& name : cases) EXPECT_EQ(run_fgc_case(name), 0) << name << " on " << GetParam().name;
}

TEST_P(ConformancePerTarget, Av1Cases) {
    const auto cases = list_cases("av1_");
    ASSERT_FALSE(cases.empty());
    for (const auto& name : cases) EXPECT_EQ(run_av1_case(name), 0) << name << " on " << GetParam().name;
}

TEST_P(ConformancePerTarget, Afgs1Cases) {
    const auto cases = list_cases("afgs1-");
    ASSERT_FALSE(cases.empty());
    SessionOptions o;
    o.threads = 2;
    for (const auto& name : cases)
        EXPECT_EQ(run_afgs1_case(load_case(name), o, false), 0) << name << " on " << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(Targets, ConformancePerTarget, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

}  // namespace

// Conformance of the VFGS flavour (TR 23002-9 clause 7.5) against the
// InterDigital VersatileFilmGrain goldens in conformance/vfgs-*: one test per
// case, every frame's md5 must match. AFGS1 input (vfgs-afgs1-*) is not an FGC
// SEI flavour and is not run here.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "conformance_case.hpp"
#include "filmgrain/vfgs.hpp"
#include "metadata/fgc_json.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;
using nlohmann::json;

namespace {

std::vector<std::string> vfgs_cases() {
    std::vector<std::string> names;
    for (auto& n : list_cases("vfgs-"))
        if (n.rfind("vfgs-afgs1-", 0) != 0) names.push_back(n);
    return names;
}

class VfgsConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(VfgsConformance, BitExact) {
    const ConformanceCase c = load_case(GetParam());
    const json& cj = c.json;
    vfgs::Options opt;
    if (!cj.at("seed").is_null()) opt.seed = cj.at("seed").get<uint32_t>();
    opt.gain_percent = cj.value("vfgs_gain_percent", 100);
    if (c.output_format.bit_depth != c.format.bit_depth) opt.output_bit_depth = c.output_format.bit_depth;
    vfgs::Synthesizer synth(opt);
    if (cj.contains("vfgs_lfsr_init")) {
        const uint32_t want = static_cast<uint32_t>(std::stoul(cj.at("vfgs_lfsr_init").get<std::string>(), nullptr, 16));
        EXPECT_EQ(synth.lfsr_state(), want) << "initial LFSR state";
    }

    json last_params;
    int mismatches = 0;
    std::string first_report;
    for (int k = 0; k < c.frames; ++k) {
        const json& pj = c.frame_info(k).at("params").at("fgc");
        // Same parameters as the previous frame: keep going (the LFSR continues
        // either way; a new set only rebuilds templates and LUTs).
        if (k == 0 || pj != last_params) {
            synth.set_params(fgc_params_from_json(pj));
            last_params = pj;
        }
        FrameBuffer src = c.input_frame(k);
        FrameBuffer dst(c.width, c.height, c.output_format);
        if (c.output_format.bit_depth == c.format.bit_depth) {
            synth.apply(src.view(), src.view());  // in place, as the reference does
            dst = src;
        } else {
            synth.apply(src.view(), dst.view());
        }
        const std::string why = describe_mismatch(c, k, dst.bytes(), dst.byte_size());
        if (!why.empty()) {
            ++mismatches;
            if (first_report.empty()) first_report = why;
        }
    }
    EXPECT_EQ(mismatches, 0) << mismatches << " of " << c.frames << " frames differ; " << first_report;
}

INSTANTIATE_TEST_SUITE_P(Cases, VfgsConformance, ::testing::ValuesIn(vfgs_cases()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

}  // namespace

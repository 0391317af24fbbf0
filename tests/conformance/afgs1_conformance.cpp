// AFGS1 conformance: every conformance/afgs1-* case (goldens from FFmpeg 7.1.5's synthesis of
// the set the AFGS1 text selects, payloads from an independent writer; README "Family
// afgs1") through the stream session: out of place and in place, with 1 and 3 stripe
// threads. The CLI (cli_conformance), the C API (capi_conformance) and every vector target
// (simd_targets_conformance) run them too.
#include <gtest/gtest.h>

#include "afgs1_case.hpp"
#include "conformance_case.hpp"

using namespace filmgrain;
using namespace filmgrain::test_support;

namespace {

class Afgs1Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Afgs1Conformance, PayloadsThroughTheSession) {
    const ConformanceCase c = load_case(GetParam());
    for (int threads : {1, 3})
        for (bool in_place : {false, true}) {
            SessionOptions o;
            o.threads = threads;
            EXPECT_EQ(run_afgs1_case(c, o, in_place), 0) << GetParam() << ", " << threads << " thread(s)"
                                                         << (in_place ? ", in place" : "");
        }
}

INSTANTIATE_TEST_SUITE_P(Cases, Afgs1Conformance, ::testing::ValuesIn(list_cases("afgs1-")),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param;
                             for (auto& ch : n)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return n;
                         });

TEST(Afgs1ConformanceSet, TenCases) { EXPECT_EQ(list_cases("afgs1-").size(), 10u); }

}  // namespace

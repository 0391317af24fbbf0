// `filmgrain --version` names the library version and the vector target the optimized kernels
// run on: benchmark reports (tools/bench-compare) and bug reports quote it.
#include <gtest/gtest.h>

#include <string>

#include "conformance_case.hpp"
#include "core/simd_targets.hpp"

using namespace filmgrain::test_support;

TEST(VersionCli, NamesVersionAndDispatchedTarget) {
    std::string log;
    ASSERT_EQ(run_command(std::string("'") + FILMGRAIN_TOOL_PATH + "' --version", &log), 0) << log;
    EXPECT_NE(log.find("filmgrain 2.0.0"), std::string::npos) << log;
    EXPECT_NE(log.find("vector target: " + filmgrain::simd::dispatched_target() + " "), std::string::npos) << log;
}

TEST(VersionCli, ForcedTargetIsTheOneReported) {
    std::string log;
    ASSERT_EQ(run_command(std::string("FILMGRAIN_SIMD_TARGET=SCALAR '") + FILMGRAIN_TOOL_PATH + "' --version", &log), 0)
        << log;
    EXPECT_NE(log.find("vector target: SCALAR "), std::string::npos) << log;
}

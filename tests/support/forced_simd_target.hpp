// Fixture of the checkasm-style equivalence tests: each test runs once per dispatch target
// the CPU has (instantiate with ::testing::ValuesIn(simd::available_targets())), with that
// target forced for its duration and a random generator seeded per target, so that a
// failure names the target and repeats.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/simd_targets.hpp"

namespace filmgrain::test_support {

template <uint32_t kSeed>
class ForcedSimdTarget : public ::testing::TestWithParam<simd::Target> {
protected:
    void SetUp() override {
        ASSERT_TRUE(simd::force_target(GetParam().bits));
        ASSERT_EQ(simd::dispatched_target(), GetParam().name) << "dispatch did not follow the forced target";
    }
    void TearDown() override { simd::force_target(0); }
    std::mt19937 rng{kSeed ^ uint32_t(GetParam().bits)};
    int uniform(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }
};

}  // namespace filmgrain::test_support

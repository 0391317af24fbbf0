// The Boolean renderer's output may not depend on how the work is split: rendered at one
// and two threads, and in a region (whose tiles start elsewhere), it must be the same
// picture. Shared by the renderer's tests at non-unit zoom and the mask estimator's.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>

#include "physical/boolean_model.hpp"

namespace filmgrain::test_support {

inline void expect_render_independent_of_split(const FloatPlane& u, physical::BooleanModelParams p, uint64_t seed,
                                               const physical::OutputRegion& region) {
    FloatPlane one, two, part;
    p.threads = 1;
    physical::render_boolean_model(u, p, {}, seed, one);
    p.threads = 2;
    physical::render_boolean_model(u, p, {}, seed, two);
    EXPECT_EQ(one.v, two.v);
    physical::render_boolean_model(u, p, region, seed, part);
    ASSERT_EQ(part.width, region.w);
    for (int y = 0; y < region.h; y++)
        for (int x = 0; x < region.w; x++)
            ASSERT_EQ(part.at(x, y), one.at(region.x + x, region.y + y)) << x << "," << y;
}

}  // namespace filmgrain::test_support

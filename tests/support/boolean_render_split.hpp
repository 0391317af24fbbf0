// The Boolean renderer's output may not depend on how the work is split: rendered at one
// and two threads, and in a region (whose tiles start elsewhere), it must be the same
// picture. Shared by the renderer's tests at non-unit zoom and the mask estimator's.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "physical/boolean_model.hpp"

namespace filmgrain::test_support {

// A smooth plane of grey levels 0.05..0.95 (a product of two sinusoids, fx and fy radians
// per pixel): every grain density the split tests need, without black or white.
inline FloatPlane wavy_plane(int w, int h, double fx, double fy) {
    FloatPlane u(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) u.at(x, y) = float(0.5 + 0.45 * std::sin(x * fx) * std::cos(y * fy));
    return u;
}

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

// The unit-zoom mask estimator's stages: the coverage-mask kernel on every dispatch target
// against its scalar reference, on random grains and points including points exactly on a
// grain's edge; the grouping of samples into classes; and a whole render with the vector
// kernels equal to one with the scalar kernels.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "core/simd_targets.hpp"
#include "physical/boolean_model.hpp"
#include "physical/coverage_masks.hpp"
#include "physical/monte_carlo_offsets.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

class CoverageMaskEquivalence : public test_support::ForcedSimdTarget<0xC0FE> {};

TEST_P(CoverageMaskEquivalence, OptimizedEqualsReference) {
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    for (int iter = 0; iter < 3000; iter++) {
        const uint32_t m = uint32_t(uniform(1, 200));
        const int words = int((m + 63) / 64) + uniform(0, 1);
        const uint32_t padded = (m + kClassPointPad - 1) / kClassPointPad * kClassPointPad;
        std::vector<float> lx(padded, std::numeric_limits<float>::quiet_NaN()), ly(lx);
        for (uint32_t j = 0; j < m; j++) lx[j] = unit(rng), ly[j] = unit(rng);
        std::vector<BinnedGrain> grains(std::size_t(uniform(0, 12)));
        for (auto& g : grains) {
            g = {unit(rng) * 1.6f - 0.3f, unit(rng) * 1.6f - 0.3f, unit(rng) * unit(rng) * 0.5f};
            // Some grains pass exactly through a sample point: the <= of the test decides.
            if (m > 0 && uniform(0, 3) == 0) {
                const uint32_t j = uint32_t(uniform(0, int(m) - 1));
                const float dx = lx[j] - g.x, dy = ly[j] - g.y;
                g.r2 = dx * dx + dy * dy;
            }
        }
        std::vector<uint64_t> want(std::size_t(words), ~0ull), got(want);
        coverage_mask_reference(grains.data(), uint32_t(grains.size()), lx.data(), ly.data(), m, want.data(), words);
        coverage_mask_optimized(grains.data(), uint32_t(grains.size()), lx.data(), ly.data(), m, got.data(), words);
        ASSERT_EQ(got, want) << "iteration " << iter << " m " << m << " grains " << grains.size();
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, CoverageMaskEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

TEST(SampleClasses, EverySampleHasOnePlaceInItsClass) {
    BooleanModelParams p;
    for (int k : {1, 3, 5, 10}) {
        const auto xi = monte_carlo_offsets(p, 9, 800);
        const SamplePoints pts(xi, 800, 1.0, k);
        const SampleClasses c = group_samples_by_class(pts);
        ASSERT_EQ(c.begin.size(), std::size_t(k) * k);
        std::vector<int> seen(c.lx.size(), 0);
        for (int i = 0; i < 800; i++) {
            const uint32_t cls = c.sample_class[std::size_t(i)];
            const int64_t sx = pts.steps_x()[std::size_t(i)].bin, sy = pts.steps_y()[std::size_t(i)].bin;
            EXPECT_EQ(cls, uint32_t(((sy % k + k) % k) * k + (sx % k + k) % k));
            const uint32_t j = c.sample_word[std::size_t(i)] * 64 + c.sample_bit[std::size_t(i)];
            ASSERT_LT(j, c.size[cls]);
            ASSERT_LT(j, uint32_t(c.words) * 64);
            const std::size_t at = c.begin[cls] + j;
            seen[at]++;
            EXPECT_EQ(c.lx[at], pts.steps_x()[std::size_t(i)].local);
            EXPECT_EQ(c.ly[at], pts.steps_y()[std::size_t(i)].local);
        }
        for (std::size_t cls = 0; cls < c.size.size(); cls++)
            for (uint32_t j = 0; j < c.size[cls]; j++) EXPECT_EQ(seen[c.begin[cls] + j], 1);
    }
}

TEST(CoverageMaskRender, VectorAndScalarKernelsRenderTheSame) {
    FloatPlane u(96, 64);
    for (int y = 0; y < u.height; y++)
        for (int x = 0; x < u.width; x++) u.at(x, y) = float((x * 5 + y * 3) % 17) / 16.f;
    for (double radius : {0.05, 0.3}) {
        BooleanModelParams p;
        p.radius_mean = radius;
        p.radius_sigma = radius * 0.5;
        p.samples = 200;
        p.algorithm = BooleanAlgorithm::kPixelWise;
        FloatPlane vec, ref;
        render_boolean_model(u, p, {}, 4, vec);
        p.reference_kernels = true;
        render_boolean_model(u, p, {}, 4, ref);
        EXPECT_EQ(vec.v, ref.v) << radius;
    }
}

}  // namespace

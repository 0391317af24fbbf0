// The unit-zoom mask estimator's stages: the mask-painting kernel on every dispatch target
// against its scalar reference, on random grains and points including points exactly on a
// grain's edge; the painted masks against the bin lists; the grouping of samples into
// classes; a whole render with the vector kernels equal to one with the scalar kernels; and
// renders that do not depend on the thread count, the tiling or the region.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/simd_targets.hpp"
#include "physical/boolean_model.hpp"
#include "physical/coverage_masks.hpp"
#include "physical/grain_field.hpp"
#include "physical/monte_carlo_offsets.hpp"
#include "boolean_render_split.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

class CoverageMaskEquivalence : public test_support::ForcedSimdTarget<0xC0FE> {};

// Random classes of points in bins 1/k wide and random grains around a small grid, at k = 1
// so that a grain's squared radius can be made exactly the float distance to a point (the
// <= of the test then decides), and at k = 3 and 10 (a class per bin residue).
TEST_P(CoverageMaskEquivalence, OptimizedEqualsReference) {
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    for (int iter = 0; iter < 600; iter++) {
        const int k = std::vector<int>{1, 3, 10}[std::size_t(uniform(0, 2))];
        SampleClasses c;
        c.cells_per_pixel = k;
        const std::size_t classes = std::size_t(k) * k;
        c.begin.resize(classes);
        c.size.resize(classes);
        uint32_t at = 0, largest = 0;
        for (std::size_t cls = 0; cls < classes; cls++) {
            c.size[cls] = uint32_t(uniform(0, 4) == 0 ? 0 : uniform(1, k == 1 ? 150 : 40));
            c.begin[cls] = at;
            largest = std::max(largest, c.size[cls]);
            at += (c.size[cls] + kClassPointPad - 1) / kClassPointPad * kClassPointPad;
        }
        c.words = std::max(1, int((largest + kMaskWordBits - 1) / kMaskWordBits)) + uniform(0, 1);
        c.lx.assign(at, std::numeric_limits<float>::quiet_NaN());
        c.ly = c.lx;
        for (std::size_t cls = 0; cls < classes; cls++)
            for (uint32_t j = 0; j < c.size[cls]; j++) c.lx[c.begin[cls] + j] = unit(rng), c.ly[c.begin[cls] + j] = unit(rng);
        const double x0 = uniform(-20, 20) / double(k), y0 = uniform(-20, 20) / double(k);
        const BinGrid grid = bin_grid_over(x0, y0, x0 + uniform(0, 6) / double(k) + 0.5 / k,
                                           y0 + uniform(0, 6) / double(k) + 0.5 / k, k);
        const MaskLayout layout = mask_layout(grid, c);
        std::vector<Grain> grains(std::size_t(uniform(0, 40)));
        for (auto& g : grains) {
            const double r = unit(rng) * 1.2 / k;
            g = {x0 + (unit(rng) * (grid.nbx + 2) - 1) / k, y0 + (unit(rng) * (grid.nby + 2) - 1) / k, r * r};
            if (k == 1 && uniform(0, 2) == 0) {
                // Through a point of the bin holding its centre, exactly on the edge.
                const int64_t bx = floor_to_int(g.x), by = floor_to_int(g.y);
                if (bx < grid.bx0 || by < grid.by0 || bx >= grid.bx0 + grid.nbx || by >= grid.by0 + grid.nby) continue;
                const uint32_t cls = layout.row_class[std::size_t(by - grid.by0)] + layout.col_class[std::size_t(bx - grid.bx0)];
                if (c.size[cls] == 0) continue;
                const uint32_t j = c.begin[cls] + uint32_t(uniform(0, int(c.size[cls]) - 1));
                const float dx = c.lx[j] - bin_local(g.x, bx), dy = c.ly[j] - bin_local(g.y, by);
                g.r2 = double(dx * dx + dy * dy);
            }
        }
        const std::size_t words = std::size_t(grid.nbx * grid.nby) * std::size_t(c.words);
        std::vector<MaskWord> want(words, 0), got(words, 0);
        paint_coverage_masks_reference(grains.data(), grains.size(), layout, c, want.data());
        paint_coverage_masks_optimized(grains.data(), grains.size(), layout, c, got.data());
        ASSERT_EQ(got, want) << "iteration " << iter << " k " << k << " grains " << grains.size();
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, CoverageMaskEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

// The masks painted row of cells by row of cells against the bin lists the pixel-wise
// estimator searches: bit j of a bin is set exactly when its class point j is covered by a
// grain of the bin's list.
TEST(CoverageMasks, PaintedMasksEqualTheBinListsLookUp) {
    FloatPlane u(24, 20);
    for (int y = 0; y < u.height; y++)
        for (int x = 0; x < u.width; x++) u.at(x, y) = float((x * 5 + y * 3) % 17) / 16.f;
    for (const double radius : {0.05, 0.12, 0.4}) {
        const GrainRadiusLaw law(radius, radius * 0.5);
        const int k = int(std::lround(1 / (2 * radius)));
        BooleanModelParams p;
        const auto xi = monte_carlo_offsets(p, 5, 300);
        const SamplePoints pts(xi, 300, 1.0, k);
        const SampleClasses c = group_samples_by_class(pts);
        const CellIntensity intensity(u, law, 1e-3, std::max(1, (k + 1) / 3), -4, -4, 28, 24);
        GrainField field;
        field.generate(intensity, law, k, 77, 2.3, 1.7, 15.2, 12.9, true);
        for (const bool reference : {true, false}) {
            std::vector<MaskWord> masks;
            GrainField painter;
            EXPECT_EQ(paint_tile_masks(painter, intensity, law, 77, 2.3, 1.7, 15.2, 12.9, c, reference, masks),
                      field.grains().size());
            const MaskLayout layout = mask_layout(field.grid(), c);
            ASSERT_EQ(masks.size(), std::size_t(field.bins_x() * field.bins_y()) * std::size_t(c.words));
            for (int64_t by = 0; by < field.bins_y(); by++)
                for (int64_t bx = 0; bx < field.bins_x(); bx++) {
                    const uint32_t cls = layout.row_class[std::size_t(by)] + layout.col_class[std::size_t(bx)];
                    const MaskWord* mask = masks.data() + std::size_t(by * field.bins_x() + bx) * std::size_t(c.words);
                    for (int w = 0; w < c.words; w++)
                        for (int bit = 0; bit < kMaskWordBits; bit++) {
                            const uint32_t j = uint32_t(w * kMaskWordBits + bit);
                            const bool want =
                                j < c.size[cls] && field.covered_in_bin(field.first_bin_x() + bx, field.first_bin_y() + by,
                                                                        c.lx[c.begin[cls] + j], c.ly[c.begin[cls] + j]);
                            ASSERT_EQ(bool((mask[w] >> bit) & 1u), want)
                                << "radius " << radius << " reference " << reference << " bin " << bx << "," << by;
                        }
                }
        }
    }
}

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
            const uint32_t j = c.sample_word[std::size_t(i)] * kMaskWordBits + c.sample_bit[std::size_t(i)];
            ASSERT_LT(j, c.size[cls]);
            ASSERT_LT(j, uint32_t(c.words) * kMaskWordBits);
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

// The mask estimator's tiles (128 pixels at unit zoom) cut this plane into six, the last
// ones partial, and a region cuts it elsewhere: the output must not see where.
TEST(CoverageMaskRender, SameOutputForEveryThreadCountTilingAndRegion) {
    const FloatPlane u = test_support::wavy_plane(260, 140, 0.07, 0.11);
    BooleanModelParams p;
    p.radius_mean = 0.15;
    p.samples = 32;
    p.algorithm = BooleanAlgorithm::kPixelWise;
    test_support::expect_render_independent_of_split(u, p, 7, {77, 33, 170, 100});
}

}  // namespace

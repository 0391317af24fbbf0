#include "physical/coverage_masks.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace filmgrain::physical {

namespace {
int positive_mod(int64_t v, int m) { return int(((v % m) + m) % m); }
}  // namespace

SampleClasses group_samples_by_class(const SamplePoints& points) {
    SampleClasses c;
    const int k = points.cells_per_pixel();
    const int n = points.count();
    c.cells_per_pixel = k;
    const std::size_t classes = std::size_t(k) * k;
    c.begin.assign(classes, 0);
    c.size.assign(classes, 0);
    c.sample_class.resize(std::size_t(n));
    c.sample_word.resize(std::size_t(n));
    c.sample_bit.resize(std::size_t(n));
    std::vector<uint32_t> place(static_cast<std::size_t>(n));
    for (int i = 0; i < n; i++) {
        const uint32_t cls = uint32_t(positive_mod(points.steps_y()[std::size_t(i)].bin, k) * k +
                                      positive_mod(points.steps_x()[std::size_t(i)].bin, k));
        c.sample_class[std::size_t(i)] = cls;
        place[std::size_t(i)] = c.size[cls]++;
    }
    uint32_t largest = 0, at = 0;
    for (std::size_t cls = 0; cls < classes; cls++) {
        largest = std::max(largest, c.size[cls]);
        c.begin[cls] = at;
        at += (c.size[cls] + kClassPointPad - 1) / kClassPointPad * kClassPointPad;
    }
    c.words = std::max(1, int((largest + kMaskWordBits - 1) / kMaskWordBits));
    c.lx.assign(at, std::numeric_limits<float>::quiet_NaN());
    c.ly.assign(at, std::numeric_limits<float>::quiet_NaN());
    for (int i = 0; i < n; i++) {
        const uint32_t cls = c.sample_class[std::size_t(i)], j = place[std::size_t(i)];
        c.lx[c.begin[cls] + j] = points.steps_x()[std::size_t(i)].local;
        c.ly[c.begin[cls] + j] = points.steps_y()[std::size_t(i)].local;
        c.sample_word[std::size_t(i)] = j / kMaskWordBits;
        c.sample_bit[std::size_t(i)] = uint8_t(j % kMaskWordBits);
    }
    return c;
}

MaskLayout mask_layout(const BinGrid& grid, const SampleClasses& classes) {
    MaskLayout l;
    l.grid = grid;
    l.words = classes.words;
    const int k = classes.cells_per_pixel;
    l.col_class.resize(std::size_t(grid.nbx));
    l.row_class.resize(std::size_t(grid.nby));
    for (int64_t bx = 0; bx < grid.nbx; bx++) l.col_class[std::size_t(bx)] = uint32_t(positive_mod(grid.bx0 + bx, k));
    for (int64_t by = 0; by < grid.nby; by++)
        l.row_class[std::size_t(by)] = uint32_t(positive_mod(grid.by0 + by, k) * k);
    return l;
}

void paint_coverage_masks_reference(const Grain* grains, std::size_t n, const MaskLayout& layout,
                                    const SampleClasses& classes, MaskWord* masks) {
    const BinGrid& grid = layout.grid;
    const std::size_t words = std::size_t(layout.words);
    for (std::size_t i = 0; i < n; i++) {
        const Grain& g = grains[i];
        const BinRange b = bins_met_by(g, std::sqrt(g.r2), grid);
        const float r2 = r2_in_bins(g.r2, grid.k);
        for (int64_t by = b.ly; by <= b.hy; by++) {
            const float gy = bin_local(g.y * grid.k, by + grid.by0);
            for (int64_t bx = b.lx; bx <= b.hx; bx++) {
                const float gx = bin_local(g.x * grid.k, bx + grid.bx0);
                const uint32_t cls = layout.row_class[std::size_t(by)] + layout.col_class[std::size_t(bx)];
                const float* lx = classes.lx.data() + classes.begin[cls];
                const float* ly = classes.ly.data() + classes.begin[cls];
                MaskWord* mask = masks + std::size_t(by * grid.nbx + bx) * words;
                for (uint32_t j = 0; j < classes.size[cls]; j++)
                    if (inside_grain(lx[j], ly[j], gx, gy, r2))
                        mask[j / kMaskWordBits] |= MaskWord(1u << (j % kMaskWordBits));
            }
        }
    }
}

std::size_t paint_tile_masks(GrainField& field, const CellIntensity& intensity, const GrainRadiusLaw& radius,
                             uint64_t seed, double x0, double y0, double x1, double y1, const SampleClasses& classes,
                             bool reference, std::vector<MaskWord>& masks) {
    const MaskLayout layout =
        mask_layout(bin_grid_over(x0, y0, x1, y1, classes.cells_per_pixel), classes);
    masks.assign(std::size_t(layout.grid.nbx * layout.grid.nby) * std::size_t(layout.words), 0);
    auto* paint = reference ? paint_coverage_masks_reference : paint_coverage_masks_optimized;
    return field.generate_by_cell_rows(intensity, radius, classes.cells_per_pixel, seed, x0, y0, x1, y1,
                                       [&](const std::vector<Grain>& grains) {
                                           paint(grains.data(), grains.size(), layout, classes, masks.data());
                                       });
}

}  // namespace filmgrain::physical

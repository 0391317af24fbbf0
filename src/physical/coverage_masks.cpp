#include "physical/coverage_masks.hpp"

#include <algorithm>
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
    c.words = std::max(1, int((largest + 63) / 64));
    c.lx.assign(at, std::numeric_limits<float>::quiet_NaN());
    c.ly.assign(at, std::numeric_limits<float>::quiet_NaN());
    for (int i = 0; i < n; i++) {
        const uint32_t cls = c.sample_class[std::size_t(i)], j = place[std::size_t(i)];
        c.lx[c.begin[cls] + j] = points.steps_x()[std::size_t(i)].local;
        c.ly[c.begin[cls] + j] = points.steps_y()[std::size_t(i)].local;
        c.sample_word[std::size_t(i)] = j / 64;
        c.sample_bit[std::size_t(i)] = uint8_t(j % 64);
    }
    return c;
}

void coverage_mask_reference(const BinnedGrain* grains, uint32_t n, const float* lx, const float* ly, uint32_t m,
                             uint64_t* mask, int words) {
    std::fill(mask, mask + words, 0);
    for (uint32_t j = 0; j < m; j++)
        for (uint32_t i = 0; i < n; i++)
            if (inside_grain(lx[j], ly[j], grains[i].x, grains[i].y, grains[i].r2)) {
                mask[j / 64] |= uint64_t(1) << (j % 64);
                break;
            }
}

void bin_coverage_masks(const GrainField& field, const SampleClasses& classes, bool reference,
                        std::vector<uint64_t>& masks) {
    const int k = classes.cells_per_pixel, words = classes.words;
    const int64_t nbx = field.bins_x(), nby = field.bins_y();
    masks.resize(std::size_t(nbx * nby) * words);
    const auto& start = field.bin_start();
    const BinnedGrain* grains = field.binned_grains().data();
    auto* kernel = reference ? coverage_mask_reference : coverage_mask_optimized;
    for (int64_t by = 0; by < nby; by++) {
        const int ry = positive_mod(field.first_bin_y() + by, k);
        for (int64_t bx = 0; bx < nbx; bx++) {
            const std::size_t b = std::size_t(by * nbx + bx);
            uint64_t* mask = masks.data() + b * words;
            const uint32_t cls = uint32_t(ry * k + positive_mod(field.first_bin_x() + bx, k));
            const uint32_t m = classes.size[cls];
            if (m == 0 || start[b] == start[b + 1]) {
                std::memset(mask, 0, sizeof(uint64_t) * std::size_t(words));
                continue;
            }
            kernel(grains + start[b], start[b + 1] - start[b], classes.lx.data() + classes.begin[cls],
                   classes.ly.data() + classes.begin[cls], m, mask, words);
        }
    }
}

}  // namespace filmgrain::physical

// Highway twin of paint_coverage_masks_reference (coverage_masks.hpp), compiled once per target.
// Built with -ffp-contract=off (CMakeLists.txt): dx*dx + dy*dy must round exactly as the
// scalar inside_grain() does, never as one fused multiply-add.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "physical/simd/coverage_masks_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <cmath>
#include <cstring>

#include "physical/coverage_masks.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::physical {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes hold the samples of the bin's class, the grain is broadcast: a class has a few to
// tens of samples, and a grain meets a few bins. The walk over grains and bins is the
// reference's, line for line.
void PaintCoverageMasks(const Grain* grains, std::size_t n, const MaskLayout& layout, const SampleClasses& classes,
                        MaskWord* masks) {
    static_assert(kClassPointPad == kMaskWordBits, "a padded group of class points fills one mask word");
    const hn::CappedTag<float, kClassPointPad> d;  // never wider than the padding
    const uint32_t lanes = uint32_t(hn::Lanes(d));
    const BinGrid grid = layout.grid;
    const std::size_t words = std::size_t(layout.words);
    // Local copies: the mask stores could alias the vectors' own fields otherwise, and the
    // compiler would reload them for every bin.
    const uint32_t* const row_class = layout.row_class.data();
    const uint32_t* const col_class = layout.col_class.data();
    const uint32_t* const begin = classes.begin.data();
    const uint32_t* const size = classes.size.data();
    const float* const class_lx = classes.lx.data();
    const float* const class_ly = classes.ly.data();
    for (std::size_t i = 0; i < n; i++) {
        const Grain g = grains[i];
        const BinRange b = bins_met_by(g, std::sqrt(g.r2), grid);
        const auto r2 = hn::Set(d, r2_in_bins(g.r2, grid.k));
        for (int64_t by = b.ly; by <= b.hy; by++) {
            const auto gy = hn::Set(d, bin_local(g.y * grid.k, by + grid.by0));
            MaskWord* const mask_row = masks + std::size_t(by * grid.nbx) * words;
            for (int64_t bx = b.lx; bx <= b.hx; bx++) {
                const auto gx = hn::Set(d, bin_local(g.x * grid.k, bx + grid.bx0));
                const uint32_t cls = row_class[by] + col_class[bx];
                const float* const lx = class_lx + begin[cls];
                const float* const ly = class_ly + begin[cls];
                MaskWord* const mask = mask_row + std::size_t(bx) * words;
                // A whole padded group of points per mask word, however many of them the
                // class fills: the group count is then the same for every class of a tile
                // (one when no class holds more than 16 points, as at ten bins per pixel),
                // where a loop over the class's own vectors ended at a different count from
                // bin to bin (5 to 13 points per class at r = 0.05), which the branch
                // predictor could not follow. Lanes past the class size read the padding,
                // NaN, which no grain covers.
                for (uint32_t j = 0, m = size[cls]; j < m; j += kMaskWordBits) {
                    uint32_t word = 0;
                    for (uint32_t v = 0; v < uint32_t(kMaskWordBits); v += lanes) {
                        const auto dx = hn::Sub(hn::LoadU(d, lx + j + v), gx);
                        const auto dy = hn::Sub(hn::LoadU(d, ly + j + v), gy);
                        const auto hit = hn::Le(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), r2);
                        uint8_t bytes[8] = {};
                        hn::StoreMaskBits(d, hit, bytes);
                        uint32_t bits;
                        std::memcpy(&bits, bytes, sizeof bits);  // little-endian, as on every target here
                        word |= bits << v;
                    }
                    mask[j / kMaskWordBits] |= MaskWord(word);
                }
            }
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::physical
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::physical {

HWY_EXPORT(PaintCoverageMasks);

void paint_coverage_masks_optimized(const Grain* grains, std::size_t n, const MaskLayout& layout,
                                    const SampleClasses& classes, MaskWord* masks) {
    HWY_DYNAMIC_DISPATCH(PaintCoverageMasks)(grains, n, layout, classes, masks);
}

}  // namespace filmgrain::physical
#endif  // HWY_ONCE

// Highway twin of coverage_mask_reference (coverage_masks.hpp), compiled once per target.
// Built with -ffp-contract=off (CMakeLists.txt): dx*dx + dy*dy must round exactly as the
// scalar inside_grain() does, never as one fused multiply-add.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "physical/simd/coverage_masks_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <algorithm>
#include <cstring>

#include "physical/coverage_masks.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::physical {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes hold samples, the grains are broadcast: a class has tens of samples and a bin a few
// grains, and a group of samples stops as soon as every lane is covered.
void CoverageMask(const BinnedGrain* grains, uint32_t n, const float* lx, const float* ly, uint32_t m,
                  uint64_t* mask, int words) {
    const hn::CappedTag<float, kClassPointPad> d;  // never wider than the padding
    const uint32_t lanes = uint32_t(hn::Lanes(d));
    std::fill(mask, mask + words, 0);
    // Bit j of the mask is bit j % 8 of byte j / 8 of the words (little-endian, as on every
    // target Highway dispatches to here).
    // Lanes past m read the padding, NaN, which no grain covers: their bits stay zero.
    uint8_t* bytes = reinterpret_cast<uint8_t*>(mask);
    for (uint32_t j = 0; j < m; j += lanes) {
        const auto px = hn::LoadU(d, lx + j), py = hn::LoadU(d, ly + j);
        auto hit = hn::Lt(px, px);  // all false (the padding is NaN)
        for (uint32_t i = 0; i < n; i++) {
            const auto dx = hn::Sub(px, hn::Set(d, grains[i].x));
            const auto dy = hn::Sub(py, hn::Set(d, grains[i].y));
            hit = hn::Or(hit, hn::Le(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Set(d, grains[i].r2)));
            if (hn::AllTrue(d, hit)) break;
        }
        uint8_t bits[8] = {};
        hn::StoreMaskBits(d, hit, bits);
        if (lanes >= 8) {
            std::memcpy(bytes + j / 8, bits, lanes / 8);
        } else {
            bytes[j / 8] = uint8_t(bytes[j / 8] | (bits[0] << (j % 8)));
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::physical
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::physical {

HWY_EXPORT(CoverageMask);

void coverage_mask_optimized(const BinnedGrain* grains, uint32_t n, const float* lx, const float* ly, uint32_t m,
                             uint64_t* mask, int words) {
    HWY_DYNAMIC_DISPATCH(CoverageMask)(grains, n, lx, ly, m, mask, words);
}

}  // namespace filmgrain::physical
#endif  // HWY_ONCE

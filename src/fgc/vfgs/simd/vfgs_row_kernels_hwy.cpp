// Highway twins of the VFGS row kernels (vfgs_row_kernels.hpp), compiled once per target
// (foreach_target) and dispatched at run time. The scalar references are in
// vfgs_row_kernels_scalar.cpp; tests/fgc/vfgs/vfgs_simd_equivalence_test.cpp holds them equal.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "fgc/vfgs/simd/vfgs_row_kernels_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "fgc/vfgs/vfgs_row_kernels.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::vfgs::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Every sample's 8-bit intensity (the look-up index of the reference) as int16 lanes.
template <class D>
HWY_INLINE hn::Vec<D> Intensity(D d, const uint8_t* in, int /*shift*/) {
    return hn::PromoteTo(d, hn::LoadU(hn::Rebind<uint8_t, D>(), in));
}
template <class D>
HWY_INLINE hn::Vec<D> Intensity(D d, const uint16_t* in, int shift) {
    const hn::RebindToUnsigned<D> du;
    // samples above the bit depth are clamped into the table, as the reference's min()
    return hn::BitCast(d, hn::Min(hn::ShiftRightSame(hn::LoadU(du, in), shift), hn::Set(du, uint16_t{255})));
}

// The grain of `block_count` blocks of one row. Lanes hold int16: the template samples
// (|t| <= 127) times the overlap weights (<= 24) sum to at most 6112 in magnitude.
// D has block_width lanes or a divisor of it (a narrower target runs a block in parts).
template <bool kOverlap, class D, typename In>
HWY_INLINE void GrainBlocks(D d, const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const hn::Rebind<int8_t, D> d8;
    const int n = static_cast<int>(hn::Lanes(d));
    const IntensityRuns& runs = *job.runs;
    const IntensityRun& first = runs.run[0];
    const auto round = hn::Set(d, int16_t{16});
    for (int b = 0; b < job.block_count; ++b) {
        const GrainBlock& blk = job.blocks[b];
        const int8_t* cur = job.pool + blk.offset;
        const int8_t* up = job.pool_up + blk.offset_up;
        const auto sign = hn::Set(d, static_cast<int16_t>(kOverlap ? blk.sign * job.overlap_c1 : blk.sign));
        const auto sign_up = hn::Set(d, static_cast<int16_t>(blk.sign_up * job.overlap_c2));
        for (int i = 0; i < job.block_width; i += n) {
            const int x = b * job.block_width + i;
            // The reference's two look-ups, as the last run starting at or below the intensity.
            auto g = hn::PromoteTo(d, hn::LoadU(d8, cur + first.tmpl * kTemplateBytes + i));
            auto gu = kOverlap ? hn::PromoteTo(d, hn::LoadU(d8, up + first.tmpl * kTemplateBytes + i)) : hn::Zero(d);
            auto sc = hn::Set(d, static_cast<int16_t>(first.scale));
            if (runs.count > 1) {
                const auto inten = Intensity(d, in + x, job.intensity_shift);
                for (int r = 1; r < runs.count; ++r) {
                    const IntensityRun& run = runs.run[r];
                    const IntensityRun& prev = runs.run[r - 1];
                    // all ones where inten >= run.start (>= 1): a vector, not a mask register,
                    // because GCC 12 fails on AVX-512 16-bit mask blends here ("could not split insn")
                    const auto m = hn::ShiftRight<15>(hn::Sub(hn::Set(d, static_cast<int16_t>(run.start - 1)), inten));
                    if (run.tmpl != prev.tmpl) {
                        const int32_t t = run.tmpl * kTemplateBytes + i;
                        g = hn::IfVecThenElse(m, hn::PromoteTo(d, hn::LoadU(d8, cur + t)), g);
                        if (kOverlap) gu = hn::IfVecThenElse(m, hn::PromoteTo(d, hn::LoadU(d8, up + t)), gu);
                    }
                    if (run.scale != prev.scale) sc = hn::IfVecThenElse(m, hn::Set(d, static_cast<int16_t>(run.scale)), sc);
                }
            }
            // overlap_blend(g * sign, gu * sign_up, c1, c2) with the signs folded into the weights
            const auto p = kOverlap ? hn::ShiftRight<5>(hn::Add(hn::Add(hn::Mul(g, sign), hn::Mul(gu, sign_up)), round))
                                    : hn::Mul(g, sign);
            hn::StoreU(p, d, grain + x);
            hn::StoreU(sc, d, scale + x);
        }
    }
}

template <typename In>
HWY_INLINE void GrainRow(const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const bool overlap = job.overlap_c1 != 0;
    if (job.block_width == 16) {
        const hn::CappedTag<int16_t, 16> d;
        if (overlap) GrainBlocks<true>(d, job, in, grain, scale);
        else GrainBlocks<false>(d, job, in, grain, scale);
    } else {
        const hn::CappedTag<int16_t, 8> d;
        if (overlap) GrainBlocks<true>(d, job, in, grain, scale);
        else GrainBlocks<false>(d, job, in, grain, scale);
    }
}

void GrainRowU8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale) {
    GrainRow(job, in, grain, scale);
}
void GrainRowU16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale) {
    GrainRow(job, in, grain, scale);
}

// Deblocking, scaling and blending in int32 lanes: the scale (<= 255) times the deblocked
// grain (|g| <= 143) can pass 32767, and 10-bit input may hold any 16-bit value.
template <bool kTo8Bit, typename In, typename Out>
HWY_INLINE void BlendRow(const BlendRowJob& job, const In* in, const int16_t* grain, const int16_t* scale, Out* out) {
    const hn::ScalableTag<int32_t> d;
    const hn::Rebind<int16_t, decltype(d)> d16;
    const hn::Rebind<In, decltype(d)> din;
    const hn::Rebind<Out, decltype(d)> dout;
    const int n = static_cast<int>(hn::Lanes(d));
    const auto zero = hn::Zero(d);
    const auto phase_mask = hn::Set(d, job.block_width - 1);  // block widths are powers of two
    const auto last_inner = hn::Set(d, job.padded_width - 1);
    const auto two = hn::Set(d, 2);
    const auto round = hn::Set(d, 1 << (job.shift - 1));
    const auto hi = hn::Set(d, 255 << (job.bit_depth - 8));
    auto idx = hn::Iota(d, 0);
    const auto step = hn::Set(d, n);
    int x = 0;
    for (; x + n <= job.width; x += n, idx = hn::Add(idx, step)) {
        const auto phase = hn::And(idx, phase_mask);
        const auto at_edge = hn::And(hn::Or(hn::Eq(phase, zero), hn::Eq(phase, phase_mask)),
                                     hn::And(hn::Ne(idx, zero), hn::Ne(idx, last_inner)));
        const auto gl = hn::PromoteTo(d, hn::LoadU(d16, grain + x - 1));
        const auto gc = hn::PromoteTo(d, hn::LoadU(d16, grain + x));
        const auto gr = hn::PromoteTo(d, hn::LoadU(d16, grain + x + 1));
        const auto filtered = hn::ShiftRight<2>(hn::Add(hn::Add(gl, gr), hn::Add(hn::Add(gc, hn::ShiftLeft<1>(gc)), two)));
        const auto g = hn::IfThenElse(at_edge, filtered, gc);
        const auto sc = hn::PromoteTo(d, hn::LoadU(d16, scale + x));
        const auto scaled = hn::ShiftRightSame(hn::Add(hn::Mul(sc, g), round), job.shift);
        auto v = hn::Min(hn::Max(hn::Add(hn::PromoteTo(d, hn::LoadU(din, in + x)), scaled), zero), hi);
        if (kTo8Bit) v = hn::ShiftRight<2>(hn::Add(v, two));  // to_8bit()
        hn::StoreU(hn::DemoteTo(dout, v), dout, out + x);
    }
    for (; x < job.width; ++x) {
        const int v = blend_sample(in[x], scale_grain(scale[x], deblocked_grain(job, grain, x), job.shift), job.bit_depth);
        out[x] = static_cast<Out>(kTo8Bit ? to_8bit(v) : v);
    }
}

void BlendRowU8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out) {
    BlendRow<false>(job, in, grain, scale, out);
}
void BlendRowU16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                 uint16_t* out) {
    BlendRow<false>(job, in, grain, scale, out);
}
void BlendRowU16ToU8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                     uint8_t* out) {
    BlendRow<true>(job, in, grain, scale, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::vfgs::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::vfgs::simd {

HWY_EXPORT(GrainRowU8);
HWY_EXPORT(GrainRowU16);
HWY_EXPORT(BlendRowU8);
HWY_EXPORT(BlendRowU16);
HWY_EXPORT(BlendRowU16ToU8);

void grain_row_u8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale) {
    HWY_DYNAMIC_DISPATCH(GrainRowU8)(job, in, grain, scale);
}
void grain_row_u16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale) {
    HWY_DYNAMIC_DISPATCH(GrainRowU16)(job, in, grain, scale);
}
void blend_row_u8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out) {
    HWY_DYNAMIC_DISPATCH(BlendRowU8)(job, in, grain, scale, out);
}
void blend_row_u16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                   uint16_t* out) {
    HWY_DYNAMIC_DISPATCH(BlendRowU16)(job, in, grain, scale, out);
}
void blend_row_u16_to_u8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                         uint8_t* out) {
    HWY_DYNAMIC_DISPATCH(BlendRowU16ToU8)(job, in, grain, scale, out);
}

}  // namespace filmgrain::vfgs::simd
#endif  // HWY_ONCE

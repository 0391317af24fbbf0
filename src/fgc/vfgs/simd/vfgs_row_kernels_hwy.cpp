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

// One boundary of the intensity runs, as the vector loop uses it.
struct RunStep {
    int16_t last_below = 0;      // run start - 1: lanes above it take this run
    int32_t tmpl_offset = 0;     // template index * kTemplateBytes
    int16_t scale = 0;
    bool new_tmpl = false, new_scale = false;  // what changes at this boundary
};

// The grain of `block_count` blocks of one row. Lanes hold int16: the template samples
// (|t| <= 127) times the overlap weights (<= 24) sum to at most 6112 in magnitude.
// D has block_width lanes or a divisor of it (a narrower target runs a block in parts).
// kRuns: the number of runs when known at compile time (the common 1..4), else 0.
template <bool kOverlap, int kRuns, class D, typename In>
HWY_NOINLINE void GrainBlocks(D d, const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const hn::Rebind<int8_t, D> d8;
    const int n = static_cast<int>(hn::Lanes(d));
    const IntensityRuns& runs = *job.runs;
    const int count = kRuns ? kRuns : runs.count;
    // Local copies: the compiler keeps them in registers across the blocks (the grain
    // stores cannot reach them).
    RunStep steps[kMaxVectorRuns];
    for (int r = 0; r < count; ++r) {
        const IntensityRun& run = runs.run[r];
        steps[r].last_below = static_cast<int16_t>(run.start - 1);
        steps[r].tmpl_offset = run.tmpl * kTemplateBytes;
        steps[r].scale = static_cast<int16_t>(run.scale);
        steps[r].new_tmpl = r > 0 && run.tmpl != runs.run[r - 1].tmpl;
        steps[r].new_scale = r > 0 && run.scale != runs.run[r - 1].scale;
    }
    // The job's fields in locals: the vector stores may alias anything, and would make
    // the compiler reload them for every block.
    const int8_t* const pool = job.pool;
    const int8_t* const pool_up = job.pool_up;
    const GrainBlock* const blocks = job.blocks;
    const int block_count = job.block_count, block_width = job.block_width, intensity_shift = job.intensity_shift;
    const int c1 = job.overlap_c1, c2 = job.overlap_c2;
    const auto round = hn::Set(d, int16_t{16});
    for (int b = 0; b < block_count; ++b) {
        const GrainBlock blk = blocks[b];
        const int8_t* cur = pool + blk.offset;
        const int8_t* up = pool_up + blk.offset_up;
        const auto sign = hn::Set(d, static_cast<int16_t>(kOverlap ? blk.sign * c1 : blk.sign));
        const auto sign_up = hn::Set(d, static_cast<int16_t>(blk.sign_up * c2));
        for (int i = 0; i < block_width; i += n) {
            const int x = b * block_width + i;
            // The reference's two look-ups, as the last run starting at or below the intensity.
            auto g = hn::PromoteTo(d, hn::LoadU(d8, cur + steps[0].tmpl_offset + i));
            auto gu = kOverlap ? hn::PromoteTo(d, hn::LoadU(d8, up + steps[0].tmpl_offset + i)) : hn::Zero(d);
            auto sc = hn::Set(d, steps[0].scale);
            if (count > 1) {
                const auto inten = Intensity(d, in + x, intensity_shift);
                for (int r = 1; r < count; ++r) {
                    const RunStep& st = steps[r];
                    // all ones where inten >= run start: a vector, not a mask register,
                    // because GCC 12 fails on AVX-512 16-bit mask blends here ("could not split insn")
                    const auto m = hn::ShiftRight<15>(hn::Sub(hn::Set(d, st.last_below), inten));
                    if (st.new_tmpl) {
                        g = hn::IfVecThenElse(m, hn::PromoteTo(d, hn::LoadU(d8, cur + st.tmpl_offset + i)), g);
                        if (kOverlap) gu = hn::IfVecThenElse(m, hn::PromoteTo(d, hn::LoadU(d8, up + st.tmpl_offset + i)), gu);
                    }
                    if (st.new_scale) sc = hn::IfVecThenElse(m, hn::Set(d, st.scale), sc);
                }
            }
            // overlap_blend(g * sign, gu * sign_up, c1, c2) with the signs folded into the weights
            const auto p = kOverlap ? hn::ShiftRight<5>(hn::Add(hn::Add(hn::Mul(g, sign), hn::Mul(gu, sign_up)), round))
                                    : hn::Mul(g, sign);
            hn::StoreU(p, d, grain + x);
            hn::StoreU(sc, d, scale + x);
        }
    }
// deblock_edge() at every inner block edge: [1 3 1] / 4 on the last sample before the
    // edge and the first after it, from unfiltered values (edges are >= 8 samples apart).
    for (int b = 1; b < block_count; ++b) {
        int16_t* e = grain + b * block_width;
        const int l1 = e[-2], l0 = e[-1], r0 = e[0], r1 = e[1];
        e[-1] = static_cast<int16_t>((l1 + 3 * l0 + r0 + 2) >> 2);
        e[0] = static_cast<int16_t>((l0 + 3 * r0 + r1 + 2) >> 2);
    }
}

template <bool kOverlap, class D, typename In>
HWY_INLINE void GrainBlocksForRuns(D d, const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    switch (job.runs->count) {
        case 1: return GrainBlocks<kOverlap, 1>(d, job, in, grain, scale);
        case 2: return GrainBlocks<kOverlap, 2>(d, job, in, grain, scale);
        case 3: return GrainBlocks<kOverlap, 3>(d, job, in, grain, scale);
        case 4: return GrainBlocks<kOverlap, 4>(d, job, in, grain, scale);
        default: return GrainBlocks<kOverlap, 0>(d, job, in, grain, scale);
    }
}

template <typename In>
HWY_INLINE void GrainRow(const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const bool overlap = job.overlap_c1 != 0;
    if (job.block_width == 16) {
        const hn::CappedTag<int16_t, 16> d;
        if (overlap) GrainBlocksForRuns<true>(d, job, in, grain, scale);
        else GrainBlocksForRuns<false>(d, job, in, grain, scale);
    } else {
        const hn::CappedTag<int16_t, 8> d;
        if (overlap) GrainBlocksForRuns<true>(d, job, in, grain, scale);
        else GrainBlocksForRuns<false>(d, job, in, grain, scale);
    }
}

void GrainRowU8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale) {
    GrainRow(job, in, grain, scale);
}
void GrainRowU16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale) {
    GrainRow(job, in, grain, scale);
}

// Scaling and blending in int32 lanes, from sample `x` on: the scale (<= 255) times the
// grain (|g| <= 159) can pass 32767, and 10-bit input may hold any 16-bit value (8 bits take
// BlendRowU8Int16 first, below).
template <bool kTo8Bit, typename In, typename Out>
HWY_INLINE void BlendRow(const BlendRowJob& job, const In* in, const int16_t* grain, const int16_t* scale, Out* out,
                         int x = 0) {
    const hn::ScalableTag<int32_t> d;
    const hn::Rebind<int16_t, decltype(d)> d16;
    const hn::Rebind<In, decltype(d)> din;
    const hn::Rebind<Out, decltype(d)> dout;
    const int n = static_cast<int>(hn::Lanes(d));
    const auto zero = hn::Zero(d);
    const auto two = hn::Set(d, 2);
    const auto round = hn::Set(d, 1 << (job.shift - 1));
    const auto hi = hn::Set(d, 255 << (job.bit_depth - 8));
    for (; x + n <= job.width; x += n) {
        const auto g = hn::PromoteTo(d, hn::LoadU(d16, grain + x));
        const auto sc = hn::PromoteTo(d, hn::LoadU(d16, scale + x));
        const auto scaled = hn::ShiftRightSame(hn::Add(hn::Mul(sc, g), round), job.shift);
        auto v = hn::Min(hn::Max(hn::Add(hn::PromoteTo(d, hn::LoadU(din, in + x)), scaled), zero), hi);
        if (kTo8Bit) v = hn::ShiftRight<2>(hn::Add(v, two));  // to_8bit()
        hn::StoreU(hn::DemoteTo(dout, v), dout, out + x);
    }
    for (; x < job.width; ++x) {
        const int v = blend_sample(in[x], scale_grain(scale[x], grain[x], job.shift), job.bit_depth);
        out[x] = static_cast<Out>(kTo8Bit ? to_8bit(v) : v);
    }
}

// 8 bits in int16 lanes, twice as many per vector: there scale_shift() is 8..13
// (log2_scale_factor - model_id is 2..7), and from a shift of 8 on the scaled value of any
// int16 grain (255 * 32768 >> 8) fits int16. The product's two halves (pmullw, pmulhw),
// with the rounding's carry into the high one, give the int32 product's shift exactly; the
// sum with the sample saturates where the 0..255 clip would cut it anyway. Returns where the
// remaining samples start.
HWY_INLINE int BlendRowU8Int16(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale,
                               uint8_t* out) {
    const hn::ScalableTag<int16_t> d;
    const hn::RebindToUnsigned<decltype(d)> du;
    const hn::Rebind<uint8_t, decltype(d)> d8;
    const int n = static_cast<int>(hn::Lanes(d));
    const int shift = job.shift;
    const auto round = hn::Set(du, static_cast<uint16_t>(1u << (shift - 1)));
    int x = 0;
    for (; x + n <= job.width; x += n) {
        const auto g = hn::LoadU(d, grain + x);
        const auto sc = hn::LoadU(d, scale + x);
        const auto low = hn::Add(hn::BitCast(du, hn::Mul(sc, g)), round);
        // all ones (-1) where the low half wrapped: the carry, subtracted
        const auto carry = hn::BitCast(d, hn::VecFromMask(du, hn::Lt(low, round)));
        const auto high = hn::Sub(hn::MulHigh(sc, g), carry);
        const auto scaled = hn::Or(hn::BitCast(d, hn::ShiftRightSame(low, shift)), hn::ShiftLeftSame(high, 16 - shift));
        const auto sample = hn::BitCast(d, hn::PromoteTo(du, hn::LoadU(d8, in + x)));
        hn::StoreU(hn::DemoteTo(d8, hn::SaturatedAdd(sample, scaled)), d8, out + x);
    }
    return x;
}

void BlendRowU8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out) {
    const int from = job.bit_depth == 8 && job.shift >= 8 && job.shift <= 15
                         ? BlendRowU8Int16(job, in, grain, scale, out)
                         : 0;
    BlendRow<false>(job, in, grain, scale, out, from);
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

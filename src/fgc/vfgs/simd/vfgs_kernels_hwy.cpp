// Highway twins of the VFGS row kernels (vfgs_row_kernels.hpp) and of block_grains()
// (vfgs_block_grains.hpp), compiled once per target (foreach_target) and dispatched at run
// time. The scalar references are in vfgs_row_kernels_scalar.cpp and
// vfgs_block_grains_scalar.cpp; tests/fgc/vfgs/vfgs_simd_equivalence_test.cpp and
// vfgs_block_grains_test.cpp hold them equal.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "fgc/vfgs/simd/vfgs_kernels_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "fgc/vfgs/vfgs_block_grains.hpp"
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

// The run steps of `runs` in the form the vector loops read, kept in the caller's locals
// (registers across the blocks: the vector stores cannot reach them). Returns the count.
HWY_INLINE int RunSteps(const IntensityRuns& runs, int known_count, RunStep* steps) {
    const int count = known_count ? known_count : runs.count;
    for (int r = 0; r < count; ++r) {
        const IntensityRun& run = runs.run[r];
        steps[r].last_below = static_cast<int16_t>(run.start - 1);
        steps[r].tmpl_offset = run.tmpl * kTemplateBytes;
        steps[r].scale = static_cast<int16_t>(run.scale);
        steps[r].new_tmpl = r > 0 && run.tmpl != runs.run[r - 1].tmpl;
        steps[r].new_scale = r > 0 && run.scale != runs.run[r - 1].scale;
    }
    return count;
}

// The reference's two look-ups (template and scale) for each lane, as the last run
// starting at or below the lane's intensity. load(t) / load_up(t): the template rows of the
// block and of the block above at template offset t, as int16 lanes.
template <bool kOverlap, class D, class Load, class LoadUp>
HWY_INLINE void PickRuns(D d, const RunStep* steps, int count, hn::Vec<D> inten, const Load& load,
                         const LoadUp& load_up, hn::Vec<D>& g, hn::Vec<D>& gu, hn::Vec<D>& sc) {
    g = load(steps[0].tmpl_offset);
    gu = kOverlap ? load_up(steps[0].tmpl_offset) : hn::Zero(d);
    sc = hn::Set(d, steps[0].scale);
    for (int r = 1; r < count; ++r) {
        const RunStep& st = steps[r];
        // all ones where inten >= run start: a vector, not a mask register,
        // because GCC 12 fails on AVX-512 16-bit mask blends here ("could not split insn")
        const auto m = hn::ShiftRight<15>(hn::Sub(hn::Set(d, st.last_below), inten));
        if (st.new_tmpl) {
            g = hn::IfVecThenElse(m, load(st.tmpl_offset), g);
            if (kOverlap) gu = hn::IfVecThenElse(m, load_up(st.tmpl_offset), gu);
        }
        if (st.new_scale) sc = hn::IfVecThenElse(m, hn::Set(d, st.scale), sc);
    }
}

// The picked template samples with their block's sign, and on the overlap rows
// overlap_blend(g * sign, gu * sign_up, c1, c2) with the signs folded into the weights.
template <bool kOverlap, class V>
HWY_INLINE V SignedGrain(V g, V gu, V sign, V sign_up, V round) {
    return kOverlap ? hn::ShiftRight<5>(hn::Add(hn::Add(hn::Mul(g, sign), hn::Mul(gu, sign_up)), round))
                    : hn::Mul(g, sign);
}

// The grain of `block_count` blocks of one row. Lanes hold int16: the template samples
// (|t| <= 127) times the overlap weights (<= 24) sum to at most 6112 in magnitude.
// D has block_width lanes or a divisor of it (a narrower target runs a block in parts).
// kRuns: the number of runs when known at compile time (the common 1..4), else 0.
template <bool kOverlap, int kRuns, class D, typename In>
HWY_NOINLINE void GrainBlocks(D d, const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const hn::Rebind<int8_t, D> d8;
    const int n = static_cast<int>(hn::Lanes(d));
    const IntensityRuns& runs = *job.runs;
    RunStep steps[kMaxVectorRuns];
    const int count = RunSteps(runs, kRuns, steps);
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
            const auto inten = count > 1 ? Intensity(d, in + x, intensity_shift) : hn::Zero(d);
            hn::Vec<D> g, gu, sc;
            PickRuns<kOverlap>(
                d, steps, count, inten, [&](int32_t t) { return hn::PromoteTo(d, hn::LoadU(d8, cur + t + i)); },
                [&](int32_t t) { return hn::PromoteTo(d, hn::LoadU(d8, up + t + i)); }, g, gu, sc);
            hn::StoreU(SignedGrain<kOverlap>(g, gu, sign, sign_up, round), d, grain + x);
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

// Scaling and blending in int32 lanes, from sample `x` on, for any int16 grain and shift
// and any 16-bit sample: the samples the int16 forms below (BlendRowU8Int16,
// BlendRowU16Int16) leave at the end of a row, and the shifts they do not take.
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

// scale_grain() in int16 lanes, for shifts of 8..15: one rounding high multiply
// (pmulhrsw) with the scale moved up to q15, (sc << (15 - shift)) * g + 2^14 >> 15, which is
// (sc * g + 2^(shift - 1)) >> shift exactly: the scale (<= 255) shifted by at most 7 still
// fits int16, and the product is formed in 32 bits.
template <class D>
HWY_INLINE hn::Vec<D> ScaledGrainInt16(D /*d*/, hn::Vec<D> g, hn::Vec<D> sc, int shift) {
    return hn::MulFixedPoint15(hn::ShiftLeftSame(sc, 15 - shift), g);
}

// Whether ScaledGrainInt16 takes the job's scaling: 8-bit samples, a shift of 8..15.
HWY_INLINE bool ScalesInInt16(const BlendRowJob& job) { return job.bit_depth == 8 && job.shift >= 8 && job.shift <= 15; }

// 8 bits in int16 lanes, twice as many per vector: there scale_shift() is 8..13
// (log2_scale_factor - model_id is 2..7; ScaledGrainInt16). The sum with the sample
// saturates where the 0..255 clip would cut it anyway. Returns where the remaining samples
// start.
HWY_INLINE int BlendRowU8Int16(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale,
                               uint8_t* out) {
    const hn::ScalableTag<int16_t> d;
    const hn::RebindToUnsigned<decltype(d)> du;
    const hn::Rebind<uint8_t, decltype(d)> d8;
    const int n = static_cast<int>(hn::Lanes(d));
    const int shift = job.shift;
    int x = 0;
    for (; x + n <= job.width; x += n) {
        const auto sample = hn::BitCast(d, hn::PromoteTo(du, hn::LoadU(d8, in + x)));
        const auto scaled = ScaledGrainInt16(d, hn::LoadU(d, grain + x), hn::LoadU(d, scale + x), shift);
        hn::StoreU(hn::DemoteTo(d8, hn::SaturatedAdd(sample, scaled)), d8, out + x);
    }
    return x;
}

// 10 bits in int16 lanes as well. There scale_shift() is 6..11, so the 15 - shift bits that
// take the product to q15 can exceed the 7 the scale (<= 255) has room for; the rest move
// the grain up, which kMaxBlendGrain << 7 leaves room for, and one pmulhrsw again gives
// (sc * g + 2^(shift - 1)) >> shift exactly. Samples are capped at kSampleCap first: a
// sample at or above it ends at the top of the clip either way, as |scaled| <= 255 * 255 >> 6
// keeps the sum above 1020.
struct Q15Shifts {
    int scale_up, grain_up;
};
HWY_INLINE Q15Shifts Q15ShiftsOf(const BlendRowJob& job) {
    const int up = 15 - job.shift;
    return up < 7 ? Q15Shifts{up, 0} : Q15Shifts{7, up - 7};
}
constexpr uint16_t kSampleCap = 32767;
static_assert(kMaxBlendGrain << 7 <= 32767 && kSampleCap - (255 * kMaxBlendGrain >> 6) > 1020);

// The blend in that form; returns where the remaining samples start.
template <bool kTo8Bit, typename Out>
HWY_INLINE int BlendRowU16Int16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain,
                                const int16_t* scale, Out* out) {
    const hn::ScalableTag<int16_t> d;
    const hn::RebindToUnsigned<decltype(d)> du;
    const hn::Rebind<Out, decltype(d)> dout;
    const int n = static_cast<int>(hn::Lanes(d));
    // plain ints, not a structured binding: lambdas capture them (clang before 16 cannot)
    const Q15Shifts shifts = Q15ShiftsOf(job);
    const int scale_up = shifts.scale_up, grain_up = shifts.grain_up;
    const auto cap = hn::Set(du, kSampleCap);
    const auto hi = hn::Set(d, static_cast<int16_t>(255 << (job.bit_depth - 8)));
    const auto zero = hn::Zero(d), two = hn::Set(d, int16_t{2});
    int x = 0;
    for (; x + n <= job.width; x += n) {
        const auto scaled = hn::MulFixedPoint15(hn::ShiftLeftSame(hn::LoadU(d, scale + x), scale_up),
                                                hn::ShiftLeftSame(hn::LoadU(d, grain + x), grain_up));
        const auto sample = hn::BitCast(d, hn::Min(hn::LoadU(du, in + x), cap));
        auto v = hn::Min(hn::Max(hn::SaturatedAdd(sample, scaled), zero), hi);
        if constexpr (kTo8Bit) {
            hn::StoreU(hn::DemoteTo(dout, hn::ShiftRight<2>(hn::Add(v, two))), dout, out + x);  // to_8bit()
        } else {
            hn::StoreU(hn::BitCast(dout, v), dout, out + x);
        }
    }
    return x;
}

// Whether BlendRowU16Int16 takes the job: 10 bits with a shift of 6..15 (scale_shift()
// gives 6..11).
HWY_INLINE bool BlendsU16InInt16(const BlendRowJob& job) {
    return job.bit_depth == 10 && job.shift >= 6 && job.shift <= 15;
}

void BlendRowU8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out) {
    const int from = ScalesInInt16(job) ? BlendRowU8Int16(job, in, grain, scale, out) : 0;
    BlendRow<false>(job, in, grain, scale, out, from);
}
void BlendRowU16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                 uint16_t* out) {
    const int from = BlendsU16InInt16(job) ? BlendRowU16Int16<false>(job, in, grain, scale, out) : 0;
    BlendRow<false>(job, in, grain, scale, out, from);
}
void BlendRowU16ToU8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                     uint8_t* out) {
    const int from = BlendsU16InInt16(job) ? BlendRowU16Int16<true>(job, in, grain, scale, out) : 0;
    BlendRow<true>(job, in, grain, scale, out, from);
}

// grain_row and blend_row in one pass over 8-bit or 10-bit rows (10-bit ones also to 8-bit
// output, --outdepth 8), with no grain or scale
// written to memory and read back, and no scalar edge loop: on a Zen 3 (AVX2) that took an
// 8-bit 1080p frame on one thread from 2.09-2.51 to 1.70-1.89 ms (4 interleaved rounds,
// docs/performance-notes.md). The grain of a
// 256-bit vector (one 16-wide block or two 8-wide ones) is scaled and blended once the
// vector after it is known, since the deblocking of an edge reads two samples either
// side (deblock_edge(), from unfiltered values). Needs whole 256-bit vectors of int16,
// a row of whole vectors and blocks (width = block_count * block_width), and a shift
// the int16 scaling takes (ScalesInInt16, BlendsU16InInt16).
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
#define FILMGRAIN_VFGS_FUSED_ROW 1

// The unfiltered grain of a vector's blocks (one 16-wide block or two 8-wide ones), its
// scales and its samples (10 bits: capped at kSampleCap, as in BlendRowU16Int16).
struct FusedVector {
    hn::Vec<hn::Full256<int16_t>> grain, scale, sample;
};

template <bool kOverlap, int kRuns, int kBlockWidth, typename In, typename Out>
HWY_NOINLINE void GrainBlendBlocks(const GrainRowJob& job, const BlendRowJob& blend, const In* in, Out* out) {
    constexpr bool k8Bit = sizeof(In) == 1;
    const hn::Full256<int16_t> d;
    const hn::Half<decltype(d)> dh;
    const hn::RebindToUnsigned<decltype(d)> du;
    const hn::Full128<int8_t> d8;
    const hn::Full64<int8_t> d8h;
    const hn::Full128<uint8_t> du8;
    constexpr int kLanes = 16;
    RunStep steps[kMaxVectorRuns];
    const int count = RunSteps(*job.runs, kRuns, steps);
    // 10 bits: BlendRowU16Int16's split of the q15 shift, the scale's part applied to the
    // runs' scales here, once.
    const Q15Shifts shifts = Q15ShiftsOf(blend);  // as plain ints, for the lambdas (see above)
    const int scale_up = shifts.scale_up, grain_up = shifts.grain_up;
    if constexpr (!k8Bit)
        for (int r = 0; r < count; ++r) steps[r].scale = static_cast<int16_t>(steps[r].scale << scale_up);
    const auto cap = hn::Set(du, kSampleCap);
    const auto hi = hn::Set(d, static_cast<int16_t>(255 << (blend.bit_depth - 8)));
    const int8_t* const pool = job.pool;
    const int8_t* const pool_up = job.pool_up;
    const GrainBlock* const blocks = job.blocks;
    const int16_t c1 = static_cast<int16_t>(job.overlap_c1), c2 = static_cast<int16_t>(job.overlap_c2);
    const int vectors = job.block_count * kBlockWidth / kLanes;
    const int shift = blend.shift;
    const auto round = hn::Set(d, int16_t{16});

    // Template rows of the vector's blocks at template offset t: for two 8-wide blocks,
    // each from its own place.
    const auto rows = [&](const int8_t* base, int32_t off0, int32_t off1, int32_t t) {
        if constexpr (kBlockWidth == 16) return hn::PromoteTo(d, hn::LoadU(d8, base + off0 + t));
        else return hn::PromoteTo(d, hn::Combine(d8, hn::LoadU(d8h, base + off1 + t), hn::LoadU(d8h, base + off0 + t)));
    };
    const auto per_block = [&](int16_t w0, int16_t w1) {
        if constexpr (kBlockWidth == 16) return hn::Set(d, w0);
        else return hn::Combine(d, hn::Set(dh, w1), hn::Set(dh, w0));
    };
    const auto load_vector = [&](int v) {
        const GrainBlock& b0 = blocks[v * kLanes / kBlockWidth];
        const GrainBlock& b1 = kBlockWidth == 16 ? b0 : blocks[v * kLanes / kBlockWidth + 1];
        FusedVector r;
        hn::Vec<decltype(d)> inten;
        if constexpr (k8Bit) {
            r.sample = hn::BitCast(d, hn::PromoteTo(du, hn::LoadU(du8, in + v * kLanes)));
            inten = r.sample;
        } else {
            const auto raw = hn::LoadU(du, in + v * kLanes);
            r.sample = hn::BitCast(d, hn::Min(raw, cap));
            inten = hn::BitCast(d, hn::Min(hn::ShiftRight<2>(raw), hn::Set(du, uint16_t{255})));  // Intensity()
        }
        hn::Vec<decltype(d)> g, gu;
        PickRuns<kOverlap>(
            d, steps, count, inten, [&](int32_t t) { return rows(pool, b0.offset, b1.offset, t); },
            [&](int32_t t) { return rows(pool_up, b0.offset_up, b1.offset_up, t); }, g, gu, r.scale);
        const int16_t s0 = static_cast<int16_t>(b0.sign), s1 = static_cast<int16_t>(b1.sign);
        const auto sign = kOverlap ? per_block(static_cast<int16_t>(s0 * c1), static_cast<int16_t>(s1 * c1))
                                   : per_block(s0, s1);
        const auto sign_up = kOverlap ? per_block(static_cast<int16_t>(b0.sign_up * c2),
                                                  static_cast<int16_t>(b1.sign_up * c2))
                                      : hn::Zero(d);
        r.grain = SignedGrain<kOverlap>(g, gu, sign, sign_up, round);
        return r;
    };

    // Lanes next to a block edge (deblock_edge() changes them), except the row's first and
    // last sample, which have no edge.
    const auto lane = hn::Iota(d, 0);
    const auto in_block = hn::And(lane, hn::Set(d, int16_t{kBlockWidth - 1}));
    const auto edge = hn::VecFromMask(d, hn::Or(hn::Eq(in_block, hn::Zero(d)),
                                                hn::Eq(in_block, hn::Set(d, int16_t{kBlockWidth - 1}))));
    const auto first_lane = hn::VecFromMask(d, hn::Eq(lane, hn::Zero(d)));
    const auto last_lane = hn::VecFromMask(d, hn::Eq(lane, hn::Set(d, int16_t{kLanes - 1})));
    const auto two = hn::Set(d, int16_t{2});

    // Deblocks, scales and blends vector v. before: [grain of v-1's upper half, v's lower
    // half]; after: [v's upper half, v+1's lower half].
    const auto finish = [&](int v, const FusedVector& c, hn::Vec<decltype(d)> before,
                            hn::Vec<decltype(d)> after) {
        const auto left = hn::CombineShiftRightBytes<14>(d, c.grain, before);  // each lane's left neighbour
        const auto right = hn::CombineShiftRightBytes<2>(d, after, c.grain);   // and its right one
        const auto filtered =
            hn::ShiftRight<2>(hn::Add(hn::Add(left, right), hn::Add(hn::Add(c.grain, c.grain), hn::Add(c.grain, two))));
        auto mask = edge;
        if (v == 0) mask = hn::AndNot(first_lane, mask);
        if (v == vectors - 1) mask = hn::AndNot(last_lane, mask);
        const auto g = hn::IfVecThenElse(mask, filtered, c.grain);
        if constexpr (k8Bit) {
            const auto scaled = ScaledGrainInt16(d, g, c.scale, shift);
            hn::StoreU(hn::DemoteTo(du8, hn::SaturatedAdd(c.sample, scaled)), du8, out + v * kLanes);
        } else {
            const auto scaled = hn::MulFixedPoint15(c.scale, hn::ShiftLeftSame(g, grain_up));
            const auto sum = hn::Min(hn::Max(hn::SaturatedAdd(c.sample, scaled), hn::Zero(d)), hi);
            if constexpr (sizeof(Out) == 1)
                hn::StoreU(hn::DemoteTo(du8, hn::ShiftRight<2>(hn::Add(sum, two))), du8, out + v * kLanes);  // to_8bit()
            else
                hn::StoreU(hn::BitCast(du, sum), du, out + v * kLanes);
        }
    };

    // Each vector is finished once the next one is loaded, which also makes out == in safe.
    auto cur = load_vector(0);
    auto before = hn::ConcatLowerUpper(d, cur.grain, hn::Zero(d));
    for (int v = 1; v < vectors; ++v) {
        const auto next = load_vector(v);
        const auto after = hn::ConcatLowerUpper(d, next.grain, cur.grain);
        finish(v - 1, cur, before, after);
        before = after;
        cur = next;
    }
    finish(vectors - 1, cur, before, hn::ConcatLowerUpper(d, hn::Zero(d), cur.grain));
}

template <bool kOverlap, int kBlockWidth, typename In, typename Out>
HWY_INLINE void GrainBlendForRuns(const GrainRowJob& job, const BlendRowJob& blend, const In* in, Out* out) {
    switch (job.runs->count) {
        case 1: return GrainBlendBlocks<kOverlap, 1, kBlockWidth>(job, blend, in, out);
        case 2: return GrainBlendBlocks<kOverlap, 2, kBlockWidth>(job, blend, in, out);
        case 3: return GrainBlendBlocks<kOverlap, 3, kBlockWidth>(job, blend, in, out);
        case 4: return GrainBlendBlocks<kOverlap, 4, kBlockWidth>(job, blend, in, out);
        default: return GrainBlendBlocks<kOverlap, 0, kBlockWidth>(job, blend, in, out);
    }
}
#endif

template <typename In, typename Out>
HWY_INLINE bool GrainBlendRow(const GrainRowJob& job, const BlendRowJob& blend, const In* in, Out* out) {
#ifdef FILMGRAIN_VFGS_FUSED_ROW
    const int width = job.block_count * job.block_width;
    const bool scales = sizeof(In) == 1 ? ScalesInInt16(blend) && job.intensity_shift == 0
                                           : BlendsU16InInt16(blend) && job.intensity_shift == 2;
    if (!scales || (job.block_width != 16 && job.block_width != 8) || width != blend.width || width == 0 ||
        width % 16 != 0)
        return false;
    const bool overlap = job.overlap_c1 != 0;
    if (job.block_width == 16) overlap ? GrainBlendForRuns<true, 16>(job, blend, in, out)
                                       : GrainBlendForRuns<false, 16>(job, blend, in, out);
    else overlap ? GrainBlendForRuns<true, 8>(job, blend, in, out) : GrainBlendForRuns<false, 8>(job, blend, in, out);
    return true;
#else
    (void)job, (void)blend, (void)in, (void)out;
    return false;
#endif
}
#undef FILMGRAIN_VFGS_FUSED_ROW

bool GrainBlendRowU8(const GrainRowJob& job, const BlendRowJob& blend, const uint8_t* in, uint8_t* out) {
    return GrainBlendRow(job, blend, in, out);
}
bool GrainBlendRowU16(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint16_t* out) {
    return GrainBlendRow(job, blend, in, out);
}
bool GrainBlendRowU16ToU8(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint8_t* out) {
    return GrainBlendRow(job, blend, in, out);
}

// The bit fields of one component (vfgs_random.hpp). Every 10-bit field is the register
// rotated right by some count and masked: Cb's vertical field takes R[31:24] with R[1:0]
// above them, which is R rotated by 24; the other fields never wrap.
struct Fields {
    int sign_bit, x_rotate, y_rotate;
    uint32_t x_unit, y_unit;  // 4 / subsampling
};

Fields FieldsOf(const BlockGrainsJob& job) {
    const uint32_t ux = 4u >> (job.subx - 1), uy = 4u >> (job.suby - 1);
    switch (job.component) {
        case 0: return {31, 0, 14, 4, 4};
        case 1: return {2, 10, 24, ux, uy};
        default: return {15, 20, 4, ux, uy};
    }
}

template <class D>
HWY_INLINE hn::Vec<D> RotateRight(D /*d*/, hn::Vec<D> r, int count) {
    return count ? hn::Or(hn::ShiftRightSame(r, count), hn::ShiftLeftSame(r, 32 - count)) : r;
}

// (offset, sign) of each lane's register value: bin_of(field, bins) = field * bins >> 10.
template <class D>
HWY_INLINE void OffsetsAndSigns(D d, const Fields& f, hn::Vec<D> r, hn::Vec<D>& offset, hn::Vec<D>& sign) {
    const auto field = hn::Set(d, 0x3FFu);
    const auto x = hn::ShiftRight<10>(hn::Mul(hn::And(RotateRight(d, r, f.x_rotate), field), hn::Set(d, 13u)));
    const auto y = hn::ShiftRight<10>(hn::Mul(hn::And(RotateRight(d, r, f.y_rotate), field), hn::Set(d, 12u)));
    offset = hn::Add(hn::Mul(y, hn::Set(d, f.y_unit * kTemplatePitch)), hn::Mul(x, hn::Set(d, f.x_unit)));
    // +1, or -1 (all ones) where the sign bit is set
    const auto bit = hn::And(hn::ShiftRightSame(r, f.sign_bit), hn::Set(d, 1u));
    sign = hn::Sub(hn::Set(d, 1u), hn::Add(bit, bit));
}

void BlockGrains(const BlockGrainsJob& job, GrainBlock* out) {
    static_assert(sizeof(GrainBlock) == 4 * sizeof(uint32_t), "GrainBlock is four 32-bit fields, stored interleaved");
    const hn::ScalableTag<uint32_t> d;
    const int n = static_cast<int>(hn::Lanes(d));
    const Fields f = FieldsOf(job);
    int b = 0;
    for (; b + n <= job.count; b += n) {
        hn::Vec<decltype(d)> offset, sign, offset_up, sign_up;
        OffsetsAndSigns(d, f, hn::LoadU(d, job.states + b), offset, sign);
        OffsetsAndSigns(d, f, hn::LoadU(d, job.states_up + b), offset_up, sign_up);
        // GrainBlock's field order: offset, offset_up, sign, sign_up
        hn::StoreInterleaved4(offset, offset_up, sign, sign_up, d, reinterpret_cast<uint32_t*>(out + b));
    }
    if (b < job.count) {
        BlockGrainsJob rest = job;
        rest.states += b;
        rest.states_up += b;
        rest.count -= b;
        scalar::block_grains(rest, out + b);
    }
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
HWY_EXPORT(GrainBlendRowU8);
HWY_EXPORT(GrainBlendRowU16);
HWY_EXPORT(GrainBlendRowU16ToU8);
HWY_EXPORT(BlockGrains);

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

bool grain_blend_row_u8(const GrainRowJob& job, const BlendRowJob& blend, const uint8_t* in, uint8_t* out) {
    return HWY_DYNAMIC_DISPATCH(GrainBlendRowU8)(job, blend, in, out);
}
bool grain_blend_row_u16(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint16_t* out) {
    return HWY_DYNAMIC_DISPATCH(GrainBlendRowU16)(job, blend, in, out);
}
bool grain_blend_row_u16_to_u8(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint8_t* out) {
    return HWY_DYNAMIC_DISPATCH(GrainBlendRowU16ToU8)(job, blend, in, out);
}

void block_grains(const BlockGrainsJob& job, GrainBlock* out) { HWY_DYNAMIC_DISPATCH(BlockGrains)(job, out); }

}  // namespace filmgrain::vfgs::simd
#endif  // HWY_ONCE

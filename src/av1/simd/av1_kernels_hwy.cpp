// Highway implementations of av1_kernels.hpp, compiled once per target (foreach_target).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "av1/simd/av1_kernels_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <type_traits>

#include "av1/simd/av1_kernels.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::av1::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// 16-bit lanes, at most 16: a block row (16 or 32 samples) is then whole vectors on every
// target, and a vector never spans two blocks.
using D16 = hn::CappedTag<int16_t, 16>;
using D32 = hn::CappedTag<int32_t, 8>;  // as many lanes as D16 has, or half
// The loops below are lambdas instantiated per form of the overlap; GCC otherwise keeps some
// of them out of line (8 bits went from 1.02 to 1.48 ms per frame that way).
#define FG_INLINE_LAMBDA __attribute__((always_inline))
constexpr int kChunk = 256;             // samples looked up at once

// Constants of the horizontal overlap fade, made once per row. The weights of lanes 2 and up
// are (0, 32): there the fade below gives back the block's own noise, (32 * own + 16) >> 5,
// already within the grain range, so no blend puts lanes 0 and 1 back into it.
struct FadeConstants {
    hn::Vec<D16> w_old, w_new, gmin, gmax, round;  // round: 1 << 10, FirstNoiseOfBlock's Round2
};

HWY_INLINE FadeConstants FadeConstantsOf(const BlockNoiseRow& row) {
    const D16 d16;
    const hn::Repartition<uint32_t, D16> d32;
    auto pair = [](int16_t a, int16_t b) { return uint32_t(uint16_t(a)) | uint32_t(uint16_t(b)) << 16; };
    const auto first_two = hn::FirstN(d16, 2);
    return {hn::IfThenElseZero(first_two, hn::BitCast(d16, hn::Set(d32, pair(row.fade_old[0], row.fade_old[1])))),
            hn::IfThenElse(first_two, hn::BitCast(d16, hn::Set(d32, pair(row.fade_new[0], row.fade_new[1]))),
                           hn::Set(d16, int16_t(32))),
            hn::Set(d16, row.gmin), hn::Set(d16, row.gmax), hn::Set(d16, int16_t(1 << 10))};
}

// The first vector of block b's noise: its first two lanes replaced by the horizontal overlap
// with the left block (7.18.3.5), given as seams or faded here. At least two lanes. The
// fade's Round2(sum, 5) is a rounding high multiply by 1 << 10; the sums fit 16 bits up to
// 10 bits (|noise| <= 512, weights summing to at most 45), the depths that fade here.
HWY_INLINE hn::Vec<D16> SeamOfBlock(D16 d16, const BlockNoiseRow& row, int b, hn::Vec<D16> own) {
    const hn::Repartition<uint32_t, D16> d32;
    return hn::IfThenElse(hn::FirstN(d16, 2), hn::BitCast(d16, hn::Set(d32, row.seams[b])), own);
}
HWY_INLINE hn::Vec<D16> FadeOfBlock(D16 d16, const BlockNoiseRow& row, int b, hn::Vec<D16> own,
                                    const FadeConstants& c) {
    const hn::Repartition<uint32_t, D16> d32;
    uint32_t left_pair;
    std::memcpy(&left_pair, row.block(b - 1) + row.block_width, sizeof left_pair);
    const auto left = hn::BitCast(d16, hn::Set(d32, left_pair));
    const auto sum = hn::Add(hn::Mul(left, c.w_old), hn::Mul(own, c.w_new));
    return hn::Min(hn::Max(hn::MulFixedPoint15(sum, c.round), c.gmin), c.gmax);
}
HWY_INLINE hn::Vec<D16> FirstNoiseOfBlock(D16 d16, const BlockNoiseRow& row, int b, hn::Vec<D16> own,
                                          const FadeConstants& c) {
    if (row.seams) return SeamOfBlock(d16, row, b, own);
    if (!row.fade || b == 0) return own;
    return FadeOfBlock(d16, row, b, own, c);
}

// Calls body(first_of_block), first_of_block(b, own) being FirstNoiseOfBlock with the
// overlap's form (seams, fade or none) decided here, once per row, instead of per block.
template <class Body>
HWY_INLINE void WithFirstOfBlock(const BlockNoiseRow& row, const FadeConstants& fade, Body&& body) {
    const D16 d16;
    if (row.seams)
        body([&](int b, hn::Vec<D16> own) FG_INLINE_LAMBDA { return SeamOfBlock(d16, row, b, own); });
    else if (row.fade)
        body([&](int b, hn::Vec<D16> own) FG_INLINE_LAMBDA {
            return b == 0 ? own : FadeOfBlock(d16, row, b, own, fade);
        });
    else
        body([](int, hn::Vec<D16> own) FG_INLINE_LAMBDA { return own; });
}

// Lanes [j, j + Lanes) of block b's row, its first vector (j = 0) with the horizontal
// overlap. At least two lanes where the row overlaps.
HWY_INLINE hn::Vec<D16> BlockNoiseAt(D16 d16, const BlockNoiseRow& row, int b, int j, const FadeConstants& fade) {
    const auto own = hn::LoadU(d16, row.block(b) + j);
    return j == 0 ? FirstNoiseOfBlock(d16, row, b, own, fade) : own;
}

// dst = clip(src + Round2(scale * noise, shift)) for `count` samples from x (x a multiple
// of the block width, count of the lane count), the scales read by `scale_at(k)` as
// pre-shifted q15 int16 lanes. Block by block, so that only a block's first vector looks
// at the overlap.
template <typename Pixel, class ScaleAt>
HWY_INLINE void AddBlockNoise(const Pixel* src, Pixel* dst, const BlockNoiseRow& noise_row, int x, int count,
                              ScaleAt scale_at, int min_value, int max_value) {
    const D16 d16;
    const hn::Rebind<Pixel, D16> dp;
    const hn::RebindToUnsigned<D16> du16;
    const int n = int(hn::Lanes(d16));
    // A local copy: byte stores to dst could alias the caller's struct, which would make the
    // compiler reload its members after every store.
    const BlockNoiseRow row = noise_row;
    const auto vmin = hn::Set(d16, int16_t(min_value)), vmax = hn::Set(d16, int16_t(max_value));
    const FadeConstants fade = FadeConstantsOf(row);
    const bool overlapped = row.seams || row.fade;
    // (the sum saturating: samples beyond the bit depth, bad input, clip as the spec's
    // integers do)
    auto blend = [&](int k, hn::Vec<D16> noise) FG_INLINE_LAMBDA {
        const auto add = hn::MulFixedPoint15(scale_at(k), noise);
        hn::Vec<D16> orig;
        if constexpr (sizeof(Pixel) == 1)
            orig = hn::BitCast(d16, hn::PromoteTo(du16, hn::LoadU(dp, src + x + k)));
        else
            orig = hn::BitCast(d16, hn::LoadU(dp, src + x + k));
        const auto v = hn::Min(hn::Max(hn::SaturatedAdd(orig, add), vmin), vmax);
        if constexpr (sizeof(Pixel) == 1)
            hn::StoreU(hn::DemoteTo(dp, v), dp, dst + x + k);
        else
            hn::StoreU(hn::BitCast(dp, v), dp, dst + x + k);
    };
    const int bw = row.block_width;
    int k = 0, b = x / bw;
    // Whole blocks of whole vectors (every vector target: blocks of 16 or 32 samples), with
    // the vectors per block and the overlap's form fixed for the loop, so that a block costs
    // its vectors and no per-block tests. (8-bit rows on AVX2 come here only for their last
    // samples after blend_u8_avx2-inl.h's steps, or for block widths the synthesis does not
    // make at 8 bits.)
    if (n >= 2 && bw % n == 0) {
        auto whole_blocks = [&](auto vectors, auto first_of_block) FG_INLINE_LAMBDA {
            constexpr int kVectors = decltype(vectors)::value;
            for (; k + kVectors * n <= count; k += kVectors * n, ++b) {
                const int16_t* own = row.block(b);
                blend(k, first_of_block(b, hn::LoadU(d16, own)));
                for (int v = 1; v < kVectors; ++v) blend(k + v * n, hn::LoadU(d16, own + v * n));
            }
        };
        auto with_overlap = [&](auto vectors) FG_INLINE_LAMBDA {
            WithFirstOfBlock(row, fade,
                             [&](auto first_of_block) FG_INLINE_LAMBDA { whole_blocks(vectors, first_of_block); });
        };
        switch (bw / n) {
            case 1: with_overlap(std::integral_constant<int, 1>()); break;
            case 2: with_overlap(std::integral_constant<int, 2>()); break;
            case 4: with_overlap(std::integral_constant<int, 4>()); break;
            default: break;  // the general loop below
        }
    }
    for (; k < count; k += bw, ++b) {
        const int16_t* own = row.block(b);
        const int in_block = std::min(bw, count - k);
        int j = 0;
        if (overlapped && n < 2) {
            // One lane (the scalar target): the two overlapped samples one by one.
            for (; j < 2 && j < in_block; ++j) blend(k + j, hn::Set(d16, row.at(x + k + j)));
        } else {
            blend(k, BlockNoiseAt(d16, row, b, 0, fade));
            j = n;
        }
        for (; j < in_block; j += n) blend(k + j, hn::LoadU(d16, own + j));
    }
}

// Scales of a byte buffer, widened and shifted to q15.
HWY_INLINE auto ByteScalesQ15(const uint8_t* scale, int up_shift) {
    return [scale, up_shift](int k) {
        const D16 d16;
        const hn::Rebind<uint8_t, D16> d8;
        const hn::RebindToUnsigned<D16> du16;
        return hn::ShiftLeftSame(hn::BitCast(d16, hn::PromoteTo(du16, hn::Load(d8, scale + k))), up_shift);
    };
}

// Luma co-sited with chroma lanes [x, x + n): the average of each horizontal pair when
// subsampled. Pairs are read as one wider lane and split, which needs no shuffles.
template <typename Pixel>
HWY_INLINE hn::Vec<D32> CositedLuma(D32 d32, const Pixel* luma, int x, int subsampling_x) {
    if (!subsampling_x) return hn::PromoteTo(d32, hn::LoadU(hn::Rebind<Pixel, D32>(), luma + x));
    using Wide = hwy::MakeWide<Pixel>;
    const hn::Rebind<Wide, D32> dw;
    const auto pairs = hn::LoadU(dw, reinterpret_cast<const Wide*>(luma + 2 * x));
    constexpr int kBits = int(sizeof(Pixel) * 8);
    const auto lo = hn::And(pairs, hn::Set(dw, Wide((Wide(1) << kBits) - 1)));
    const auto hi = hn::ShiftRight<kBits>(pairs);
    const auto avg = hn::ShiftRight<1>(hn::Add(hn::Add(lo, hi), hn::Set(dw, Wide(1))));
    if constexpr (sizeof(Wide) == 4)
        return hn::BitCast(d32, avg);
    else
        return hn::PromoteTo(d32, avg);
}

// The chroma scaling index (`merged`, AV1 7.18.3.5) of `count` samples from x (a multiple of
// the int32 lane count) into out[0..count): the co-sited luma when chroma scales from luma,
// else (luma * cb_luma_mult + chroma * cb_mult) >> 6 plus the offset, clipped to the sample
// range.
template <typename Pixel, typename Out>
HWY_INLINE void ChromaScalingIndices(const Pixel* src, const Pixel* luma, int x, int count, int subsampling_x,
                                     const ChromaScalingIndex& index, int bit_depth, Out* out) {
    const D32 d32;
    const hn::Rebind<Pixel, D32> dp;
    const hn::Rebind<Out, D32> dout;
    const int n = int(hn::Lanes(d32));
    const auto luma_mult = hn::Set(d32, index.luma_mult), mult = hn::Set(d32, index.mult);
    const auto offset = hn::Set(d32, index.offset * (1 << (bit_depth - 8)));
    const auto pixel_max = hn::Set(d32, (1 << bit_depth) - 1);
    for (int k = 0; k < count; k += n) {
        auto m = CositedLuma(d32, luma, x + k, subsampling_x);
        if (!index.from_luma) {
            const auto orig = hn::PromoteTo(d32, hn::LoadU(dp, src + x + k));
            const auto combined = hn::Add(hn::Mul(m, luma_mult), hn::Mul(orig, mult));
            m = hn::Min(hn::Max(hn::Add(hn::ShiftRight<6>(combined), offset), hn::Zero(d32)), pixel_max);
        }
        if constexpr (sizeof(Out) == 4)
            hn::Store(m, d32, out + k);
        else
            hn::Store(hn::DemoteTo(dout, m), dout, out + k);
    }
}

// ChromaScalingIndices in 16-bit lanes, twice as many per vector: the co-sited luma
// averaged with AverageRound, and luma * luma_mult + chroma * mult as one multiply-add of
// interleaved (luma, chroma) pairs into int32, whose >> 6 fits 16 bits again. The pairs of
// the lower and upper lanes of each 128-bit block and the narrowing pack then restore the
// lane order. Needs at least 8 lanes (every x86 target but the scalar one).
#if HWY_TARGET != HWY_SCALAR
template <typename Pixel, typename Out>
HWY_INLINE void ChromaScalingIndices16(const Pixel* src, const Pixel* luma, int x, int count, int subsampling_x,
                                       const ChromaScalingIndex& index, int bit_depth, Out* out) {
    const D16 d16;
    const hn::RebindToUnsigned<D16> du16;
    const hn::Repartition<int32_t, D16> d32;
    const hn::Repartition<uint32_t, D16> du32;
    const int n = int(hn::Lanes(d16));
    const auto mults = hn::BitCast(d16, hn::Set(du32, uint32_t(uint16_t(index.luma_mult)) |
                                                          uint32_t(uint16_t(index.mult)) << 16));
    const auto offset = hn::Set(d16, int16_t(index.offset * (1 << (bit_depth - 8))));
    const auto pixel_max = hn::Set(d16, int16_t((1 << bit_depth) - 1));
#if HWY_TARGET == HWY_AVX2
    [[maybe_unused]] const __m256i byte_mults =
        _mm256_set1_epi16(int16_t(uint16_t(uint8_t(index.luma_mult)) | uint16_t(uint16_t(uint8_t(index.mult)) << 8)));
#endif
    for (int k = 0; k < count; k += n) {
        const int cx = x + k;
        hn::Vec<decltype(du16)> avg;
        if (!subsampling_x) {
            if constexpr (sizeof(Pixel) == 1)
                avg = hn::PromoteTo(du16, hn::LoadU(hn::Rebind<uint8_t, D16>(), luma + cx));
            else
                avg = hn::LoadU(du16, luma + cx);
        } else if constexpr (sizeof(Pixel) == 1) {
            const auto pairs = hn::LoadU(du16, reinterpret_cast<const uint16_t*>(luma + 2 * cx));
            avg = hn::AverageRound(hn::And(pairs, hn::Set(du16, uint16_t(0xFF))), hn::ShiftRight<8>(pairs));
        } else {
            const auto a = hn::LoadU(du16, luma + 2 * cx), b = hn::LoadU(du16, luma + 2 * cx + n);
            avg = hn::AverageRound(hn::ConcatEven(du16, b, a), hn::ConcatOdd(du16, b, a));
        }
        auto m = hn::BitCast(d16, avg);
        if (!index.from_luma) {
            hn::Vec<D16> orig;
            if constexpr (sizeof(Pixel) == 1)
                orig = hn::BitCast(d16, hn::PromoteTo(du16, hn::LoadU(hn::Rebind<uint8_t, D16>(), src + cx)));
            else
                orig = hn::BitCast(d16, hn::LoadU(du16, src + cx));
#if HWY_TARGET == HWY_AVX2
            // 8 bits: (luma, chroma) as the two bytes of each 16-bit lane and one unsigned x
            // signed byte multiply-add (pmaddubsw; Highway 1.0 has none). Its sum saturates
            // at int16, but only where the exact index is clipped anyway: 32767 >> 6 = 511
            // and -32768 >> 6 = -512 stay beyond 0..255 after any offset in -256..255.
            if constexpr (sizeof(Pixel) == 1) {
                const hn::Vec<D16> sum{_mm256_maddubs_epi16(hn::Or(m, hn::ShiftLeft<8>(orig)).raw, byte_mults)};
                m = hn::Add(hn::ShiftRight<6>(sum), offset);
                // Narrowing to bytes saturates to 0..255, which is the clip.
                if constexpr (sizeof(Out) != 1) m = hn::Min(hn::Max(m, hn::Zero(d16)), pixel_max);
            } else
#endif
            {
                auto sum1 = hn::Zero(d32);
                auto lo =
                    hn::ReorderWidenMulAccumulate(d32, hn::InterleaveLower(d16, m, orig), mults, hn::Zero(d32), sum1);
                lo = hn::RearrangeToOddPlusEven(lo, sum1);
                auto sum1h = hn::Zero(d32);
                auto hi =
                    hn::ReorderWidenMulAccumulate(d32, hn::InterleaveUpper(d16, m, orig), mults, hn::Zero(d32), sum1h);
                hi = hn::RearrangeToOddPlusEven(hi, sum1h);
                m = hn::ReorderDemote2To(d16, hn::ShiftRight<6>(lo), hn::ShiftRight<6>(hi));
                m = hn::Min(hn::Max(hn::SaturatedAdd(m, offset), hn::Zero(d16)), pixel_max);
            }
        }
        if constexpr (sizeof(Out) == 1)
            hn::Store(hn::DemoteTo(hn::Rebind<uint8_t, D16>(), m), hn::Rebind<uint8_t, D16>(), out + k);
        else
            hn::Store(m, d16, out + k);
    }
}
#endif

// ChromaScalingIndices16 where the target has the lanes for it.
template <typename Pixel, typename Out>
HWY_INLINE void ChromaIndicesForTarget(const Pixel* src, const Pixel* luma, int x, int count, int subsampling_x,
                                       const ChromaScalingIndex& index, int bit_depth, Out* out) {
#if HWY_TARGET != HWY_SCALAR
    ChromaScalingIndices16(src, luma, x, count, subsampling_x, index, bit_depth, out);
#else
    ChromaScalingIndices(src, luma, x, count, subsampling_x, index, bit_depth, out);
#endif
}

// The samples the vector loops leave, one by one (AV1 7.18.3.5); scaled(merged, noise) is
// Round2(scale_lut(merged) * noise, shift).
template <typename Pixel, class Scaled>
void BlendChromaScalar(const Pixel* src, Pixel* dst, const Pixel* luma, int luma_width, const BlockNoiseRow& noise,
                       int x, int width, int subsampling_x, const ChromaScalingIndex& index, Scaled scaled,
                       int bit_depth, int min_value, int max_value) {
    for (; x < width; ++x) {
        const int orig = src[x];
        const int merged = chroma_scaling_index(luma, luma_width, x, subsampling_x, orig, index, bit_depth);
        const int v = orig + scaled(merged, noise.at(x));
        dst[x] = static_cast<Pixel>(v < min_value ? min_value : v > max_value ? max_value : v);
    }
}

// Above 8 bits the vector forms hold the spec's integers only for samples below 2^14 (their
// 16-bit pair sums, the chroma index's multiply-add and the saturating sum treat the top bits
// as a sign). Samples above the bit depth are bad input nobody scans for beforehand, so that
// the output does not depend on the kernels even then, the vector forms check what they read
// and leave steps or rows holding one to the scalar forms here, whose int arithmetic is the
// reference's for any 16-bit sample.

// Samples [x, end) of a luma row one by one (the vector loops' tails, and the steps and rows
// above the bit depth), and with co_sited its co-sited averages of the whole pairs in
// [x, end) (x even), made first: in place, the blend overwrites the samples.
template <typename Pixel>
void BlendLumaScalar(const Pixel* src, Pixel* dst, const BlockNoiseRow& noise, int x, int end, int width,
                     const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                     Pixel* co_sited = nullptr) {
    if (co_sited)
        for (int c = x / 2; c < (end + 1) / 2; ++c) co_sited[c] = static_cast<Pixel>(co_sited_luma(src, width, c));
    for (; x < end; ++x) {
        const int v = src[x] + round2_signed(scaling(src[x]) * noise.at(x), scaling_shift);
        dst[x] = static_cast<Pixel>(v < min_value ? min_value : v > max_value ? max_value : v);
    }
}

// Chroma samples [x, end) one by one, as BlendChromaScalar, scaled by the ScalingLookup.
inline void BlendChromaLookedUp(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                                const BlockNoiseRow& noise, int x, int end, int subsampling_x,
                                const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                                int bit_depth, int min_value, int max_value) {
    BlendChromaScalar(
        src, dst, luma, luma_width, noise, x, end, subsampling_x, index,
        [&](int merged, int nz) { return round2_signed(scaling(merged) * nz, scaling_shift); }, bit_depth, min_value,
        max_value);
}

// Whether any of n samples lies above the bit depth.
bool AnyAboveBitDepth(const uint16_t* p, int n, int bit_depth) {
    const hn::ScalableTag<uint16_t> du16;
    const int lanes = int(hn::Lanes(du16));
    auto any = hn::Zero(du16);
    int x = 0;
    for (; x + lanes <= n; x += lanes) any = hn::Or(any, hn::LoadU(du16, p + x));
    unsigned tail = 0;
    for (; x < n; ++x) tail |= p[x];
    const uint16_t above = uint16_t(~((1u << bit_depth) - 1u));
    return (tail & above) != 0 || !hn::AllFalse(du16, hn::Ne(hn::And(any, hn::Set(du16, above)), hn::Zero(du16)));
}

// Runs blend(), a row's vector forms that do not check their steps, and returns whether the
// samples it read lie within the bit depth, bad() saying whether any does not: checked after
// blend() has brought them into the first-level cache (checked before, the rows came from
// memory twice: AV1 10-bit 1080p 0.60 to 0.72 ms per frame), except in place, where the output
// would hide them: checked before, and blend() not run where they do not.
template <class Bad, class Blend>
bool CheckedRow(bool in_place, Bad&& bad, Blend&& blend) {
    if (in_place && bad()) return false;
    blend();
    return in_place || !bad();
}

// What the caller of a 10-bit form keeps for the steps it leaves out (AnyAbove10Bits):
// bad(x, n), whether samples [x, x + n) hold one above 10 bits; scalar(x, n), their scalar
// blend; `skipped`, set by the form.
template <class Bad, class Scalar>
struct SkippedSteps {
    Bad bad;
    Scalar scalar;
    int width;
    bool skipped = false;
    int vector_end;  // where the form's tail began
    // The tail from x: the scalar way where it holds a sample above 10 bits, else generic().
    template <class Generic>
    void Tail(int x, Generic&& generic) {
        vector_end = x;
        if (bad(x, width - x))
            scalar(x, width - x);
        else
            generic();
    }
    // After the form, the steps it left out: its steps before where its tail began (64
    // samples each, the last one 32 where the AVX2 form took 32) that hold a sample above the
    // bit depth. A step it blended holds samples within the bit depth (out of place) or its
    // output (in place) by now, so it does not count.
    // Finish for a form that left a step out before where its tail began (tail_begin).
    void FinishSkipped(int tail_begin) {
        skipped = true;
        vector_end = tail_begin;
        Finish();
    }
    void Finish() {
        if (!skipped) return;
        for (int x = 0; x < vector_end; x += 64) {
            const int n = std::min(64, vector_end - x);
            if (bad(x, n)) scalar(x, n);
        }
    }
};
// A single row for the several-row forms, `ahead` its row to prefetch (or null).
inline PlaneRows OneRow(const uint16_t* ahead) {
    PlaneRows one;
    one.ahead = ahead;
    one.ahead_count = ahead ? 1 : 0;
    return one;
}

template <class Bad, class Scalar>
SkippedSteps<Bad, Scalar> MakeSkippedSteps(int width, Bad bad, Scalar scalar) {
    return {bad, scalar, width, false, width};
}

// SkippedSteps of a luma row (co-sited averages made too where co_sited) and of a chroma row
// with unsubsampled luma, the row and scaling held by reference.
inline auto LumaSkippedSteps(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& row, int width,
                             const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                             uint16_t* co_sited) {
    return MakeSkippedSteps(
        width, [src](int x, int n) { return AnyAboveBitDepth(src + x, n, 10); },
        [=, &row, &scaling](int x, int n) {
            BlendLumaScalar(src, dst, row, x, x + n, width, scaling, scaling_shift, min_value, max_value, co_sited);
        });
}
inline auto ChromaSkippedSteps(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                               const BlockNoiseRow& row, int width, const ChromaScalingIndex& index,
                               const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
    return MakeSkippedSteps(
        width,
        [src, luma](int x, int n) { return AnyAboveBitDepth(src + x, n, 10) || AnyAboveBitDepth(luma + x, n, 10); },
        [=, &row, &index, &scaling](int x, int n) {
            BlendChromaLookedUp(src, dst, luma, luma_width, row, x, x + n, 0, index, scaling, scaling_shift, 10,
                                min_value, max_value);
        });
}

// 8 bits: the scaling function is the spec's 256-byte ScalingLut (values 0..255), looked up
// with sixteen 16-entry byte shuffles. A shuffle yields 0 in lanes whose index has bit 7 set,
// so an index saturated upwards by 16 per step stays valid (below 128) exactly for the steps
// j >= its high nibble; with each step's table the XOR of two neighbouring 16-entry rows of
// the LUT, the XOR over those steps leaves the wanted row. The indices from 128 up take a
// second chain on index - 128. Three vector operations per 16 entries and no per-step
// constants replace a scalar load and store per sample. The XOR'd rows are made once per
// parameter set (ScalingLookup::lut8_chain()) and read by 16-byte broadcast loads where the
// chain uses them (copying them to whole vectors once per row cost 1-2 % of a frame).
// Rows row - 1, row and row + 1 of a table of 16-entry rows (clamped to 0..last_row), each
// broadcast to every 16-byte block: the three rows a vector whose samples lie near one
// another is looked up in (the 8-bit LUT, or above 8 bits the full-range table).
template <class D8>
struct ThreeRows {
    hn::Vec<D8> below, same, above;
    static HWY_INLINE ThreeRows At(const uint8_t* table, int row, int last_row) {
        const D8 du8;
        return {hn::LoadDup128(du8, table + 16 * (row > 0 ? row - 1 : 0)), hn::LoadDup128(du8, table + 16 * row),
                hn::LoadDup128(du8, table + 16 * (row < last_row ? row + 1 : last_row))};
    }
    // The entry at each byte's low nibble `low` in the row `rel` names (0 below, 1 the same,
    // 2 above). `one` and `two` are the constants 1 and 2, passed in so that a loop makes
    // them once.
    HWY_INLINE hn::Vec<D8> Pick(hn::Vec<D8> low, hn::Vec<D8> rel, hn::Vec<D8> one, hn::Vec<D8> two) const {
        return hn::IfThenElse(hn::Eq(rel, two), hn::TableLookupBytes(above, low),
                              hn::IfThenElse(hn::Eq(rel, one), hn::TableLookupBytes(same, low),
                                             hn::TableLookupBytes(below, low)));
    }
};

template <class D8>
struct ShuffleRows {
    const uint8_t* lut;         // 256 entries
    const uint8_t* chain_rows;  // 16 XOR'd rows of 16 bytes
    ShuffleRows(const uint8_t* lut_in, const uint8_t* chain_in) : lut(lut_in), chain_rows(chain_in) {}
    HWY_INLINE hn::Vec<D8> chain(int j) const { return hn::LoadDup128(D8(), chain_rows + 16 * j); }
};

// The bytes of kTables tables at the byte indices `index` (the 8-bit LUT alone, or above 8
// bits the LUT and its successor for the interpolation), sharing the index arithmetic.
// Needs whole 16-byte blocks.
template <int kTables, class D8>
HWY_INLINE void LookUpVector(D8 du8, hn::Vec<D8> index, const ShuffleRows<D8>* const (&tables)[kTables],
                             hn::Vec<D8> (&out)[kTables]) {
    // Picture content is locally smooth: most vectors' high nibbles lie within one of the
    // first lane's (90 % of 32-sample luma vectors of the benchmark stream), and three plain
    // rows of the LUT then give the same values as the chain below.
    const int h0 = hn::GetLane(index) >> 4;
    const auto rel = hn::Sub(hn::ShiftRight<4>(index), hn::Set(du8, uint8_t(h0 - 1)));  // wraps below 0
    const auto two = hn::Set(du8, uint8_t(2));
    if (hn::AllTrue(du8, hn::Eq(hn::SaturatedSub(rel, two), hn::Zero(du8)))) {
        const auto low = hn::And(index, hn::Set(du8, uint8_t(15)));
        for (int t = 0; t < kTables; ++t) {
            out[t] = ThreeRows<D8>::At(tables[t]->lut, h0, 15).Pick(low, rel, hn::Set(du8, uint8_t(1)), two);
        }
        return;
    }
    const auto step = hn::Set(du8, uint8_t(16));
    auto lo = index, hi = hn::Xor(index, hn::Set(du8, uint8_t(0x80)));
    hn::Vec<D8> r_lo[kTables], r_hi[kTables];
    for (int t = 0; t < kTables; ++t) {
        r_lo[t] = hn::TableLookupBytesOr0(tables[t]->chain(7), lo);
        r_hi[t] = hn::TableLookupBytesOr0(tables[t]->chain(15), hi);
    }
    for (int j = 6; j >= 0; --j) {
        lo = hn::SaturatedAdd(lo, step);
        hi = hn::SaturatedAdd(hi, step);
        for (int t = 0; t < kTables; ++t) {
            r_lo[t] = hn::Xor(r_lo[t], hn::TableLookupBytesOr0(tables[t]->chain(j), lo));
            r_hi[t] = hn::Xor(r_hi[t], hn::TableLookupBytesOr0(tables[t]->chain(8 + j), hi));
        }
    }
    for (int t = 0; t < kTables; ++t) out[t] = hn::Xor(r_lo[t], r_hi[t]);
}

using D8 = hn::ScalableTag<uint8_t>;

// The lines of a step's kSamples source samples `ahead` (null: none), one prefetch per 64
// bytes, for the 10-bit AVX2 and AVX-512 blends (blend_10bit_*-inl.h). The decoded picture
// comes from the decoder, not from the cache, and the hardware prefetcher alone left 38 % of
// the AVX2 luma kernel's samples on its source loads while the shared host was busy: in one
// process against dav1d_apply_grain (1080p 10-bit, one thread) 16 rows ahead took the
// per-picture cost to 0.957 of what it was on a Zen 3 (AVX2, median of 10 interleaved rounds;
// 8, 24 and 64 rows gained less, 32 about as much; with the host quiet it made no difference)
// and to 0.91 on an Emerald Rapids Xeon (AVX-512, median of 8; docs/performance-notes.md). At
// 8 bits it gained nothing on the Zen 3 and no more than the host's noise on the Xeon: none
// there.
template <int kSamples>
HWY_INLINE void PrefetchSourceAhead(const uint16_t* ahead) {
    if (!ahead) return;
    for (int k = 0; k < kSamples; k += 32) __builtin_prefetch(ahead + k, 0, 2);
}

// A row `r` rows down from `p`, `stride` bytes apart (PlaneRows' strides are in bytes).
template <typename T>
HWY_INLINE T* RowDown(T* p, int r, std::ptrdiff_t stride) {
    using Byte = std::conditional_t<std::is_const_v<T>, const uint8_t, uint8_t>;
    return reinterpret_cast<T*>(reinterpret_cast<Byte*>(p) + r * stride);
}

// Drives rows.count rows of a 10-bit form (blend_10bit_avx2-inl.h, blend_10bit_avx512-inl.h)
// with what they share made once by the caller: called row by row, the per-row set-up, the
// dispatch and the tail bookkeeping were about a tenth of the 10-bit synthesis (Zen 4 profile,
// docs/performance-notes.md). For each row r: row_steps(r, row, s, d, ahead, skipped) runs the
// row's steps (`s`, `d` its source and output, `ahead` PrefetchSourceAhead's row or null) and
// returns where its tail began, setting `skipped` where it left a step out (a sample above 10
// bits); left_out(r, row, vector_end) then blends those.
template <class RowSteps, class LeftOut>
HWY_INLINE void ForEachRow10(const uint16_t* src, uint16_t* dst, const PlaneRows& rows,
                             const BlockNoiseRow& first_row, RowSteps&& row_steps, LeftOut&& left_out) {
    BlockNoiseRow row = first_row;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step) {
        const uint16_t* ahead = r < rows.ahead_count ? RowDown(rows.ahead, r, rows.src_stride) : nullptr;
        bool skipped = false;
        const int vector_end =
            row_steps(r, row, RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride), ahead, skipped);
        if (skipped) left_out(r, row, vector_end);
    }
}

#include "av1/simd/blend_u8_avx512-inl.h"
#include "av1/simd/blend_10bit_avx512-inl.h"

// lut[a] and lut[b] for two vectors of byte indices, h0 the high nibble of a's first lane
// (needs whole 16-byte blocks). The two share one three-row test (against that lane) and its
// row loads; where that fails each vector takes LookUpVector's own test.
HWY_INLINE void LookUpPair(hn::Vec<D8> a, hn::Vec<D8> b, int h0, const ShuffleRows<D8>& rows, hn::Vec<D8>& out_a,
                           hn::Vec<D8>& out_b) {
    const D8 du8;
    const ShuffleRows<D8>* const tables[1] = {&rows};
    const auto one = hn::Set(du8, uint8_t(1)), two = hn::Set(du8, uint8_t(2)), nibble = hn::Set(du8, uint8_t(15));
    const auto first = hn::Set(du8, uint8_t(h0 - 1));  // wraps below 0
    const auto rel_a = hn::Sub(hn::ShiftRight<4>(a), first), rel_b = hn::Sub(hn::ShiftRight<4>(b), first);
    const ThreeRows<D8> near = ThreeRows<D8>::At(rows.lut, h0, 15);
    auto pick = [&](hn::Vec<D8> idx, hn::Vec<D8> rel) { return near.Pick(hn::And(idx, nibble), rel, one, two); };
    if (hn::AllTrue(du8, hn::Eq(hn::SaturatedSub(hn::Max(rel_a, rel_b), two), hn::Zero(du8)))) {
        out_a = pick(a, rel_a);
        out_b = pick(b, rel_b);
        return;
    }
    // The first vector may still lie within those rows (its own test is the same).
    hn::Vec<D8> got[1];
    if (hn::AllTrue(du8, hn::Eq(hn::SaturatedSub(rel_a, two), hn::Zero(du8)))) {
        out_a = pick(a, rel_a);
    } else {
        LookUpVector<1>(du8, a, tables, got);
        out_a = got[0];
    }
    LookUpVector<1>(du8, b, tables, got);
    out_b = got[0];
}

// out[k] = lut[index[k]] for k < count.
HWY_INLINE void LookUpScaling8(const uint8_t* index, uint8_t* out, int count, const ShuffleRows<D8>& rows) {
    const D8 du8;
    const int n = int(hn::Lanes(du8));
    int k = 0;
    if (n >= 16) {
        const ShuffleRows<D8>* const tables[1] = {&rows};
        for (; k + 2 * n <= count; k += 2 * n) {
            hn::Vec<D8> a, b;
            LookUpPair(hn::LoadU(du8, index + k), hn::LoadU(du8, index + k + n), index[k] >> 4, rows, a, b);
            hn::StoreU(a, du8, out + k);
            hn::StoreU(b, du8, out + k + n);
        }
        for (; k + n <= count; k += n) {
            hn::Vec<D8> got[1];
            LookUpVector<1>(du8, hn::LoadU(du8, index + k), tables, got);
            hn::StoreU(got[0], du8, out + k);
        }
    }
    for (; k < count; ++k) out[k] = rows.lut[index[k]];
}

#include "av1/simd/blend_u8_avx2-inl.h"

// Above 8 bits the scale of sample i is scale_lut(i) (7.18.3.5: the 8-bit LUT at
// i >> shift, interpolated towards its next entry by the low bits, shift = bit_depth - 8).
// ScalingLookup keeps it over the whole bit-depth range (exact by construction): too many
// entries for byte shuffles, but decoded pictures are locally smooth. Four vectors whose
// samples all lie in the three 16-entry rows of that table at and around the first sample's
// row (74 % of the 64-sample luma groups of the 10-bit benchmark stream) are looked up with
// three shuffles per pair; the others, where they lie within 16 rows around it, by a chain of 16 shuffles over
// those rows (StoreByWindow). The rest take the spec's form: the two 8-bit LUT entries by
// byte shuffles as at 8 bits (where most vectors again need only three rows) and the
// interpolation in 16-bit lanes. Each way two vectors' bytes share one byte vector
// (PackBytes), so no byte crosses a lane on the way there and back. Where more than half the
// pairs of a chunk take the spec's form (noisy content), the rest of the row skips the
// tests and looks a whole chunk's LUT entries up at once, which schedules better than pair by
// pair. The results are shifted up to q15.
class InterpolatedScales {
public:
    InterpolatedScales(const ScalingLookup& scaling, int bit_depth, int scaling_shift)
        :
#if HWY_TARGET != HWY_SCALAR
          lut_rows_(scaling.table8().data(), scaling.lut8_chain()),
          next_rows_(scaling.next8(), scaling.next8_chain()),
#endif
          full_(scaling.full_table()),
          full_chain_(scaling.full_chain()),
          bd_shift_(bit_depth - 8),
          last_row_((1 << bit_depth) / 16 - 1),
          index_max_((1 << bit_depth) - 1),
          up_shift_(15 - scaling_shift) {}
    // Looks up `count` indices (a multiple of the 16-bit lane count); then At(k) gives the
    // q15 scales of lanes [k, k + Lanes). Every form clamps the indices to the table first:
    // indices beyond the bit depth (samples of bad input) read its last entry, as in Scalar.
    template <typename Index>
    HWY_INLINE void LookUp(const Index* index, int count) {
        const auto* in = reinterpret_cast<const uint16_t*>(index);
        int k = 0;
#if HWY_TARGET != HWY_SCALAR  // byte shuffles need whole 16-byte blocks
        const D16 d16;
        const hn::RebindToUnsigned<D16> du16;
        const int n = int(hn::Lanes(d16));
        const Consts c = MakeConsts();
        const auto two = c.two;
        if (!by_rows_) return LookUpChunk(in, 0, count);
        int misses = 0;
        // Two pairs share one row test (against the first sample of the first) and its row
        // loads. A group that fails it (an edge) may still lie within 16 rows of the full
        // table around that row (78 % of the failing 64-sample luma groups of the benchmark
        // stream), where a chain of byte shuffles over those rows looks it up; the others
        // take the spec's form pair by pair.
        const int max_base = last_row_ - 15;
        for (; k + 4 * n <= count; k += 4 * n) {
            hn::Vec<decltype(du16)> v[4], rel[4];
            const int row = std::min(int(in[k]), index_max_) >> 4;
            const auto first = hn::Set(du16, uint16_t(row - 1));  // wraps below 0
            for (int g = 0; g < 4; ++g) {
                v[g] = hn::Min(hn::LoadU(du16, in + k + g * n), c.index_max);
                rel[g] = hn::Sub(hn::ShiftRight<4>(v[g]), first);
            }
            const auto top = hn::Max(hn::Max(rel[0], rel[1]), hn::Max(rel[2], rel[3]));
            if (hn::AllTrue(du16, hn::Eq(hn::SaturatedSub(top, two), hn::Zero(du16)))) {
                const auto rows = ThreeRows<D8x>::At(full_, row, last_row_);
                StoreByRows(c, rows, v[0], v[1], rel[0], rel[1], k);
                StoreByRows(c, rows, v[2], v[3], rel[2], rel[3], k + 2 * n);
                continue;
            }
            const int base = std::max(0, std::min(row - 7, max_base));
            const auto offset = hn::Set(du16, uint16_t(16 * base));
            hn::Vec<decltype(du16)> idx[4];
            for (int g = 0; g < 4; ++g) idx[g] = hn::Sub(v[g], offset);  // wraps below
            const auto window_top = hn::Max(hn::Max(idx[0], idx[1]), hn::Max(idx[2], idx[3]));
            if (hn::AllTrue(du16, hn::Eq(hn::ShiftRight<8>(window_top), hn::Zero(du16)))) {
                StoreByWindow(c, base, idx, k);
                continue;
            }
            misses += !LookUpPair(c, in, k, false);
            misses += !LookUpPair(c, in, k + 2 * n, false);
        }
        for (; k + 2 * n <= count; k += 2 * n) misses += !LookUpPair(c, in, k);
        // Noisy content: where more than half the pairs of a chunk took the spec's form, the
        // rest of the row skips the tests.
        by_rows_ = 2 * misses * 2 * n <= k;
#endif
        for (; k < count; ++k) scale_[k] = int16_t(Scalar(in[k]) << up_shift_);
    }
#if HWY_TARGET != HWY_SCALAR
    // The row form's constants, made once per LookUp call and passed down: made inside the
    // pair functions, the compiler re-made them at every use under the register pressure of
    // the inlined loop (the q15 shift is a multiply by pow2 for the same reason: a shift by
    // a run-time count reloaded the count each time).
    struct Consts {
        hn::Vec<hn::RebindToUnsigned<D16>> nibble, low_byte, two, index_max;
        hn::Vec<D16> pow2;  // 1 << up_shift_
        hn::Vec<hn::Repartition<uint8_t, D16>> one8, two8;
    };
    HWY_INLINE Consts MakeConsts() const {
        const hn::RebindToUnsigned<D16> du16;
        const hn::Repartition<uint8_t, D16> du8;
        return {hn::Set(du16, uint16_t(15)),
                hn::Set(du16, uint16_t(0x00FF)),
                hn::Set(du16, uint16_t(2)),
                hn::Set(du16, uint16_t(index_max_)),
                hn::Set(D16(), int16_t(1 << up_shift_)),
                hn::Set(du8, uint8_t(1)),
                hn::Set(du8, uint8_t(2))};
    }
    // The q15 scales of the pair (a, b) into scale_[k, k + 2 * Lanes), every sample of it
    // within `rows` of the full table (rel_a, rel_b: its row numbers relative to
    // rows.below, 0..2). The two vectors' low nibbles share one byte vector (PackBytes).
    HWY_INLINE void StoreByRows(const Consts& c, const ThreeRows<hn::Repartition<uint8_t, D16>>& rows, hn::Vec<hn::RebindToUnsigned<D16>> a,
                                hn::Vec<hn::RebindToUnsigned<D16>> b, hn::Vec<hn::RebindToUnsigned<D16>> rel_a,
                                hn::Vec<hn::RebindToUnsigned<D16>> rel_b, int k) {
        const D16 d16;
        const int n = int(hn::Lanes(d16));
        const auto low = PackBytes(hn::And(a, c.nibble), hn::And(b, c.nibble));
        hn::Vec<D16> scale_a, scale_b;
        UnpackBytes(c, rows.Pick(low, PackBytes(rel_a, rel_b), c.one8, c.two8), scale_a, scale_b);
        hn::Store(hn::Mul(scale_a, c.pow2), d16, scale_ + k);
        hn::Store(hn::Mul(scale_b, c.pow2), d16, scale_ + k + n);
    }
    // Two vectors of 16-bit lanes below 256 as the even and odd bytes of one byte vector (so
    // that no byte crosses a lane on the way there and back), and back.
    static HWY_INLINE hn::Vec<hn::Repartition<uint8_t, D16>> PackBytes(hn::Vec<hn::RebindToUnsigned<D16>> a,
                                                                   hn::Vec<hn::RebindToUnsigned<D16>> b) {
        return hn::BitCast(hn::Repartition<uint8_t, D16>(), hn::Or(a, hn::ShiftLeft<8>(b)));
    }
    static HWY_INLINE void UnpackBytes(const Consts& c, hn::Vec<hn::Repartition<uint8_t, D16>> v, hn::Vec<D16>& a,
                                       hn::Vec<D16>& b) {
        const hn::RebindToUnsigned<D16> du16;
        a = hn::BitCast(D16(), hn::And(hn::BitCast(du16, v), c.low_byte));
        b = hn::BitCast(D16(), hn::ShiftRight<8>(hn::BitCast(du16, v)));
    }
    // The q15 scales of four vectors into scale_[k, k + 4 * Lanes), every index of them
    // within rows base..base + 15 of the full table (idx: the index minus 16 * base, below
    // 256). Each pair's indices as bytes, then the 8-bit LUT's chain of XOR'd rows
    // (LookUpVector) over those 16 rows, shared by both pairs.
    HWY_INLINE void StoreByWindow(const Consts& c, int base, const hn::Vec<hn::RebindToUnsigned<D16>> (&idx)[4],
                                  int k) {
        const D16 d16;
        const D8x du8;
        const int n = int(hn::Lanes(d16));
        const auto step = hn::Set(du8, uint8_t(16)), high = hn::Set(du8, uint8_t(0x80));
        hn::Vec<D8x> lo[2], hi[2], r_lo[2], r_hi[2];
        const uint8_t* rows = full_ + 16 * base;
        const uint8_t* chain = full_chain_ + 16 * base;
        for (int p = 0; p < 2; ++p) {
            lo[p] = PackBytes(idx[2 * p], idx[2 * p + 1]);
            hi[p] = hn::Xor(lo[p], high);
        }
        {
            const auto t_lo = hn::LoadDup128(du8, rows + 16 * 7), t_hi = hn::LoadDup128(du8, rows + 16 * 15);
            for (int p = 0; p < 2; ++p) {
                r_lo[p] = hn::TableLookupBytesOr0(t_lo, lo[p]);
                r_hi[p] = hn::TableLookupBytesOr0(t_hi, hi[p]);
            }
        }
        for (int j = 6; j >= 0; --j) {
            const auto t_lo = hn::LoadDup128(du8, chain + 16 * j), t_hi = hn::LoadDup128(du8, chain + 16 * (8 + j));
            for (int p = 0; p < 2; ++p) {
                lo[p] = hn::SaturatedAdd(lo[p], step);
                hi[p] = hn::SaturatedAdd(hi[p], step);
                r_lo[p] = hn::Xor(r_lo[p], hn::TableLookupBytesOr0(t_lo, lo[p]));
                r_hi[p] = hn::Xor(r_hi[p], hn::TableLookupBytesOr0(t_hi, hi[p]));
            }
        }
        for (int p = 0; p < 2; ++p) {
            hn::Vec<D16> a, b;
            UnpackBytes(c, hn::Xor(r_lo[p], r_hi[p]), a, b);
            hn::Store(hn::Mul(a, c.pow2), d16, scale_ + k + 2 * p * n);
            hn::Store(hn::Mul(b, c.pow2), d16, scale_ + k + (2 * p + 1) * n);
        }
    }
    // One pair at in[k, k + 2 * Lanes) into scale_: by its own row test (true) or from the
    // two LUT entries and the interpolation (false).
    HWY_INLINE bool LookUpPair(const Consts& c, const uint16_t* in, int k, bool try_rows = true) {
        const D16 d16;
        const hn::RebindToUnsigned<D16> du16;
        const hn::Repartition<uint8_t, D16> du8;
        const int n = int(hn::Lanes(d16));
        const auto two = c.two, low_byte = c.low_byte, high_byte = hn::Set(du16, uint16_t(0xFF00));
        const auto a = hn::Min(hn::LoadU(du16, in + k), c.index_max);
        const auto b = hn::Min(hn::LoadU(du16, in + k + n), c.index_max);
        const int row = std::min(int(in[k]), index_max_) >> 4;
        const auto first = hn::Set(du16, uint16_t(row - 1));  // wraps below 0
        const auto rel_a = hn::Sub(hn::ShiftRight<4>(a), first), rel_b = hn::Sub(hn::ShiftRight<4>(b), first);
        if (try_rows &&
            hn::AllTrue(du16, hn::Eq(hn::SaturatedSub(hn::Max(rel_a, rel_b), two), hn::Zero(du16)))) {
            StoreByRows(c, ThreeRows<D8x>::At(full_, row, last_row_), a, b, rel_a, rel_b, k);
            return true;
        }
        // (the top bytes of the clamped indices fit 8 bits)
        const auto top = hn::Or(hn::And(hn::ShiftRightSame(a, bd_shift_), low_byte),
                                hn::And(hn::ShiftLeftSame(b, 8 - bd_shift_), high_byte));
        hn::Vec<decltype(du8)> ends[2];
        LookUpVector<2>(du8, hn::BitCast(du8, top), tables_, ends);
        hn::Vec<D16> start_a, start_b, end_a, end_b;
        UnpackBytes(c, ends[0], start_a, start_b);
        UnpackBytes(c, ends[1], end_a, end_b);
        const auto scale_a = Interpolate(start_a, end_a, hn::BitCast(d16, a));
        const auto scale_b = Interpolate(start_b, end_b, hn::BitCast(d16, b));
        hn::Store(hn::ShiftLeftSame(scale_a, up_shift_), d16, scale_ + k);
        hn::Store(hn::ShiftLeftSame(scale_b, up_shift_), d16, scale_ + k + n);
        return false;
    }
#endif
    HWY_INLINE hn::Vec<D16> At(int k) const { return hn::Load(D16(), scale_ + k); }
    // scale_lut(i), one sample (indices beyond the bit depth read the last entry).
    int Scalar(int i) const { return full_[std::min(i, index_max_)]; }

private:
#if HWY_TARGET != HWY_SCALAR
    // The spec's form for a whole chunk: top bytes, then both LUT entries of every sample,
    // then the interpolation.
    HWY_INLINE void LookUpChunk(const uint16_t* in, int from, int count) {
        const D16 d16;
        const hn::RebindToUnsigned<D16> du16;
        const hn::Rebind<uint8_t, D16> d8;
        const hn::Repartition<uint8_t, D16> du8;
        const int n = int(hn::Lanes(d16)), nb = int(hn::Lanes(du8));
        const auto index_max = hn::Set(du16, uint16_t(index_max_));
        auto index_at = [&](int i) { return hn::BitCast(d16, hn::Min(hn::LoadU(du16, in + i), index_max)); };
        for (int j = from; j < count; j += n)
            hn::Store(hn::DemoteTo(d8, hn::ShiftRightSame(index_at(j), bd_shift_)), d8, top_ + j);
        int j = from;
        for (; j + nb <= count; j += nb) {
            hn::Vec<decltype(du8)> ends[2];
            LookUpVector<2>(du8, hn::LoadU(du8, top_ + j), tables_, ends);
            hn::StoreU(ends[0], du8, start_ + j);
            hn::StoreU(ends[1], du8, end_ + j);
        }
        for (; j < count; ++j) start_[j] = lut_rows_.lut[top_[j]], end_[j] = next_rows_.lut[top_[j]];
        for (int i = from; i < count; i += n) {
            const auto s = hn::BitCast(d16, hn::PromoteTo(du16, hn::Load(d8, start_ + i)));
            const auto e = hn::BitCast(d16, hn::PromoteTo(du16, hn::Load(d8, end_ + i)));
            const auto scale = Interpolate(s, e, index_at(i));
            hn::Store(hn::ShiftLeftSame(scale, up_shift_), d16, scale_ + i);
        }
    }

    // scale_lut from its two LUT entries: start + Round2((end - start) * rem, shift), rem the
    // low bits of the index.
    HWY_INLINE hn::Vec<D16> Interpolate(hn::Vec<D16> start, hn::Vec<D16> end, hn::Vec<D16> index) const {
        const D16 d16;
        const auto rem = hn::And(index, hn::Set(d16, int16_t((1 << bd_shift_) - 1)));
        const auto step = hn::Add(hn::Mul(hn::Sub(end, start), rem), hn::Set(d16, int16_t(1 << (bd_shift_ - 1))));
        return hn::Add(start, hn::ShiftRightSame(step, bd_shift_));
    }
#endif

#if HWY_TARGET != HWY_SCALAR
    using D8x = hn::Repartition<uint8_t, D16>;
    ShuffleRows<D8x> lut_rows_, next_rows_;  // ScalingLut and its successor
    const ShuffleRows<D8x>* const tables_[2] = {&lut_rows_, &next_rows_};
#endif
    const uint8_t* full_;
    const uint8_t* full_chain_;
    int bd_shift_, last_row_, index_max_, up_shift_;
    bool by_rows_ = true;
    HWY_ALIGN uint8_t top_[kChunk];
    HWY_ALIGN uint8_t start_[kChunk];
    HWY_ALIGN uint8_t end_[kChunk];
    HWY_ALIGN int16_t scale_[kChunk];
};

#include "av1/simd/blend_10bit_avx2-inl.h"

// 8 bits: scale * noise in 16-bit lanes (255 * 128 fits), rounded by pmulhrsw with the
// scale shifted up to q15.
// Samples [x_begin, width), x_begin a multiple of the block width: the vector forms hand
// the generic kernels a row's last samples so, the block on their left in place for the fade.
void BlendLumaRowU8Generic(const uint8_t* src, uint8_t* dst, const BlockNoiseRow& noise, int width,
                           const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                           int x_begin = 0) {
    const int n = int(hn::Lanes(D16()));
    const int vec_end = std::max(x_begin, width / n * n);
    HWY_ALIGN uint8_t scale[kChunk];
    const ShuffleRows<D8> rows(scaling.table8().data(), scaling.lut8_chain());
    for (int x = x_begin; x < vec_end; x += kChunk) {
        const int chunk = std::min(kChunk, vec_end - x);
        LookUpScaling8(src + x, scale, chunk, rows);
        AddBlockNoise(src, dst, noise, x, chunk, ByteScalesQ15(scale, 15 - scaling_shift), min_value, max_value);
    }
    BlendLumaScalar(src, dst, noise, vec_end, width, width, scaling, scaling_shift, min_value, max_value);
}

// Above 8 bits the 16-bit lanes hold the samples themselves. Samples [x_begin, width), as
// BlendLumaRowU8Generic.
void BlendLumaRowU16Generic(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& noise, int width,
                            const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                            int max_value, int x_begin = 0) {
    const int n = int(hn::Lanes(D16()));
    const int vec_end = std::max(x_begin, width / n * n);
    InterpolatedScales scales(scaling, bit_depth, scaling_shift);
    for (int x = x_begin; x < vec_end; x += kChunk) {
        const int chunk = std::min(kChunk, vec_end - x);
        scales.LookUp(src + x, chunk);
        AddBlockNoise(src, dst, noise, x, chunk, [&](int k) { return scales.At(k); }, min_value, max_value);
    }
    BlendLumaScalar(src, dst, noise, vec_end, width, width, scaling, scaling_shift, min_value, max_value);
}


// co_sited_luma_row above 8 bits: the pair sums of a multiply-add by ones, halved with
// rounding by a rounding high multiply by 1 << 14 ((2 * sum + 1) >> 1 of the q15 product).
// The column whose right luma sample lies past an odd-width row is left to the scalar tail.
void CoSitedLumaRowU16Unchecked(const uint16_t* luma, int luma_width, int width, uint16_t* out) {
    const hn::ScalableTag<uint16_t> du16;
    [[maybe_unused]] const int n = int(hn::Lanes(du16));
    [[maybe_unused]] const int pairs = std::min(width, luma_width / 2);
    int x = 0;
#if HWY_TARGET == HWY_AVX2
    const __m256i half = _mm256_set1_epi16(1 << 14), ones = _mm256_set1_epi16(1);
    for (; x + n <= pairs; x += n) {
        const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(luma + 2 * x));
        const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(luma + 2 * x + n));
        // sums of two 12-bit samples fit int16
        const __m256i sums = _mm256_packs_epi32(_mm256_madd_epi16(a, ones), _mm256_madd_epi16(b, ones));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + x),
                            _mm256_mulhrs_epi16(_mm256_permute4x64_epi64(sums, 0xD8), half));
    }
#elif HWY_TARGET != HWY_SCALAR
    for (; x + n <= pairs; x += n) {
        const auto a = hn::LoadU(du16, luma + 2 * x), b = hn::LoadU(du16, luma + 2 * x + n);
        hn::StoreU(hn::AverageRound(hn::ConcatEven(du16, b, a), hn::ConcatOdd(du16, b, a)), du16, out + x);
    }
#endif
    for (; x < width; ++x)
        out[x] = static_cast<uint16_t>(co_sited_luma(luma, luma_width, x));
}

// The AVX2 form's pair sums hold 15 bits: luma from 2^14 on (bad input) is averaged again the
// scalar way. (The output is scratch, never the luma: checked after.)
void CoSitedLumaRowU16(const uint16_t* luma, int luma_width, int width, uint16_t* out) {
    CoSitedLumaRowU16Unchecked(luma, luma_width, width, out);
#if HWY_TARGET == HWY_AVX2  // (the other targets' rounding average is exact for any sample)
    if (AnyAboveBitDepth(luma, std::min(luma_width, 2 * width), 14))
        for (int x = 0; x < width; ++x) out[x] = static_cast<uint16_t>(co_sited_luma(luma, luma_width, x));
#endif
}

#if HWY_TARGET == HWY_AVX3
// 10 bits in whole 512-bit vectors (blend_10bit_avx512-inl.h), rows.count rows in one call;
// the samples after the last whole 64 of a row the generic way, with the seams of their blocks.
// The co-sited averages are made from each clean row before its blend, in a pass of their own
// (made inside the luma steps they measured no faster: docs/performance-notes.md).
FG_AVX512_VBMI void BlendLumaRowsU10Avx512(const uint16_t* src, uint16_t* dst, const PlaneRows& rows,
                                           const BlockNoiseRow& noise, int width, const ScalingLookup& scaling,
                                           int scaling_shift, int min_value, int max_value,
                                           const CoSitedRows& co_sited) {
    const BlockNoiseRow first = noise;  // local: the stores cannot alias it
    auto before_row = [&](int r, const uint16_t* s) {
        if (uint16_t* out = co_sited.row(r)) CoSitedLumaRowU16Unchecked(s, width, (width + 1) / 2, out);  // (exact here)
    };
    auto steps_of = [&](int r, const BlockNoiseRow& row) {
        return LumaSkippedSteps(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride), row, width,
                                scaling, scaling_shift, min_value, max_value, nullptr);
    };
    auto rest = [&](int r, const BlockNoiseRow& row, int x, const uint32_t* seams) {
        steps_of(r, row).Tail(x, [&] {
            BlendLumaRowU16Generic(RowDown(src, r, rows.src_stride) + x, RowDown(dst, r, rows.dst_stride) + x,
                                   avx512::RowFrom(row, x, seams), width - x, scaling, scaling_shift, 10, min_value,
                                   max_value);
        });
    };
    auto left_out = [&](int r, const BlockNoiseRow& row, int vector_end) {
        steps_of(r, row).FinishSkipped(vector_end);
    };
    avx512::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA FG_AVX512_VBMI {
        avx512::Luma10Rows<decltype(overlap)::value>(src, dst, rows, first, width, scaling, scaling_shift, min_value,
                                                     max_value, before_row, rest, left_out);
    });
}
#endif

#if HWY_TARGET == HWY_AVX2
// 10 bits 64 samples per step in registers (blend_10bit_avx2-inl.h), rows.count rows in one
// call; the samples after a row's last whole 32 the generic way.
void BlendLumaRowsU10Avx2(const uint16_t* src, uint16_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                          int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                          const CoSitedRows& co_sited) {
    const BlockNoiseRow first = noise;  // local: the stores cannot alias it
    auto steps_of = [&](int r, const BlockNoiseRow& row) {
        return LumaSkippedSteps(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride), row, width,
                                scaling, scaling_shift, min_value, max_value, co_sited.row(r));
    };
    auto rest = [&](int r, const BlockNoiseRow& row, int x, uint16_t* out) {
        steps_of(r, row).Tail(x, [&] {
            const uint16_t* s = RowDown(src, r, rows.src_stride);
            if (out) CoSitedLumaRowU16Unchecked(s + x, width - x, (width + 1) / 2 - x / 2, out + x / 2);
            BlendLumaRowU16Generic(s, RowDown(dst, r, rows.dst_stride), row, width, scaling, scaling_shift, 10,
                                   min_value, max_value, x);
        });
    };
    auto left_out = [&](int r, const BlockNoiseRow& row, int vector_end) {
        steps_of(r, row).FinishSkipped(vector_end);
    };
    avx2::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA {
        avx2::Luma10Rows<decltype(overlap)::value>(src, dst, rows, first, width, scaling, scaling_shift, min_value,
                                                   max_value, co_sited, rest, left_out);
    });
}
#endif

// A row of the generic forms, checked by the row (CheckedRow): made again the scalar way where
// it holds a sample above the bit depth. (The 10-bit target forms check each step as they
// read it.)
void BlendLumaRowU16Checked(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& noise, int width,
                            const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                            int max_value, uint16_t* co_sited) {
    if (!CheckedRow(
            src == dst, [&] { return AnyAboveBitDepth(src, width, bit_depth); },
            [&] {
                if (co_sited) CoSitedLumaRowU16Unchecked(src, width, (width + 1) / 2, co_sited);
                BlendLumaRowU16Generic(src, dst, noise, width, scaling, scaling_shift, bit_depth, min_value,
                                       max_value);
            }))
        BlendLumaScalar(src, dst, noise, 0, width, width, scaling, scaling_shift, min_value, max_value, co_sited);
}

// The one place that picks a target's 10-bit form (a stripe's rows in one call); where none
// applies, row by row in the same target (no dispatch per row).
void BlendLumaRowsU16(const uint16_t* src, uint16_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                      int width, const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                      int max_value, const CoSitedRows& co_sited) {
#if HWY_TARGET == HWY_AVX3
    if (bit_depth == 10 && noise.block_width == 32 && avx512::HasAvx512Vbmi())
        return BlendLumaRowsU10Avx512(src, dst, rows, noise, width, scaling, scaling_shift, min_value, max_value,
                                      co_sited);
#endif
#if HWY_TARGET == HWY_AVX2
    if (bit_depth == 10 && noise.block_width == 32)
        return BlendLumaRowsU10Avx2(src, dst, rows, noise, width, scaling, scaling_shift, min_value, max_value,
                                    co_sited);
#endif
    BlockNoiseRow row = noise;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step)
        BlendLumaRowU16Checked(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride), row, width,
                               scaling, scaling_shift, bit_depth, min_value, max_value, co_sited.row(r));
}

// One row: the rows form with one row (the generic forms do not prefetch).
void BlendLumaRowU16(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& noise, int width,
                     const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                     uint16_t* co_sited, const uint16_t* ahead) {
    BlendLumaRowsU16(src, dst, OneRow(ahead), noise, width, scaling, scaling_shift, bit_depth, min_value, max_value,
                     CoSitedRows{co_sited});
}

// The last chroma column of an odd-width subsampled picture pairs the last luma sample with
// itself; that column is left to the scalar tail.
inline int ChromaVectorEnd(int width, int luma_width, int subsampling_x) {
    const int n = int(hn::Lanes(D16()));
    const int vec_width = (subsampling_x && (luma_width & 1)) ? width - 1 : width;
    return vec_width / n * n;
}

// Samples [x_begin, width), as BlendLumaRowU8Generic.
void BlendChromaRowU8Generic(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                             const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                             const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                             int max_value, int x_begin = 0) {
    const int vec_end = std::max(x_begin, ChromaVectorEnd(width, luma_width, subsampling_x));
    HWY_ALIGN uint8_t merged[kChunk];
    HWY_ALIGN uint8_t scale[kChunk];
    const ShuffleRows<D8> rows(scaling.table8().data(), scaling.lut8_chain());
    for (int x = x_begin; x < vec_end; x += kChunk) {
        const int chunk = std::min(kChunk, vec_end - x);
        ChromaIndicesForTarget(src, luma, x, chunk, subsampling_x, index, bit_depth, merged);
        LookUpScaling8(merged, scale, chunk, rows);
        AddBlockNoise(src, dst, noise, x, chunk, ByteScalesQ15(scale, 15 - scaling_shift), min_value, max_value);
    }
    BlendChromaScalar(
        src, dst, luma, luma_width, noise, vec_end, width, subsampling_x, index,
        [&](int merged_index, int nz) { return round2_signed(scaling(merged_index) * nz, scaling_shift); }, bit_depth,
        min_value, max_value);
}

#if HWY_TARGET == HWY_AVX3
// Whole 512-bit vectors with VBMI byte permutes (blend_u8_avx512-inl.h); the samples after
// the last whole 64 of a row go to the generic kernels, with the seams of their blocks.
FG_AVX512_VBMI void BlendLumaRowsU8Avx512(const uint8_t* src, uint8_t* dst, const PlaneRows& rows,
                                          const BlockNoiseRow& noise, int width, const ScalingLookup& scaling,
                                          int scaling_shift, int min_value, int max_value) {
    const BlockNoiseRow first = noise;  // local: the byte stores cannot alias it
    auto rest = [&](int r, const BlockNoiseRow& row, int x, const uint32_t* seams) {
        BlendLumaRowU8Generic(src + r * rows.src_stride + x, dst + r * rows.dst_stride + x,
                              avx512::RowFrom(row, x, seams), width - x, scaling, scaling_shift, min_value, max_value);
    };
    avx512::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA FG_AVX512_VBMI {
        avx512::WithFlag(min_value > 0 || max_value < 255, [&](auto clip) FG_INLINE_LAMBDA FG_AVX512_VBMI {
            constexpr avx512::Overlap kOverlap = decltype(overlap)::value;
            if constexpr (kOverlap != avx512::Overlap::kGivenSeams)
                if (first.byte_blocks)
                    return avx512::LumaRows<kOverlap, decltype(clip)::value, true>(
                        src, dst, rows, first, width, scaling, scaling_shift, min_value, max_value, rest);
            avx512::LumaRows<kOverlap, decltype(clip)::value, false>(src, dst, rows, first, width, scaling,
                                                                    scaling_shift, min_value, max_value, rest);
        });
    });
}

FG_AVX512_VBMI void BlendChromaRowsU8Avx512(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                                            const PlaneRows& rows, const BlockNoiseRow& noise, int width,
                                            int subsampling_x, const ChromaScalingIndex& index,
                                            const ScalingLookup& scaling, int scaling_shift, int bit_depth,
                                            int min_value, int max_value) {
    const BlockNoiseRow first = noise;  // local: the byte stores cannot alias it
    auto rest = [&](int r, const BlockNoiseRow& row, int x, const uint32_t* seams) {
        BlendChromaRowU8Generic(src + r * rows.src_stride + x, dst + r * rows.dst_stride + x,
                                luma + r * rows.luma_stride + (x << subsampling_x), luma_width - (x << subsampling_x),
                                avx512::RowFrom(row, x, seams), width - x, subsampling_x, index, scaling,
                                scaling_shift, bit_depth, min_value, max_value);
    };
    avx512::WithFlag(subsampling_x != 0, [&](auto subsampled) FG_INLINE_LAMBDA FG_AVX512_VBMI {
        avx512::WithFlag(index.from_luma, [&](auto from_luma) FG_INLINE_LAMBDA FG_AVX512_VBMI {
            avx512::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA FG_AVX512_VBMI {
                avx512::WithFlag(min_value > 0 || max_value < 255, [&](auto clip) FG_INLINE_LAMBDA FG_AVX512_VBMI {
                    avx512::ChromaRows<decltype(subsampled)::value, decltype(from_luma)::value,
                                       decltype(overlap)::value, decltype(clip)::value>(
                        src, dst, luma, luma_width, rows, first, width, index, scaling, scaling_shift, min_value,
                        max_value, rest);
                });
            });
        });
    });
}
#endif

#if HWY_TARGET == HWY_AVX2
// 64 samples per step with the indices, scales and sums in registers (blend_u8_avx2-inl.h);
// the samples after the last whole 32 of a row go to the generic kernels.
void BlendLumaRowsU8Avx2(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                         int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
    const BlockNoiseRow first = noise;  // local: the byte stores cannot alias it
    auto rest = [&](int r, const BlockNoiseRow& row, int x) {
        BlendLumaRowU8Generic(src + r * rows.src_stride, dst + r * rows.dst_stride, row, width, scaling,
                              scaling_shift, min_value, max_value, x);
    };
    avx2::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA {
        avx2::WithFlag(min_value > 0 || max_value < 255, [&](auto clip) FG_INLINE_LAMBDA {
            constexpr avx2::Overlap kOverlap = decltype(overlap)::value;
            if constexpr (kOverlap != avx2::Overlap::kGivenSeams)
                if (first.byte_blocks)
                    return avx2::LumaRows<kOverlap, decltype(clip)::value, true>(
                        src, dst, rows, first, width, scaling, scaling_shift, min_value, max_value, rest);
            avx2::LumaRows<kOverlap, decltype(clip)::value, false>(src, dst, rows, first, width, scaling,
                                                                  scaling_shift, min_value, max_value, rest);
        });
    });
}

void BlendChromaRowsU8Avx2(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                           const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                           const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                           int bit_depth, int min_value, int max_value) {
    const BlockNoiseRow first = noise;  // local: the byte stores cannot alias it
    auto rest = [&](int r, const BlockNoiseRow& row, int x) {
        BlendChromaRowU8Generic(src + r * rows.src_stride, dst + r * rows.dst_stride, luma + r * rows.luma_stride,
                                luma_width, row, width, subsampling_x, index, scaling, scaling_shift, bit_depth,
                                min_value, max_value, x);
    };
    avx2::WithFlag(subsampling_x != 0, [&](auto subsampled) FG_INLINE_LAMBDA {
        avx2::WithFlag(index.from_luma, [&](auto from_luma) FG_INLINE_LAMBDA {
            avx2::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA {
                avx2::WithFlag(min_value > 0 || max_value < 255, [&](auto clip) FG_INLINE_LAMBDA {
                    avx2::ChromaRows<decltype(subsampled)::value, decltype(from_luma)::value,
                                     decltype(overlap)::value, decltype(clip)::value>(
                        src, dst, luma, luma_width, rows, first, width, index, scaling, scaling_shift, min_value,
                        max_value, rest);
                });
            });
        });
    });
}
#endif

bool LumaRowsReadByteNoise() {
#if HWY_TARGET == HWY_AVX3
    return avx512::HasAvx512Vbmi();  // BlendLumaRowsU8Avx512
#elif HWY_TARGET == HWY_AVX2
    return true;  // BlendLumaRowsU8Avx2
#else
    return false;
#endif
}

// Row by row where no target form takes several (each row one call of the same target: no
// dispatch per row).
void BlendLumaRowsU8(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise, int width,
                     const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
#if HWY_TARGET == HWY_AVX3
    if (noise.block_width == 32 && avx512::HasAvx512Vbmi())
        return BlendLumaRowsU8Avx512(src, dst, rows, noise, width, scaling, scaling_shift, min_value, max_value);
#endif
#if HWY_TARGET == HWY_AVX2
    if (noise.block_width == 32)
        return BlendLumaRowsU8Avx2(src, dst, rows, noise, width, scaling, scaling_shift, min_value, max_value);
#endif
    BlockNoiseRow row = noise;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step)
        BlendLumaRowU8Generic(src + r * rows.src_stride, dst + r * rows.dst_stride, row, width, scaling,
                              scaling_shift, min_value, max_value);
}

void BlendChromaRowsU8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width, const PlaneRows& rows,
                       const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                       const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value) {
#if HWY_TARGET == HWY_AVX3
    // (the vector forms take the block width the subsampling gives)
    if (noise.block_width == (subsampling_x ? 16 : 32) && avx512::HasAvx512Vbmi())
        return BlendChromaRowsU8Avx512(src, dst, luma, luma_width, rows, noise, width, subsampling_x, index, scaling,
                                       scaling_shift, bit_depth, min_value, max_value);
#endif
#if HWY_TARGET == HWY_AVX2
    if (noise.block_width == (subsampling_x ? 16 : 32))
        return BlendChromaRowsU8Avx2(src, dst, luma, luma_width, rows, noise, width, subsampling_x, index, scaling,
                                     scaling_shift, bit_depth, min_value, max_value);
#endif
    BlockNoiseRow row = noise;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step)
        BlendChromaRowU8Generic(src + r * rows.src_stride, dst + r * rows.dst_stride, luma + r * rows.luma_stride,
                                luma_width, row, width, subsampling_x, index, scaling, scaling_shift, bit_depth,
                                min_value, max_value);
}

void BlendLumaRowU8(const uint8_t* src, uint8_t* dst, const BlockNoiseRow& noise, int width,
                    const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
    BlendLumaRowsU8(src, dst, PlaneRows{}, noise, width, scaling, scaling_shift, min_value, max_value);
}

void BlendChromaRowU8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                      const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                      const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value) {
    BlendChromaRowsU8(src, dst, luma, luma_width, PlaneRows{}, noise, width, subsampling_x, index, scaling,
                      scaling_shift, bit_depth, min_value, max_value);
}

void BlendChromaRowU16Generic(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                              const BlockNoiseRow& noise, int width, int subsampling_x,
                              const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                              int bit_depth, int min_value, int max_value, int x_begin = 0) {
    const int vec_end = std::max(x_begin, ChromaVectorEnd(width, luma_width, subsampling_x));
    HWY_ALIGN int16_t merged[kChunk];
    InterpolatedScales scales(scaling, bit_depth, scaling_shift);
    for (int x = x_begin; x < vec_end; x += kChunk) {
        const int chunk = std::min(kChunk, vec_end - x);
        ChromaIndicesForTarget(src, luma, x, chunk, subsampling_x, index, bit_depth, merged);
        scales.LookUp(merged, chunk);
        AddBlockNoise(src, dst, noise, x, chunk, [&](int k) { return scales.At(k); }, min_value, max_value);
    }
    BlendChromaScalar(
        src, dst, luma, luma_width, noise, vec_end, width, subsampling_x, index,
        [&](int merged_index, int nz) { return round2_signed(scales.Scalar(merged_index) * nz, scaling_shift); },
        bit_depth, min_value, max_value);
}

#if HWY_TARGET == HWY_AVX3
// 10 bits with unsubsampled (or shared co-sited) luma in whole 512-bit vectors
// (blend_10bit_avx512-inl.h), rows.count rows in one call; the samples after the last whole 64
// of a row the generic way.
FG_AVX512_VBMI void BlendChromaRowsU10Avx512(const uint16_t* src, uint16_t* dst, const uint16_t* luma,
                                             int luma_width, const PlaneRows& rows, const BlockNoiseRow& noise,
                                             int width, const ChromaScalingIndex& index,
                                             const ScalingLookup& scaling, int scaling_shift, int min_value,
                                             int max_value) {
    const BlockNoiseRow first = noise;  // local: the stores cannot alias it
    auto steps_of = [&](int r, const BlockNoiseRow& row) {
        return ChromaSkippedSteps(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride),
                                  RowDown(luma, r, rows.luma_stride), luma_width, row, width, index, scaling,
                                  scaling_shift, min_value, max_value);
    };
    auto rest = [&](int r, const BlockNoiseRow& row, int x, const uint32_t* seams) {
        steps_of(r, row).Tail(x, [&] {
            BlendChromaRowU16Generic(RowDown(src, r, rows.src_stride) + x, RowDown(dst, r, rows.dst_stride) + x,
                                     RowDown(luma, r, rows.luma_stride) + x, luma_width - x,
                                     avx512::RowFrom(row, x, seams), width - x, 0, index, scaling, scaling_shift,
                                     10, min_value, max_value);
        });
    };
    auto left_out = [&](int r, const BlockNoiseRow& row, int vector_end) {
        steps_of(r, row).FinishSkipped(vector_end);
    };
    avx512::WithFlag(first.block_width == 16, [&](auto narrow) FG_INLINE_LAMBDA FG_AVX512_VBMI {
        avx512::WithFlag(index.from_luma, [&](auto from_luma) FG_INLINE_LAMBDA FG_AVX512_VBMI {
            avx512::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA FG_AVX512_VBMI {
                avx512::Chroma10Rows<decltype(narrow)::value ? 16 : 32, decltype(from_luma)::value,
                                     decltype(overlap)::value>(src, dst, luma, rows, first, width, index, scaling,
                                                               scaling_shift, min_value, max_value, rest, left_out);
            });
        });
    });
}
#endif

#if HWY_TARGET == HWY_AVX2
// 10 bits with unsubsampled (or shared co-sited) luma, 64 samples per step in registers
// (blend_10bit_avx2-inl.h), rows.count rows in one call; the samples after a row's last whole
// 32 the generic way.
void BlendChromaRowsU10Avx2(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                            const PlaneRows& rows, const BlockNoiseRow& noise, int width,
                            const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                            int min_value, int max_value) {
    const BlockNoiseRow first = noise;  // local: the stores cannot alias it
    auto steps_of = [&](int r, const BlockNoiseRow& row) {
        return ChromaSkippedSteps(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride),
                                  RowDown(luma, r, rows.luma_stride), luma_width, row, width, index, scaling,
                                  scaling_shift, min_value, max_value);
    };
    auto rest = [&](int r, const BlockNoiseRow& row, int x) {
        steps_of(r, row).Tail(x, [&] {
            BlendChromaRowU16Generic(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride),
                                     RowDown(luma, r, rows.luma_stride), luma_width, row, width, 0, index, scaling,
                                     scaling_shift, 10, min_value, max_value, x);
        });
    };
    auto left_out = [&](int r, const BlockNoiseRow& row, int vector_end) {
        steps_of(r, row).FinishSkipped(vector_end);
    };
    avx2::WithFlag(first.block_width == 16, [&](auto narrow) FG_INLINE_LAMBDA {
        avx2::WithFlag(index.from_luma, [&](auto from_luma) FG_INLINE_LAMBDA {
            avx2::WithOverlap(first, [&](auto overlap) FG_INLINE_LAMBDA {
                avx2::Chroma10Rows<decltype(narrow)::value ? 16 : 32, decltype(from_luma)::value,
                                   decltype(overlap)::value>(src, dst, luma, rows, first, width, index, scaling,
                                                             scaling_shift, min_value, max_value, rest, left_out);
            });
        });
    });
}
#endif

// As BlendLumaRowU16Checked.
void BlendChromaRowU16Checked(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                              const BlockNoiseRow& noise, int width, int subsampling_x,
                              const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                              int bit_depth, int min_value, int max_value) {
    const int luma_read = std::min(luma_width, width << subsampling_x);
    if (!CheckedRow(
            src == dst,
            [&] { return AnyAboveBitDepth(src, width, bit_depth) || AnyAboveBitDepth(luma, luma_read, bit_depth); },
            [&] {
                BlendChromaRowU16Generic(src, dst, luma, luma_width, noise, width, subsampling_x, index, scaling,
                                         scaling_shift, bit_depth, min_value, max_value);
            }))
        BlendChromaLookedUp(src, dst, luma, luma_width, noise, 0, width, subsampling_x, index, scaling, scaling_shift,
                            bit_depth, min_value, max_value);
}

// As BlendLumaRowsU16: the one place that picks a target's 10-bit form.
void BlendChromaRowsU16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                        const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                        const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                        int bit_depth, int min_value, int max_value) {
#if HWY_TARGET == HWY_AVX3
    if (bit_depth == 10 && subsampling_x == 0 && (noise.block_width == 16 || noise.block_width == 32) &&
        avx512::HasAvx512Vbmi())
        return BlendChromaRowsU10Avx512(src, dst, luma, luma_width, rows, noise, width, index, scaling,
                                        scaling_shift, min_value, max_value);
#endif
#if HWY_TARGET == HWY_AVX2
    if (bit_depth == 10 && subsampling_x == 0 && (noise.block_width == 16 || noise.block_width == 32))
        return BlendChromaRowsU10Avx2(src, dst, luma, luma_width, rows, noise, width, index, scaling,
                                      scaling_shift, min_value, max_value);
#endif
    BlockNoiseRow row = noise;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step)
        BlendChromaRowU16Checked(RowDown(src, r, rows.src_stride), RowDown(dst, r, rows.dst_stride),
                                 RowDown(luma, r, rows.luma_stride), luma_width, row, width, subsampling_x, index,
                                 scaling, scaling_shift, bit_depth, min_value, max_value);
}

void BlendChromaRowU16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                       const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                       const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                       const uint16_t* ahead) {
    BlendChromaRowsU16(src, dst, luma, luma_width, OneRow(ahead), noise, width, subsampling_x, index, scaling,
                       scaling_shift, bit_depth, min_value, max_value);
}

// A row's noise written out flat (the rows a stripe shares with the one above, which are
// cross-faded before use), block by block as AddBlockNoise reads it.
void AssembleNoiseRow(const BlockNoiseRow& noise_row, int width, int16_t* out) {
    const D16 d16;
    const int n = int(hn::Lanes(d16));
    const BlockNoiseRow row = noise_row;  // local: the int16 stores cannot alias it
    const FadeConstants fade = FadeConstantsOf(row);
    const int vec_end = n >= 2 ? width / n * n : 0;
    const int bw = row.block_width;
    for (int x = 0, b = 0; x < vec_end; x += bw, ++b)
        for (int j = 0; j < std::min(bw, vec_end - x); j += n)
            hn::StoreU(BlockNoiseAt(d16, row, b, j, fade), d16, out + x + j);
    for (int x = vec_end; x < width; ++x) out[x] = row.at(x);
}

// The vertical overlap fused with the assembly of both rows: no row is written twice. Up to
// 10 bits the weighted sum fits 16-bit lanes (|noise| <= 512, weights summing to at most 45)
// and Round2(sum, 5) is a rounding high multiply by 1 << 10, as in FirstNoiseOfBlock.
void AssembleCrossFadedRowGeneric(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise, int width,
                                  int old_weight, int new_weight, int16_t* out) {
    const D16 d16;
    const int n = int(hn::Lanes(d16));
    const BlockNoiseRow above = old_noise, own = new_noise;  // local: the stores cannot alias them
    const FadeConstants fade_above = FadeConstantsOf(above), fade_own = FadeConstantsOf(own);
    const auto w_old = hn::Set(d16, int16_t(old_weight)), w_new = hn::Set(d16, int16_t(new_weight));
    const auto gmin = hn::Set(d16, own.gmin), gmax = hn::Set(d16, own.gmax), round = hn::Set(d16, int16_t(1 << 10));
    const int vec_end = n >= 2 ? width / n * n : 0;
    const int bw = own.block_width;
    auto store_mix = [&](int at, hn::Vec<D16> a, hn::Vec<D16> o) FG_INLINE_LAMBDA {
        const auto sum = hn::Add(hn::Mul(a, w_old), hn::Mul(o, w_new));
        hn::StoreU(hn::Min(hn::Max(hn::MulFixedPoint15(sum, round), gmin), gmax), d16, out + at);
    };
    int x = 0, b = 0;
    // Whole blocks of one or two vectors where both rows overlap alike (the rows of one
    // plane: faded here or not at all), the form fixed for the loop, so that a block costs
    // its vectors and no tests of the overlap's form (the blocks one by one took 8 % of an
    // 8-bit frame on AVX2 for the 2 rows in 32 that cross-fade).
    if (n >= 2 && bw % n == 0 && bw / n <= 2 && !above.seams && !own.seams && above.fade == own.fade &&
        above.block_width == bw) {
        auto whole_blocks = [&](auto vectors, auto fade) FG_INLINE_LAMBDA {
            constexpr int kVectors = decltype(vectors)::value;
            for (; x + kVectors * n <= vec_end; x += kVectors * n, ++b) {
                const int16_t* a = above.block(b);
                const int16_t* o = own.block(b);
                auto first_a = hn::LoadU(d16, a), first_o = hn::LoadU(d16, o);
                if constexpr (decltype(fade)::value) {
                    if (b > 0) {
                        first_a = FadeOfBlock(d16, above, b, first_a, fade_above);
                        first_o = FadeOfBlock(d16, own, b, first_o, fade_own);
                    }
                }
                store_mix(x, first_a, first_o);
                if constexpr (kVectors == 2) store_mix(x + n, hn::LoadU(d16, a + n), hn::LoadU(d16, o + n));
            }
        };
        auto with_fade = [&](auto vectors) FG_INLINE_LAMBDA {
            if (own.fade)
                whole_blocks(vectors, std::true_type());
            else
                whole_blocks(vectors, std::false_type());
        };
        if (bw == n)
            with_fade(std::integral_constant<int, 1>());
        else
            with_fade(std::integral_constant<int, 2>());
    }
    for (; x < vec_end; x += bw, ++b)
        for (int j = 0; j < std::min(bw, vec_end - x); j += n)
            store_mix(x + j, BlockNoiseAt(d16, above, b, j, fade_above), BlockNoiseAt(d16, own, b, j, fade_own));
    for (x = vec_end; x < width; ++x) {
        const int v = (above.at(x) * old_weight + own.at(x) * new_weight + 16) >> 5;
        out[x] = int16_t(v < own.gmin ? own.gmin : v > own.gmax ? own.gmax : v);
    }
}

#if HWY_TARGET == HWY_AVX3
// Whole 512-bit vectors (blend_u8_avx512-inl.h), for the block widths the synthesis makes; the
// samples after the last whole 64 (with the seams of their blocks) the generic way.
FG_AVX512_VBMI void AssembleCrossFadedRowAvx512(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise,
                                                int width, int old_weight, int new_weight, int16_t* out) {
    auto rest = [&](int x) {
        auto seams = [&](const BlockNoiseRow& row, uint32_t* faded) {
            const int bw = row.block_width;
            for (int b = x / bw, k = 0; b * bw < width; ++b, ++k)
                faded[k] = uint32_t(uint16_t(row.at(b * bw))) | uint32_t(uint16_t(row.at(b * bw + 1))) << 16;
            return row.fade ? faded : nullptr;
        };
        uint32_t above[64 / 16 + 1], own[64 / 16 + 1];
        AssembleCrossFadedRowGeneric(avx512::RowFrom(old_noise, x, seams(old_noise, above)),
                                     avx512::RowFrom(new_noise, x, seams(new_noise, own)), width - x, old_weight,
                                     new_weight, out + x);
    };
    avx512::WithFlag(new_noise.fade, [&](auto fade) FG_INLINE_LAMBDA FG_AVX512_VBMI {
        if (new_noise.block_width == 16)
            avx512::CrossFadedRow<16, decltype(fade)::value>(old_noise, new_noise, width, old_weight, new_weight, out,
                                                             rest);
        else
            avx512::CrossFadedRow<32, decltype(fade)::value>(old_noise, new_noise, width, old_weight, new_weight, out,
                                                             rest);
    });
}
#endif

void AssembleCrossFadedRow(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise, int width, int old_weight,
                           int new_weight, int16_t* out) {
#if HWY_TARGET == HWY_AVX3
    // both rows alike (the same plane): no given seams, fade or not, blocks of 16 or 32
    const bool whole_vectors = !old_noise.seams && !new_noise.seams && old_noise.fade == new_noise.fade &&
                               old_noise.block_width == new_noise.block_width &&
                               (new_noise.block_width == 16 || new_noise.block_width == 32);
    if (whole_vectors && avx512::HasAvx512Vbmi())
        return AssembleCrossFadedRowAvx512(old_noise, new_noise, width, old_weight, new_weight, out);
#endif
    AssembleCrossFadedRowGeneric(old_noise, new_noise, width, old_weight, new_weight, out);
}

void CrossFadeRow(const int16_t* old_row, int16_t* cur, int width, int old_weight, int new_weight, int gmin,
                  int gmax) {
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<int16_t, decltype(d32)> d16;
    const int n = int(hn::Lanes(d32));
    const auto wo = hn::Set(d32, old_weight), wn = hn::Set(d32, new_weight), r = hn::Set(d32, 16);
    const auto lo = hn::Set(d32, gmin), hi = hn::Set(d32, gmax);
    int x = 0;
    for (; x + n <= width; x += n) {
        const auto o = hn::PromoteTo(d32, hn::LoadU(d16, old_row + x));
        const auto c = hn::PromoteTo(d32, hn::LoadU(d16, cur + x));
        const auto v = hn::ShiftRight<5>(hn::Add(hn::Add(hn::Mul(o, wo), hn::Mul(c, wn)), r));
        hn::StoreU(hn::DemoteTo(d16, hn::Min(hn::Max(v, lo), hi)), d16, cur + x);
    }
    for (; x < width; ++x) {
        const int v = (old_row[x] * old_weight + cur[x] * new_weight + 16) >> 5;
        cur[x] = static_cast<int16_t>(v < gmin ? gmin : v > gmax ? gmax : v);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::av1::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::av1::simd {

HWY_EXPORT(BlendLumaRowU8);
HWY_EXPORT(BlendLumaRowU16);
HWY_EXPORT(BlendChromaRowU8);
HWY_EXPORT(BlendLumaRowsU8);
HWY_EXPORT(LumaRowsReadByteNoise);
HWY_EXPORT(BlendChromaRowsU8);
HWY_EXPORT(BlendChromaRowU16);
HWY_EXPORT(BlendLumaRowsU16);
HWY_EXPORT(BlendChromaRowsU16);
HWY_EXPORT(CrossFadeRow);
HWY_EXPORT(CoSitedLumaRowU16);
HWY_EXPORT(AssembleNoiseRow);
HWY_EXPORT(AssembleCrossFadedRow);

void blend_luma_row_u8(const uint8_t* src, uint8_t* dst, const BlockNoiseRow& noise, int width,
                       const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowU8)(src, dst, noise, width, scaling, scaling_shift, min_value, max_value);
}
bool luma_rows_read_byte_noise() { return HWY_DYNAMIC_DISPATCH(LumaRowsReadByteNoise)(); }

void copy_noise_as_bytes(const std::vector<int16_t>& samples, std::vector<int8_t>& out) {
    out.assign(samples.size() + kByteNoiseReadBytes, 0);
    std::transform(samples.begin(), samples.end(), out.begin(), [](int16_t v) { return int8_t(v); });
}

void blend_luma_rows_u8(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                        int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowsU8)(src, dst, rows, noise, width, scaling, scaling_shift, min_value, max_value);
}
void blend_chroma_rows_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                          const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                          const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                          int bit_depth, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowsU8)(src, dst, luma, luma_width, rows, noise, width, subsampling_x, index,
                                            scaling, scaling_shift, bit_depth, min_value, max_value);
}
void blend_luma_row_u16(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& noise, int width,
                        const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                        uint16_t* co_sited, const uint16_t* ahead) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowU16)(src, dst, noise, width, scaling, scaling_shift, bit_depth, min_value,
                                          max_value, co_sited, ahead);
}
void blend_luma_rows_u16(const uint16_t* src, uint16_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                         int width, const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                         int max_value, const CoSitedRows& co_sited) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowsU16)(src, dst, rows, noise, width, scaling, scaling_shift, bit_depth,
                                           min_value, max_value, co_sited);
}
void blend_chroma_rows_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                           const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                           const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                           int bit_depth, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowsU16)(src, dst, luma, luma_width, rows, noise, width, subsampling_x, index,
                                             scaling, scaling_shift, bit_depth, min_value, max_value);
}
void blend_chroma_row_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                         const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                         const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowU8)(src, dst, luma, luma_width, noise, width, subsampling_x, index, scaling,
                                           scaling_shift, bit_depth, min_value, max_value);
}
void blend_chroma_row_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                          const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                          const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                          const uint16_t* ahead) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowU16)(src, dst, luma, luma_width, noise, width, subsampling_x, index, scaling,
                                            scaling_shift, bit_depth, min_value, max_value, ahead);
}
void cross_fade_row(const int16_t* old_row, int16_t* cur, int width, int old_weight, int new_weight, int gmin,
                    int gmax) {
    HWY_DYNAMIC_DISPATCH(CrossFadeRow)(old_row, cur, width, old_weight, new_weight, gmin, gmax);
}
void co_sited_luma_row_u16(const uint16_t* luma, int luma_width, int width, uint16_t* out) {
    HWY_DYNAMIC_DISPATCH(CoSitedLumaRowU16)(luma, luma_width, width, out);
}
void assemble_noise_row(const BlockNoiseRow& noise, int width, int16_t* out) {
    HWY_DYNAMIC_DISPATCH(AssembleNoiseRow)(noise, width, out);
}
void assemble_cross_faded_row(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise, int width,
                              int old_weight, int new_weight, int16_t* out) {
    HWY_DYNAMIC_DISPATCH(AssembleCrossFadedRow)(old_noise, new_noise, width, old_weight, new_weight, out);
}

}  // namespace filmgrain::av1::simd
#endif  // HWY_ONCE

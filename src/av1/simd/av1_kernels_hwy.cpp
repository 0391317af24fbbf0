// Highway implementations of av1_kernels.hpp, compiled once per target (foreach_target).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "av1/simd/av1_kernels_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <algorithm>

#include "av1/simd/av1_kernels.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::av1::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Round2(scale * noise, shift) added to the sample and clipped, in int32 lanes (the
// product needs up to 9 + 13 bits at 12-bit depth).
template <class D, class V>
HWY_INLINE V AddScaledNoise(D d, V orig, V scale, V noise, int shift, V round, V vmin, V vmax) {
    const auto n = hn::ShiftRightSame(hn::Add(hn::Mul(scale, noise), round), shift);
    (void)d;
    return hn::Min(hn::Max(hn::Add(orig, n), vmin), vmax);
}

template <typename Pixel>
void BlendLumaRow(const Pixel* src, Pixel* dst, const int16_t* noise, int width, const int32_t* scaling,
                  int scaling_shift, int min_value, int max_value) {
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<Pixel, decltype(d32)> dp;
    const hn::Rebind<int16_t, decltype(d32)> d16;
    const int n = int(hn::Lanes(d32));
    const auto round = hn::Set(d32, 1 << (scaling_shift - 1));
    const auto vmin = hn::Set(d32, min_value), vmax = hn::Set(d32, max_value);
    int x = 0;
    for (; x + n <= width; x += n) {
        const auto orig = hn::PromoteTo(d32, hn::LoadU(dp, src + x));
        const auto scale = hn::GatherIndex(d32, scaling, orig);
        const auto nz = hn::PromoteTo(d32, hn::LoadU(d16, noise + x));
        hn::StoreU(hn::DemoteTo(dp, AddScaledNoise(d32, orig, scale, nz, scaling_shift, round, vmin, vmax)), dp,
                   dst + x);
    }
    for (; x < width; ++x) {
        const int orig = src[x];
        const int v = orig + round2_signed(scaling[orig] * noise[x], scaling_shift);
        dst[x] = static_cast<Pixel>(v < min_value ? min_value : v > max_value ? max_value : v);
    }
}

// Luma co-sited with chroma lanes [x, x + n): the average of each horizontal pair when
// subsampled. Pairs are read as one wider lane and split, which needs no shuffles.
template <typename Pixel, class D32>
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

// The chroma scaling index of AV1 7.18.3.5 in int32 lanes: the co-sited luma when chroma
// scales from luma, else (luma * cb_luma_mult + chroma * cb_mult) >> 6 plus the offset,
// clipped to the sample range. `orig` is only read in the second case.
template <class D32, class V>
HWY_INLINE V ChromaScalingIndexLanes(D32 d32, V avg_luma, V orig, bool from_luma, V luma_mult, V mult, V offset,
                                     V pixel_max) {
    if (from_luma) return avg_luma;
    const auto combined = hn::Add(hn::Mul(avg_luma, luma_mult), hn::Mul(orig, mult));
    return hn::Min(hn::Max(hn::Add(hn::ShiftRight<6>(combined), offset), hn::Zero(d32)), pixel_max);
}

// Above 8 bits: `count` samples (a multiple of the lane count) whose scaling values were
// looked up into `scale`, scaled noise added in int32 lanes.
template <class D32>
HWY_INLINE void AddLookedUpNoiseU16(D32 d32, const uint16_t* src, uint16_t* dst, const int16_t* noise,
                                    const int32_t* scale, int count, int scaling_shift, hn::Vec<D32> round,
                                    hn::Vec<D32> vmin, hn::Vec<D32> vmax) {
    const hn::Rebind<uint16_t, D32> dp;
    const hn::Rebind<int16_t, D32> d16;
    for (int k = 0; k < count; k += int(hn::Lanes(d32))) {
        const auto orig = hn::PromoteTo(d32, hn::LoadU(dp, src + k));
        const auto nz = hn::PromoteTo(d32, hn::LoadU(d16, noise + k));
        hn::StoreU(hn::DemoteTo(dp, AddScaledNoise(d32, orig, hn::Load(d32, scale + k), nz, scaling_shift, round,
                                                   vmin, vmax)),
                   dp, dst + k);
    }
}

// The samples the vector loops leave, one by one (AV1 7.18.3.5), from an int32 or a byte
// scaling table.
template <typename Pixel, typename Scale>
void BlendChromaScalar(const Pixel* src, Pixel* dst, const Pixel* luma, int luma_width, const int16_t* noise, int x,
                       int width, int subsampling_x, const ChromaScalingIndex& index, const Scale* scaling,
                       int scaling_shift, int bit_depth, int min_value, int max_value) {
    const int pixel_max = (1 << bit_depth) - 1;
    for (; x < width; ++x) {
        const int lx = x << subsampling_x;
        int average_luma = luma[lx];
        if (subsampling_x) {
            const int rx = lx + 1 < luma_width ? lx + 1 : luma_width - 1;
            average_luma = (average_luma + luma[rx] + 1) >> 1;
        }
        const int orig = src[x];
        int merged;
        if (index.from_luma) {
            merged = average_luma;
        } else {
            const int combined = average_luma * index.luma_mult + orig * index.mult;
            merged = (combined >> 6) + index.offset * (1 << (bit_depth - 8));
            merged = merged < 0 ? 0 : merged > pixel_max ? pixel_max : merged;
        }
        const int v = orig + round2_signed(scaling[merged] * noise[x], scaling_shift);
        dst[x] = static_cast<Pixel>(v < min_value ? min_value : v > max_value ? max_value : v);
    }
}

template <typename Pixel>
void BlendChromaRow(const Pixel* src, Pixel* dst, const Pixel* luma, int luma_width, const int16_t* noise, int width,
                    int subsampling_x, const ChromaScalingIndex& index, const int32_t* scaling, int scaling_shift,
                    int bit_depth, int min_value, int max_value) {
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<Pixel, decltype(d32)> dp;
    const hn::Rebind<int16_t, decltype(d32)> d16;
    const int n = int(hn::Lanes(d32));
    const int pixel_max = (1 << bit_depth) - 1;
    const auto round = hn::Set(d32, 1 << (scaling_shift - 1));
    const auto vmin = hn::Set(d32, min_value), vmax = hn::Set(d32, max_value);
    const auto luma_mult = hn::Set(d32, index.luma_mult), mult = hn::Set(d32, index.mult);
    const auto offset = hn::Set(d32, index.offset * (1 << (bit_depth - 8)));
    const auto vpixel_max = hn::Set(d32, pixel_max);
    // The last chroma column of an odd-width subsampled picture pairs the last luma sample
    // with itself; that column is left to the scalar tail.
    const int vec_width = (subsampling_x && (luma_width & 1)) ? width - 1 : width;
    int x = 0;
    for (; x + n <= vec_width; x += n) {
        const auto avg_luma = CositedLuma(d32, luma, x, subsampling_x);
        const auto orig = hn::PromoteTo(d32, hn::LoadU(dp, src + x));
        const auto merged =
            ChromaScalingIndexLanes(d32, avg_luma, orig, index.from_luma, luma_mult, mult, offset, vpixel_max);
        const auto scale = hn::GatherIndex(d32, scaling, merged);
        const auto nz = hn::PromoteTo(d32, hn::LoadU(d16, noise + x));
        hn::StoreU(hn::DemoteTo(dp, AddScaledNoise(d32, orig, scale, nz, scaling_shift, round, vmin, vmax)), dp,
                   dst + x);
    }
    BlendChromaScalar(src, dst, luma, luma_width, noise, x, width, subsampling_x, index, scaling, scaling_shift,
                      bit_depth, min_value, max_value);
}

// 8 bits: the scaling function is the spec's 256-byte ScalingLut (values 0..255, made once
// per parameter set) and the look-up sixteen 16-entry byte shuffles, one per high nibble of
// the index, each kept where that nibble matches. Three vector operations per 16 entries
// replace a scalar load and store per sample, which were the bound of the 8-bit blends.
HWY_INLINE void LookUpScaling8(const uint8_t* index, uint8_t* out, int count, const uint8_t* table) {
    const hn::ScalableTag<uint8_t> du8;
    const int n = int(hn::Lanes(du8));
    const auto low_mask = hn::Set(du8, uint8_t(15));
    int k = 0;
    // Byte shuffles need whole 16-byte blocks: a one-lane (scalar) target loads instead.
    for (; n >= 16 && k + n <= count; k += n) {
        const auto x = hn::LoadU(du8, index + k);
        const auto lo = hn::And(x, low_mask);
        const auto hi = hn::ShiftRight<4>(x);
        auto r = hn::TableLookupBytes(hn::LoadDup128(du8, table), lo);
        for (int j = 1; j < 16; ++j)
            r = hn::IfThenElse(hn::Eq(hi, hn::Set(du8, uint8_t(j))),
                               hn::TableLookupBytes(hn::LoadDup128(du8, table + 16 * j), lo), r);
        hn::StoreU(r, du8, out + k);
    }
    for (; k < count; ++k) out[k] = table[index[k]];
}

// 8 bits: scale * noise fits int16 (255 * 128), and Round2(x, s) equals
// ((x >> (s - 1)) + 1) >> 1, which stays in int16 too. The 256-entry scaling look-up is done
// with scalar loads into a small buffer: on the CPUs measured that beats vector gathers.
void BlendLumaRowU8(const uint8_t* src, uint8_t* dst, const int16_t* noise, int width, const uint8_t* scaling,
                    int scaling_shift, int min_value, int max_value) {
    const hn::ScalableTag<int16_t> d16;
    const hn::Rebind<uint8_t, decltype(d16)> d8;
    const hn::Rebind<uint16_t, decltype(d16)> du16;
    const int n = int(hn::Lanes(d16));
    const auto vmin = hn::Set(d16, int16_t(min_value)), vmax = hn::Set(d16, int16_t(max_value));
    const auto one = hn::Set(d16, int16_t(1));
    constexpr int kChunk = 256;
    HWY_ALIGN uint8_t scale[kChunk];
    int x = 0;
    while (x + n <= width) {
        const int chunk = std::min(kChunk, (width - x) / n * n);
        LookUpScaling8(src + x, scale, chunk, scaling);
        for (int k = 0; k < chunk; k += n) {
            const auto s16 = hn::BitCast(d16, hn::PromoteTo(du16, hn::Load(d8, scale + k)));
            const auto prod = hn::Mul(s16, hn::LoadU(d16, noise + x + k));
            const auto add = hn::ShiftRight<1>(hn::Add(hn::ShiftRightSame(prod, scaling_shift - 1), one));
            const auto orig = hn::BitCast(d16, hn::PromoteTo(du16, hn::LoadU(d8, src + x + k)));
            const auto v = hn::Min(hn::Max(hn::Add(orig, add), vmin), vmax);
            hn::StoreU(hn::DemoteTo(d8, v), d8, dst + x + k);
        }
        x += chunk;
    }
    for (; x < width; ++x) {
        const int orig = src[x];
        const int v = orig + round2_signed(scaling[orig] * noise[x], scaling_shift);
        dst[x] = static_cast<uint8_t>(v < min_value ? min_value : v > max_value ? max_value : v);
    }
}
// Above 8 bits the product needs int32 lanes, but the look-up is still done as for 8 bits:
// scalar loads into a buffer measured faster than GatherIndex on the CPUs tried.
void BlendLumaRowU16(const uint16_t* src, uint16_t* dst, const int16_t* noise, int width, const int32_t* scaling,
                     int scaling_shift, int min_value, int max_value) {
    const hn::ScalableTag<int32_t> d32;
    const int n = int(hn::Lanes(d32));
    const auto round = hn::Set(d32, 1 << (scaling_shift - 1));
    const auto vmin = hn::Set(d32, min_value), vmax = hn::Set(d32, max_value);
    constexpr int kChunk = 256;
    HWY_ALIGN int32_t scale[kChunk];
    int x = 0;
    while (x + n <= width) {
        const int chunk = std::min(kChunk, (width - x) / n * n);
        for (int k = 0; k < chunk; ++k) scale[k] = scaling[src[x + k]];
        AddLookedUpNoiseU16(d32, src + x, dst + x, noise + x, scale, chunk, scaling_shift, round, vmin, vmax);
        x += chunk;
    }
    BlendLumaRow<uint16_t>(src + x, dst + x, noise + x, width - x, scaling, scaling_shift, min_value, max_value);
}
// 8 bits, as BlendLumaRowU8: the index (`merged`) is formed in 32-bit lanes and stored as
// bytes, looked up with scalar loads, and the noise is scaled in 16-bit lanes.
void BlendChromaRowU8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width, const int16_t* noise,
                      int width, int subsampling_x, const ChromaScalingIndex& index, const uint8_t* scaling,
                      int scaling_shift, int bit_depth, int min_value, int max_value) {
    const hn::ScalableTag<int16_t> d16;
    const hn::Rebind<uint8_t, decltype(d16)> d8;
    const hn::Rebind<uint16_t, decltype(d16)> du16;
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<uint8_t, decltype(d32)> d8q;
    const int n = int(hn::Lanes(d16)), n32 = int(hn::Lanes(d32));
    const auto vmin = hn::Set(d16, int16_t(min_value)), vmax = hn::Set(d16, int16_t(max_value));
    const auto one = hn::Set(d16, int16_t(1));
    const auto luma_mult = hn::Set(d32, index.luma_mult), mult = hn::Set(d32, index.mult);
    const auto offset = hn::Set(d32, index.offset);
    const auto vmax8 = hn::Set(d32, 255);
    constexpr int kChunk = 256;
    HWY_ALIGN uint8_t merged[kChunk];
    HWY_ALIGN uint8_t scale[kChunk];
    // The last chroma column of an odd-width subsampled picture is left to the scalar tail.
    const int vec_width = (subsampling_x && (luma_width & 1)) ? width - 1 : width;
    int x = 0;
    if (n % n32 == 0) {
        while (x + n <= vec_width) {
            const int chunk = std::min(kChunk, (vec_width - x) / n * n);
            for (int k = 0; k < chunk; k += n32) {
                const auto avg_luma = CositedLuma(d32, luma, x + k, subsampling_x);
                const auto orig = index.from_luma ? avg_luma : hn::PromoteTo(d32, hn::LoadU(d8q, src + x + k));
                const auto m =
                    ChromaScalingIndexLanes(d32, avg_luma, orig, index.from_luma, luma_mult, mult, offset, vmax8);
                hn::Store(hn::DemoteTo(d8q, m), d8q, merged + k);
            }
            LookUpScaling8(merged, scale, chunk, scaling);
            for (int k = 0; k < chunk; k += n) {
                const auto s16 = hn::BitCast(d16, hn::PromoteTo(du16, hn::Load(d8, scale + k)));
                const auto prod = hn::Mul(s16, hn::LoadU(d16, noise + x + k));
                const auto add = hn::ShiftRight<1>(hn::Add(hn::ShiftRightSame(prod, scaling_shift - 1), one));
                const auto orig = hn::BitCast(d16, hn::PromoteTo(du16, hn::LoadU(d8, src + x + k)));
                const auto v = hn::Min(hn::Max(hn::Add(orig, add), vmin), vmax);
                hn::StoreU(hn::DemoteTo(d8, v), d8, dst + x + k);
            }
            x += chunk;
        }
    }
    BlendChromaScalar(src, dst, luma, luma_width, noise, x, width, subsampling_x, index, scaling, scaling_shift,
                      bit_depth, min_value, max_value);
}
// Above 8 bits, as BlendLumaRowU16: the index (`merged`) is formed in vector lanes and
// stored, looked up with scalar loads, and the noise scaled in int32 lanes.
void BlendChromaRowU16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                       const int16_t* noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                       const int32_t* scaling, int scaling_shift, int bit_depth, int min_value, int max_value) {
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<uint16_t, decltype(d32)> dp;
    const int n = int(hn::Lanes(d32));
    const auto round = hn::Set(d32, 1 << (scaling_shift - 1));
    const auto vmin = hn::Set(d32, min_value), vmax = hn::Set(d32, max_value);
    const auto luma_mult = hn::Set(d32, index.luma_mult), mult = hn::Set(d32, index.mult);
    const auto offset = hn::Set(d32, index.offset * (1 << (bit_depth - 8)));
    const auto vpixel_max = hn::Set(d32, (1 << bit_depth) - 1);
    constexpr int kChunk = 256;
    HWY_ALIGN int32_t merged[kChunk];
    HWY_ALIGN int32_t scale[kChunk];
    // The last chroma column of an odd-width subsampled picture is left to the scalar tail.
    const int vec_width = (subsampling_x && (luma_width & 1)) ? width - 1 : width;
    int x = 0;
    while (x + n <= vec_width) {
        const int chunk = std::min(kChunk, (vec_width - x) / n * n);
        for (int k = 0; k < chunk; k += n) {
            const auto avg_luma = CositedLuma(d32, luma, x + k, subsampling_x);
            const auto orig = index.from_luma ? avg_luma : hn::PromoteTo(d32, hn::LoadU(dp, src + x + k));
            hn::Store(ChromaScalingIndexLanes(d32, avg_luma, orig, index.from_luma, luma_mult, mult, offset, vpixel_max),
                      d32, merged + k);
        }
        for (int k = 0; k < chunk; ++k) scale[k] = scaling[merged[k]];
        AddLookedUpNoiseU16(d32, src + x, dst + x, noise + x, scale, chunk, scaling_shift, round, vmin, vmax);
        x += chunk;
    }
    BlendChromaRow<uint16_t>(src + x, dst + x, luma + (x << subsampling_x), luma_width - (x << subsampling_x),
                             noise + x, width - x, subsampling_x, index, scaling, scaling_shift, bit_depth, min_value,
                             max_value);
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
HWY_EXPORT(BlendChromaRowU16);
HWY_EXPORT(CrossFadeRow);

void blend_luma_row_u8(const uint8_t* src, uint8_t* dst, const int16_t* noise, int width, const uint8_t* scaling,
                       int scaling_shift, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowU8)(src, dst, noise, width, scaling, scaling_shift, min_value, max_value);
}
void blend_luma_row_u16(const uint16_t* src, uint16_t* dst, const int16_t* noise, int width, const int32_t* scaling,
                        int scaling_shift, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendLumaRowU16)(src, dst, noise, width, scaling, scaling_shift, min_value, max_value);
}
void blend_chroma_row_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width, const int16_t* noise,
                         int width, int subsampling_x, const ChromaScalingIndex& index, const uint8_t* scaling,
                         int scaling_shift, int bit_depth, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowU8)(src, dst, luma, luma_width, noise, width, subsampling_x, index, scaling,
                                           scaling_shift, bit_depth, min_value, max_value);
}
void blend_chroma_row_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                          const int16_t* noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                          const int32_t* scaling, int scaling_shift, int bit_depth, int min_value, int max_value) {
    HWY_DYNAMIC_DISPATCH(BlendChromaRowU16)(src, dst, luma, luma_width, noise, width, subsampling_x, index, scaling,
                                            scaling_shift, bit_depth, min_value, max_value);
}
void cross_fade_row(const int16_t* old_row, int16_t* cur, int width, int old_weight, int new_weight, int gmin,
                    int gmax) {
    HWY_DYNAMIC_DISPATCH(CrossFadeRow)(old_row, cur, width, old_weight, new_weight, gmin, gmax);
}

}  // namespace filmgrain::av1::simd
#endif  // HWY_ONCE

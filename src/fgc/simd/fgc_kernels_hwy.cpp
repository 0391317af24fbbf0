// Highway implementations of fgc_kernels.hpp, compiled once per target (foreach_target).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "fgc/simd/fgc_kernels_hwy.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <algorithm>
#include <cstring>

#include "fgc/simd/fgc_kernels.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::fgc::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// |scale| <= 258 keeps scale * template (|template| <= 127) inside int16, so the product
// can be formed in 16-bit lanes (always so at 8 bits, where |scale| <= 255); larger scales
// take 32-bit lanes.
void ScaleTemplateBlocks(const BlockCopy* blocks, int count, int rows, int shift, std::ptrdiff_t dst_stride) {
    const hn::CappedTag<int32_t, 32> d32;
    const hn::Rebind<int8_t, decltype(d32)> d8;
    const hn::Rebind<int16_t, decltype(d32)> d16;
    const hn::CappedTag<int16_t, 8> w16;  // one 8-sample block row per vector
    const hn::Rebind<int8_t, decltype(w16)> w8;
    const int n = int(hn::Lanes(d32));
    for (int b = 0; b < count; b++) {
        const BlockCopy& bc = blocks[b];
        if (bc.scale >= -258 && bc.scale <= 258) {
            const int n16 = int(hn::Lanes(w16));
            const auto scale = hn::Set(w16, int16_t(bc.scale));
            if (n16 == 8 && bc.cols == 8) {
                const int8_t* t = bc.tmpl;
                int16_t* g = bc.dst;
                for (int l = 0; l < rows; l++, t += 64, g += dst_stride) {
                    const auto prod = hn::Mul(hn::PromoteTo(w16, hn::LoadU(w8, t)), scale);
                    hn::StoreU(hn::ShiftRightSame(prod, shift), w16, g);
                }
                continue;
            }
            if (n16 == 8 && bc.cols % 8 == 0) {
                for (int l = 0; l < rows; l++) {
                    const int8_t* t = bc.tmpl + 64 * l;
                    int16_t* g = bc.dst + dst_stride * l;
                    for (int k = 0; k < bc.cols; k += n16) {
                        const auto prod = hn::Mul(hn::PromoteTo(w16, hn::LoadU(w8, t + k)), scale);
                        hn::StoreU(hn::ShiftRightSame(prod, shift), w16, g + k);
                    }
                }
                continue;
            }
        }
        const auto scale = hn::Set(d32, bc.scale);
        const int vec_cols = bc.cols - bc.cols % n;
        for (int l = 0; l < rows; l++) {
            const int8_t* t = bc.tmpl + 64 * l;
            int16_t* g = bc.dst + dst_stride * l;
            int k = 0;
            for (; k < vec_cols; k += n) {
                const auto v = hn::ShiftRightSame(hn::Mul(hn::PromoteTo(d32, hn::LoadU(d8, t + k)), scale), shift);
                hn::StoreU(hn::DemoteTo(d16, v), d16, g + k);
            }
            for (; k < bc.cols; k++) g[k] = int16_t((bc.scale * t[k]) >> shift);
        }
    }
}

// The [1 2 1] / 4 value at every position, selected where the position is the last sample
// before a vertical block edge or the first after it (edges at multiples of block_size in
// (0, width)). Both use the unfiltered neighbours, as the reference does.
// `phase` holds each lane's position modulo block_size (a power of two).
template <class D, class V>
HWY_INLINE V DeblockedGrain(D d, const int16_t* grain, int x, V phase, V last) {
    const auto a = hn::LoadU(d, grain + x - 1);
    const auto b = hn::LoadU(d, grain + x);
    const auto c = hn::LoadU(d, grain + x + 1);
    const auto f = hn::ShiftRight<2>(hn::Add(hn::Add(a, c), hn::ShiftLeft<1>(b)));
    const auto edge = hn::Or(hn::Eq(phase, hn::Zero(d)), hn::Eq(phase, last));
    return hn::IfThenElse(edge, f, b);
}

// bs is 8, 16 or 32: a mask gives x mod bs (a division per sample costs more than the rest)
template <typename G>
inline int32_t deblocked_scalar(const G* g, int x, int width, int bs) {
    const bool right_of_edge = (x & (bs - 1)) == 0 && x > 0;
    const bool left_of_edge = (x & (bs - 1)) == bs - 1 && x + 1 < width;
    if (right_of_edge || left_of_edge) return (g[x - 1] + (g[x] << 1) + g[x + 1]) >> 2;
    return g[x];
}

// The blend kernels touch the same row of the next stripe (NextStripeRow) as they go: that
// stripe's block sums are otherwise the first read of a picture the decoder wrote long
// enough ago to have left the caches (in `filmgrain decode` of a 1080p 8-bit HEVC stream
// they took 0.19-0.25 of 0.69-0.82 ms per frame; with the prefetch 0.08-0.09 of 0.61-0.64),
// and the output row is fetched for writing before its stores wait on it (fgc_kernels.hpp).
// One prefetch per 64-byte line: the kernels call this once per vector, and with vectors
// narrower than a line every other call (AVX2) fetched the line the call before had
// (1080p 8-bit rdd5 on a Zen 3, one thread: the median of 12 interleaved pairs 5 % faster).
template <typename T>
HWY_INLINE void PrefetchAhead(const NextStripeRow<T>& ahead, int x) {
    constexpr int kVectorBytes = int(hn::MaxLanes(hn::ScalableTag<uint8_t>()));
    if (kVectorBytes < 64 && (int(x * sizeof(T)) & 63) >= kVectorBytes) return;
    if (ahead.src) __builtin_prefetch(ahead.src + x, 0, 2);
    if (ahead.dst) __builtin_prefetch(ahead.dst + x, 1, 2);
}

void DeblockBlendRowU8(const uint8_t* src, uint8_t* dst, const int16_t* grain, int width, int block_size,
                       NextStripeRow<uint8_t> ahead) {
    const hn::ScalableTag<int16_t> d16;
    const hn::Rebind<uint8_t, decltype(d16)> d8;
    const int n = int(hn::Lanes(d16));
    // Lane x = 0 has no left neighbour and is never filtered; vector lanes stop before the
    // last column so that no left-of-edge lane sees an edge at `width`.
    int x = 1;
    dst[0] = uint8_t(std::clamp<int32_t>(src[0] + deblocked_scalar(grain, 0, width, block_size), 0, 255));
    const auto last = hn::Set(d16, int16_t(block_size - 1));
    const auto step = hn::Set(d16, int16_t(n));
    auto phase = hn::And(hn::Iota(d16, 1), last);
    auto blend = [&](int at, auto g) {
        const auto s = hn::BitCast(d16, hn::PromoteTo(hn::Rebind<uint16_t, decltype(d16)>(), hn::LoadU(d8, src + at)));
        hn::StoreU(hn::DemoteTo(d8, hn::Add(s, g)), d8, dst + at);
    };
    if (n % block_size == 0) {
        // every vector starts at the same phase: one edge mask for the whole row
        const auto edge = hn::Or(hn::Eq(phase, hn::Zero(d16)), hn::Eq(phase, last));
        for (; x + n <= width - 1; x += n) {
            const auto a = hn::LoadU(d16, grain + x - 1);
            const auto b = hn::LoadU(d16, grain + x);
            const auto c = hn::LoadU(d16, grain + x + 1);
            const auto f = hn::ShiftRight<2>(hn::Add(hn::Add(a, c), hn::ShiftLeft<1>(b)));
            blend(x, hn::IfThenElse(edge, f, b));
            PrefetchAhead(ahead, x);
        }
    }
    for (; x + n <= width - 1; x += n) {
        blend(x, DeblockedGrain(d16, grain, x, phase, last));
        PrefetchAhead(ahead, x);
        phase = hn::And(hn::Add(phase, step), last);
    }
    for (; x < width; x++)
        dst[x] = uint8_t(std::clamp<int32_t>(src[x] + deblocked_scalar(grain, x, width, block_size), 0, 255));
}

// The [1 2 1] / 4 filter and the clipped addition done entirely in bytes, 32 samples per
// AVX2 vector. (a + 2b + c) >> 2 = floor((floor((a + c) / 2) + b) / 2): an odd a + c loses
// a half that cannot carry the outer floor over an integer. With grain biased by 128 the
// values are unsigned and the bias survives floor averaging; a floor average is the
// complement of the rounding average (AverageRound) of the complements, and the complement
// of biased grain is grain ^ 0x7F, so the filter is two AverageRounds between four XORs.
// Biasing the picture by 128 the other way makes clip(src + g, 0, 255) a signed
// saturating add.
void DeblockBlendRowU8I8(const uint8_t* src, uint8_t* dst, const int8_t* grain, int width, int block_size,
                         NextStripeRow<uint8_t> ahead) {
    const hn::ScalableTag<uint8_t> du;
    const hn::RebindToSigned<decltype(du)> di;
    const int n = int(hn::Lanes(du));
    const auto bias = hn::Set(du, uint8_t(0x80));
    const auto flip = hn::Set(du, uint8_t(0x7F));
    const auto last = hn::Set(du, uint8_t(block_size - 1));
    const auto lane = hn::Iota(du, 0);
    // block_size divides 256, so the position modulo block_size survives the byte wrap
    auto edges_at = [&](int x) {
        const auto phase = hn::And(hn::Add(lane, hn::Set(du, uint8_t(x))), last);
        return hn::Or(hn::Eq(phase, hn::Zero(du)), hn::Eq(phase, last));
    };
    // g points at grain[x - 1]; `filtered` says which lanes sit either side of an edge
    auto blend = [&](const uint8_t* s, const int8_t* g, uint8_t* d, auto filtered) {
        const auto b = hn::BitCast(du, hn::LoadU(di, g + 1));
        const auto na = hn::Xor(hn::BitCast(du, hn::LoadU(di, g)), flip);
        const auto nc = hn::Xor(hn::BitCast(du, hn::LoadU(di, g + 2)), flip);
        const auto nf = hn::AverageRound(hn::AverageRound(na, nc), hn::Xor(b, flip));
        const auto gr = hn::BitCast(di, hn::IfThenElse(filtered, hn::Xor(nf, flip), b));
        const auto sv = hn::BitCast(di, hn::Xor(hn::LoadU(du, s), bias));
        hn::StoreU(hn::Xor(hn::BitCast(du, hn::SaturatedAdd(sv, gr)), bias), du, d);
    };
    // Column 0 has no edge on its left, and no edge lies at `width` for the last column of a
    // row of whole blocks to be left of.
    const bool whole_blocks = width % block_size == 0;
    auto filtered_at = [&](int x) {
        auto m = edges_at(x);
        if (x == 0) m = hn::AndNot(hn::FirstN(du, 1), m);
        if (whole_blocks && x + n >= width) m = hn::And(m, hn::FirstN(du, std::size_t(width - 1 - x)));
        return m;
    };
    int x = 0;
    if (n < width) {  // the first vector; a last one that ends the row exactly is done below
        blend(src, grain - 1, dst, filtered_at(0));
        x = n;
    }
    if (n % block_size == 0) {
        // every vector starts at the same phase: one edge mask for the whole row
        const auto edges = edges_at(0);
        for (; x + n < width; x += n) {
            blend(src + x, grain + x - 1, dst + x, edges);
            PrefetchAhead(ahead, x);
        }
    } else {
        for (; x + n < width; x += n) {
            blend(src + x, grain + x - 1, dst + x, edges_at(x));
            PrefetchAhead(ahead, x);
        }
    }
    if (x + n == width) {
        blend(src + x, grain + x - 1, dst + x, filtered_at(x));
    } else if (x < width) {
        // the last partial vector through buffers, so that nothing past the row is touched
        HWY_ALIGN uint8_t s[hn::MaxLanes(du)] = {}, d[hn::MaxLanes(du)];
        HWY_ALIGN int8_t g[hn::MaxLanes(du) + 2] = {};
        std::copy(src + x, src + width, s);
        std::copy(grain + x - 1, grain + width + 1, g);
        blend(s, g, d, filtered_at(x));
        std::copy(d, d + (width - x), dst + x);
    }
}

// Up to 12 bits everything fits int16 lanes (twice as many per vector as int32): with
// |grain| <= 32385 >> (16 - bd), the [1 2 1] sum is at most 4 * 2024 and the shifted grain
// at most 32385. The sample is unsigned and may exceed the bit depth (bad input, which the
// reference's 32-bit clip still handles): flipping its top bit maps 0..65535 onto the signed
// range in order, so the signed saturating add is the unsigned sum clamped to 0..65535,
// and flipping back leaves only the clip to 2^bd - 1.
template <typename G>
void DeblockBlendRowU16Narrow(const uint16_t* src, uint16_t* dst, const G* grain, int width, int block_size,
                              int bit_depth, NextStripeRow<uint16_t> ahead) {
    const hn::ScalableTag<int16_t> d16;
    const hn::Rebind<uint16_t, decltype(d16)> du16;
    const int n = int(hn::Lanes(d16));
    const int shift = bit_depth - 8;
    const int32_t max_value = (1 << bit_depth) - 1;
    const auto vmax = hn::Set(du16, uint16_t(max_value));
    const auto top_bit = hn::Set(d16, int16_t(-32768));
    const auto last = hn::Set(d16, int16_t(block_size - 1));
    auto blend1 = [&](int x) {
        dst[x] = uint16_t(std::clamp<int32_t>(src[x] + deblocked_scalar(grain, x, width, block_size) * (1 << shift), 0,
                                              max_value));
    };
    auto load = [&](const G* p) {
        if constexpr (sizeof(G) == 1)
            return hn::PromoteTo(d16, hn::LoadU(hn::Rebind<int8_t, decltype(d16)>(), p));
        else
            return hn::LoadU(d16, p);
    };
    auto blend = [&](int at, auto edge) {
        const auto a = load(grain + at - 1);
        const auto b = load(grain + at);
        const auto c = load(grain + at + 1);
        const auto f = hn::ShiftRight<2>(hn::Add(hn::Add(a, c), hn::ShiftLeft<1>(b)));
        const auto g = hn::ShiftLeftSame(hn::IfThenElse(edge, f, b), shift);
        const auto s = hn::Xor(hn::BitCast(d16, hn::LoadU(du16, src + at)), top_bit);
        const auto v = hn::BitCast(du16, hn::Xor(hn::SaturatedAdd(s, g), top_bit));
        hn::StoreU(hn::Min(v, vmax), du16, dst + at);
    };
    int x = 1;
    blend1(0);
    const auto step = hn::Set(d16, int16_t(n));
    auto phase = hn::And(hn::Iota(d16, 1), last);
    if (n % block_size == 0) {
        const auto edge = hn::Or(hn::Eq(phase, hn::Zero(d16)), hn::Eq(phase, last));
        for (; x + n <= width - 1; x += n) {
            blend(x, edge);
            PrefetchAhead(ahead, x);
        }
    }
    for (; x + n <= width - 1; x += n, phase = hn::And(hn::Add(phase, step), last)) {
        blend(x, hn::Or(hn::Eq(phase, hn::Zero(d16)), hn::Eq(phase, last)));
        PrefetchAhead(ahead, x);
    }
    for (; x < width; x++) blend1(x);
}

template <typename G>
void DeblockBlendRowU16Of(const uint16_t* src, uint16_t* dst, const G* grain, int width, int block_size,
                            int bit_depth, NextStripeRow<uint16_t> ahead) {
    if (bit_depth <= 12) return DeblockBlendRowU16Narrow<G>(src, dst, grain, width, block_size, bit_depth, ahead);
    const hn::ScalableTag<int32_t> d32;
    const hn::Rebind<G, decltype(d32)> dg;
    const hn::Rebind<uint16_t, decltype(d32)> du16;
    const int n = int(hn::Lanes(d32));
    const int shift = bit_depth - 8;
    const int32_t max_value = (1 << bit_depth) - 1;
    const auto vmax = hn::Set(d32, max_value);
    const auto bs_mask = hn::Set(d32, block_size - 1);
    auto blend1 = [&](int x) {
        dst[x] = uint16_t(std::clamp<int32_t>(src[x] + deblocked_scalar(grain, x, width, block_size) * (1 << shift), 0,
                                              max_value));
    };
    int x = 1;
    blend1(0);
    const auto step = hn::Set(d32, n);
    auto phase = hn::And(hn::Iota(d32, 1), bs_mask);
    auto blend = [&](int at, auto edge) {
        const auto a = hn::PromoteTo(d32, hn::LoadU(dg, grain + at - 1));
        const auto b = hn::PromoteTo(d32, hn::LoadU(dg, grain + at));
        const auto c = hn::PromoteTo(d32, hn::LoadU(dg, grain + at + 1));
        const auto f = hn::ShiftRight<2>(hn::Add(hn::Add(a, c), hn::ShiftLeft<1>(b)));
        const auto g = hn::ShiftLeftSame(hn::IfThenElse(edge, f, b), shift);
        const auto s = hn::PromoteTo(d32, hn::LoadU(du16, src + at));
        const auto v = hn::Min(hn::Max(hn::Add(s, g), hn::Zero(d32)), vmax);
        hn::StoreU(hn::DemoteTo(du16, v), du16, dst + at);
    };
    if (n % block_size == 0) {
        // every vector starts at the same phase: one edge mask for the whole row
        const auto edge = hn::Or(hn::Eq(phase, hn::Zero(d32)), hn::Eq(phase, bs_mask));
        for (; x + n <= width - 1; x += n) {
            blend(x, edge);
            PrefetchAhead(ahead, x);
        }
    }
    for (; x + n <= width - 1; x += n, phase = hn::And(hn::Add(phase, step), bs_mask)) {
        blend(x, hn::Or(hn::Eq(phase, hn::Zero(d32)), hn::Eq(phase, bs_mask)));
        PrefetchAhead(ahead, x);
    }
    for (; x < width; x++) blend1(x);
}

void DeblockBlendRowU16(const uint16_t* src, uint16_t* dst, const int16_t* grain, int width, int block_size,
                        int bit_depth, NextStripeRow<uint16_t> ahead) {
    DeblockBlendRowU16Of<int16_t>(src, dst, grain, width, block_size, bit_depth, ahead);
}
void DeblockBlendRowU16I8(const uint16_t* src, uint16_t* dst, const int8_t* grain, int width, int block_size,
                          int bit_depth, NextStripeRow<uint16_t> ahead) {
    DeblockBlendRowU16Of<int8_t>(src, dst, grain, width, block_size, bit_depth, ahead);
}

// Whole-vector stores instead of one 8-byte move per block row: 8-sample blocks are joined
// two (four with 256-bit vectors) per vector; wider blocks are moved 16 bytes at a time
// (a byte count known only at run time would otherwise be a memcpy call per block row).
void GatherBlockBandsI8(const int8_t* const* blocks, std::ptrdiff_t offset, int count, int block, int rows,
                        std::ptrdiff_t pitch, int8_t* out, std::ptrdiff_t out_stride) {
    int j = 0;
#if HWY_TARGET != HWY_SCALAR
    const hn::Full64<int8_t> d8;
    const hn::Full128<int8_t> d16;
    if (block == 8) {
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
        const hn::Full256<int8_t> d32;
        for (; j + 4 <= count; j += 4) {
            const int8_t *p0 = blocks[j] + offset, *p1 = blocks[j + 1] + offset, *p2 = blocks[j + 2] + offset,
                         *p3 = blocks[j + 3] + offset;
            int8_t* o = out + j * 8;
            for (int r = 0; r < rows; r++, p0 += pitch, p1 += pitch, p2 += pitch, p3 += pitch, o += out_stride) {
                const auto lo = hn::Combine(d16, hn::LoadU(d8, p1), hn::LoadU(d8, p0));
                const auto hi = hn::Combine(d16, hn::LoadU(d8, p3), hn::LoadU(d8, p2));
                hn::StoreU(hn::Combine(d32, hi, lo), d32, o);
            }
        }
#endif
        for (; j + 2 <= count; j += 2) {
            const int8_t *p0 = blocks[j] + offset, *p1 = blocks[j + 1] + offset;
            int8_t* o = out + j * 8;
            for (int r = 0; r < rows; r++, p0 += pitch, p1 += pitch, o += out_stride)
                hn::StoreU(hn::Combine(d16, hn::LoadU(d8, p1), hn::LoadU(d8, p0)), d16, o);
        }
    } else {
        for (; j < count; j++) {
            const int8_t* p = blocks[j] + offset;
            int8_t* o = out + j * block;
            for (int r = 0; r < rows; r++, p += pitch, o += out_stride)
                for (int k = 0; k < block; k += 16) hn::StoreU(hn::LoadU(d16, p + k), d16, o + k);
        }
    }
#endif
    for (; j < count; j++)
        for (int r = 0; r < rows; r++)
            std::memcpy(out + r * out_stride + j * block, blocks[j] + offset + r * pitch, std::size_t(block));
}

// The generic form: the rows gathered into `row` block by block, each block's pointer read
// once for all of them (gathered row by row, the pointer loads cost a frame 5 % more on a
// Zen 3: 1080p 8-bit rdd5, one thread, median of 12 interleaved pairs), then each row zeroed
// from `end` and blended by blend_row(src row, dst row, grain row, prefetch rows). Every row
// has one element before column 0, which DeblockBlendRowU8I8 reads and never uses (the
// previous row's padding, or the byte before the first boundary).
template <typename Pixel, typename BlendRow>
void DeblockBlendBlockRowsViaBuffer(const Pixel* src, std::ptrdiff_t src_stride, Pixel* dst, std::ptrdiff_t dst_stride,
                                    const int8_t* const* blocks, std::ptrdiff_t offset, std::ptrdiff_t pitch, int rows,
                                    int width, int grain_end, int block, int8_t* row, NextStripeRow<Pixel> ahead,
                                    BlendRow blend_row) {
    // row 0 on the first 64-byte boundary after row[0] (deblock_blend_block_rows_scratch)
    const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(row + 1);
    int8_t* g = row + 1 + std::ptrdiff_t((kBlockRowsBandAlign - first % kBlockRowsBandAlign) % kBlockRowsBandAlign);
    const int end = std::min(grain_end, width + 1);
    const int count = (end + block - 1) / block;
    const auto stride = std::ptrdiff_t(deblock_blend_block_rows_band_stride(width, grain_end, block));
    GatherBlockBandsI8(blocks, offset, count, block, rows, pitch, g, stride);
    for (int r = 0; r < rows; r++, g += stride) {
        std::fill(g + end, g + width + 2, int8_t(0));
        blend_row(src + r * src_stride, dst + r * dst_stride, g, ahead.below(r, src_stride, dst_stride));
    }
}

#include "fgc/simd/block_sums_u16_avx2-inl.h"
#include "fgc/simd/block_sums_u16_avx512-inl.h"
#include "fgc/simd/block_tables_u8_avx2-inl.h"
#include "fgc/simd/block_rows_u8_avx512-inl.h"
#include "fgc/simd/block_rows_u16_avx512-inl.h"

void DeblockBlendBlockRowsU8I8(const uint8_t* src, std::ptrdiff_t src_stride, uint8_t* dst,
                               std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                               std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int8_t* row,
                               NextStripeRow<uint8_t> ahead) {
#if HWY_TARGET == HWY_AVX3
    if (block == 8)
        return avx512::DeblockBlendBlockRows<8>(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows, width,
                                                grain_end, ahead);
    if (block == 16)
        return avx512::DeblockBlendBlockRows<16>(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows, width,
                                                 grain_end, ahead);
#endif
    DeblockBlendBlockRowsViaBuffer(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows, width, grain_end,
                                   block, row, ahead, [&](const uint8_t* s, uint8_t* d, const int8_t* g, auto next) {
                                       DeblockBlendRowU8I8(s, d, g, width, block, next);
                                   });
}

void DeblockBlendBlockRowsU16I8(const uint16_t* src, std::ptrdiff_t src_stride, uint16_t* dst,
                                std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int bit_depth,
                                int8_t* row, NextStripeRow<uint16_t> ahead) {
#if HWY_TARGET == HWY_AVX3
    if (block == 8 && bit_depth <= 12)
        return avx512::DeblockBlendBlockRowsU16<8>(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows,
                                                   width, grain_end, bit_depth, ahead);
    if (block == 16 && bit_depth <= 12)
        return avx512::DeblockBlendBlockRowsU16<16>(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows,
                                                    width, grain_end, bit_depth, ahead);
#endif
    DeblockBlendBlockRowsViaBuffer(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows, width, grain_end,
                                   block, row, ahead, [&](const uint16_t* s, uint16_t* d, const int8_t* g, auto next) {
                                       DeblockBlendRowU16I8(s, d, g, width, block, bit_depth, next);
                                   });
}

void BlockSumsU8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums) {
    const hn::ScalableTag<uint8_t> d8;
    const hn::Repartition<uint64_t, decltype(d8)> d64;
    const int n = int(hn::Lanes(d8));
    const int blocks = width / block;
    const int limit = blocks * block;
    std::fill(sums, sums + blocks, 0u);
    HWY_ALIGN uint64_t lanes[hn::MaxLanes(d64)];
    const int log2_block = block == 8 ? 3 : block == 16 ? 4 : 5;  // shifts, not divisions
    int x = 0;
    // SumsOf8 needs whole groups of 8 bytes per vector (not so on the one-lane SCALAR target).
    for (; n >= 8 && x + n <= limit; x += n) {
        auto acc = hn::Zero(d64);
        for (int y = 0; y < rows; y++) acc = hn::Add(acc, hn::SumsOf8(hn::LoadU(d8, src + stride * y + x)));
        hn::Store(acc, d64, lanes);
        if (block == 8) {
            for (int i = 0; i < n / 8; i++) sums[(x >> 3) + i] = uint32_t(lanes[i]);
        } else {
            for (int i = 0; i < n / 8; i++) sums[(x + 8 * i) >> log2_block] += uint32_t(lanes[i]);
        }
    }
    for (; x < limit; x++)
        for (int y = 0; y < rows; y++) sums[x >> log2_block] += src[stride * y + x];
}

// The generic table look-up, from block j on: the sums of up to 64 blocks at a time
// (sum_blocks: BlockSumsU8 or BlockSumsU16), then each block's table.
template <typename Pixel, typename SumBlocks>
void TablesFromBlockSums(const Pixel* src, std::ptrdiff_t stride, int rows, int blocks, int j, int block, int shift,
                         const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out,
                         SumBlocks sum_blocks) {
    uint32_t sums[64];
    for (; j < blocks; j += 64) {
        const int n = std::min(64, blocks - j);
        sum_blocks(src + j * block, stride, rows, n * block, block, sums);
        for (int k = 0; k < n; k++)
            out[j + k] = base + offsets[std::min<uint32_t>(sums[k] >> shift, 255)] + places[j + k];
    }
}

void BlockSumsU16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums) {
#if HWY_TARGET == HWY_AVX3
    if (block == 8) {
        const int done = avx512::BlockSums8U16(src, stride, rows, width / 8, sums);
        src += 8 * done, sums += done, width -= 8 * done;
    }
#endif
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3
    if (block == 8) {
        const int done = avx2::BlockSums8U16(src, stride, rows, width / 8, sums);
        src += 8 * done, sums += done, width -= 8 * done;
    }
#endif
    const hn::ScalableTag<uint32_t> d32;
    const hn::Rebind<uint16_t, decltype(d32)> d16;
    const int n = int(hn::Lanes(d32));
    const int blocks = width / block;
    const int limit = blocks * block;
    std::fill(sums, sums + blocks, 0u);
    HWY_ALIGN uint32_t lanes[hn::MaxLanes(d32)];
    const std::ptrdiff_t pitch = stride / std::ptrdiff_t(sizeof(uint16_t));
    const int log2_block = block == 8 ? 3 : block == 16 ? 4 : 5;  // shifts, not divisions
    int x = 0;
    for (; x + n <= limit; x += n) {
        auto acc = hn::Zero(d32);
        for (int y = 0; y < rows; y++) acc = hn::Add(acc, hn::PromoteTo(d32, hn::LoadU(d16, src + pitch * y + x)));
        if (block % n == 0) {  // the vector lies in one block: a horizontal sum, not n scalar adds
            sums[x >> log2_block] += hn::GetLane(hn::SumOfLanes(d32, acc));
        } else {
            hn::Store(acc, d32, lanes);
            for (int i = 0; i < n; i++) sums[(x + i) >> log2_block] += lanes[i];
        }
    }
    for (; x < limit; x++)
        for (int y = 0; y < rows; y++) sums[x >> log2_block] += src[pitch * y + x];
}

void BlockTablesU8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                   const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out) {
    const int blocks = width / block;
    int j = 0;
#if HWY_TARGET == HWY_AVX3
    if (block == 8) j = avx512::BlockTables8(src, stride, rows, blocks, shift, offsets, places, base, out);
#elif HWY_TARGET == HWY_AVX2
    if (block == 8) j = avx2::BlockTables8(src, stride, rows, blocks, shift, offsets, places, base, out);
#endif
    TablesFromBlockSums(src, stride, rows, blocks, j, block, shift, offsets, places, base, out, BlockSumsU8);
}

void BlockTablesU16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                    const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out) {
    const int blocks = width / block;
    int j = 0;
#if HWY_TARGET == HWY_AVX3
    if (block == 8) j = avx512::BlockTables8U16(src, stride, rows, blocks, shift, offsets, places, base, out);
#endif
    TablesFromBlockSums(src, stride, rows, blocks, j, block, shift, offsets, places, base, out, BlockSumsU16);
}

}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::fgc::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::fgc::simd {

HWY_EXPORT(ScaleTemplateBlocks);
HWY_EXPORT(DeblockBlendRowU8);
HWY_EXPORT(DeblockBlendRowU16);
HWY_EXPORT(DeblockBlendRowU8I8);
HWY_EXPORT(GatherBlockBandsI8);
HWY_EXPORT(DeblockBlendBlockRowsU16I8);
HWY_EXPORT(DeblockBlendRowU16I8);
HWY_EXPORT(DeblockBlendBlockRowsU8I8);
HWY_EXPORT(BlockSumsU8);
HWY_EXPORT(BlockTablesU8);
HWY_EXPORT(BlockSumsU16);
HWY_EXPORT(BlockTablesU16);

void scale_template_blocks(const BlockCopy* blocks, int count, int rows, int shift, std::ptrdiff_t dst_stride) {
    HWY_DYNAMIC_DISPATCH(ScaleTemplateBlocks)(blocks, count, rows, shift, dst_stride);
}
void deblock_blend_row_u8(const uint8_t* src, uint8_t* dst, const int16_t* grain, int width, int block_size,
                          NextStripeRow<uint8_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendRowU8)(src, dst, grain, width, block_size, ahead);
}
void deblock_blend_row_u16(const uint16_t* src, uint16_t* dst, const int16_t* grain, int width, int block_size,
                           int bit_depth, NextStripeRow<uint16_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendRowU16)(src, dst, grain, width, block_size, bit_depth, ahead);
}
void deblock_blend_row_u8_i8(const uint8_t* src, uint8_t* dst, const int8_t* grain, int width, int block_size,
                             NextStripeRow<uint8_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendRowU8I8)(src, dst, grain, width, block_size, ahead);
}
void deblock_blend_row_u16_i8(const uint16_t* src, uint16_t* dst, const int8_t* grain, int width, int block_size,
                              int bit_depth, NextStripeRow<uint16_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendRowU16I8)(src, dst, grain, width, block_size, bit_depth, ahead);
}
void gather_block_bands_i8(const int8_t* const* blocks, std::ptrdiff_t offset, int count, int block, int rows,
                           std::ptrdiff_t pitch, int8_t* out, std::ptrdiff_t out_stride) {
    HWY_DYNAMIC_DISPATCH(GatherBlockBandsI8)(blocks, offset, count, block, rows, pitch, out, out_stride);
}
void deblock_blend_block_rows_u8_i8(const uint8_t* src, std::ptrdiff_t src_stride, uint8_t* dst,
                                    std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                    std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int8_t* row,
                                    NextStripeRow<uint8_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendBlockRowsU8I8)(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows,
                                                    width, grain_end, block, row, ahead);
}
void deblock_blend_block_rows_u16_i8(const uint16_t* src, std::ptrdiff_t src_stride, uint16_t* dst,
                                     std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                     std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int bit_depth,
                                     int8_t* row, NextStripeRow<uint16_t> ahead) {
    HWY_DYNAMIC_DISPATCH(DeblockBlendBlockRowsU16I8)(src, src_stride, dst, dst_stride, blocks, offset, pitch, rows,
                                                     width, grain_end, block, bit_depth, row, ahead);
}
void block_sums_u8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums) {
    HWY_DYNAMIC_DISPATCH(BlockSumsU8)(src, stride, rows, width, block, sums);
}
void block_tables_u8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                     const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** blocks) {
    HWY_DYNAMIC_DISPATCH(BlockTablesU8)(src, stride, rows, width, block, shift, offsets, places, base, blocks);
}
void block_tables_u16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                      const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** blocks) {
    HWY_DYNAMIC_DISPATCH(BlockTablesU16)(src, stride, rows, width, block, shift, offsets, places, base, blocks);
}
void block_sums_u16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums) {
    HWY_DYNAMIC_DISPATCH(BlockSumsU16)(src, stride, rows, width, block, sums);
}

}  // namespace filmgrain::fgc::simd
#endif  // HWY_ONCE

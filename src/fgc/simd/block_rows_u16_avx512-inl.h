// 16-bit FGC stripe kernel for 8x8 and 16x16 blocks with int8 grain (the narrow scaled tables) and bit
// depths up to 12, for the AVX3 target of fgc_kernels_hwy.cpp; included inside that file's
// HWY_NAMESPACE, on the AVX3 pass only, after block_rows_u8_avx512-inl.h (whose column walk,
// ForEachVectorOfRow, and GrainAroundColumns it shares). Twin of the generic form there
// (DeblockBlendBlockRowsU16ViaBuffer: GatherBlockBandsI8, then DeblockBlendRowU16Narrow per
// row), bit-equal to it and to the reference stages (fgc_simd_equivalence_test).
//
// Why a separate form: the generic one copies every row of grain into a band and reads it
// back three times (the [1 2 1] neighbours); on the Zen 5 EPYC (1080p 10-bit rdd5, one
// thread) the copy alone was 15 % of the frame (17 % with vtm's 16x16 blocks). Here a vector
// is four 8x8 blocks or two 16x16 blocks side by side, 32 samples: each row is assembled in
// registers from the blocks' table pointers, read once for all the rows, and widened to
// 16-bit lanes, as block_rows_u8_avx512-inl.h does with bytes.
#if HWY_TARGET == HWY_AVX3

namespace avx512 {

// Strides are in samples. The arithmetic is DeblockBlendRowU16Narrow's (up to 12 bits the
// [1 2 1] sum, the shifted grain and the saturating add all fit int16 lanes).
template <int kBlock>
inline void DeblockBlendBlockRowsU16(const uint16_t* src, std::ptrdiff_t src_stride, uint16_t* dst,
                                      std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                      std::ptrdiff_t pitch, int rows, int width, int grain_end, int bit_depth,
                                      NextStripeRow<uint16_t> ahead) {
    auto first_n = [](int len) -> __mmask32 {
        return len <= 0 ? 0 : len >= 32 ? ~__mmask32(0) : (__mmask32(1) << len) - 1;
    };
    auto qword = [](const int8_t* p) {
        int64_t v;
        std::memcpy(&v, p, sizeof(v));
        return v;
    };
    const int end = std::min(grain_end, width + 1);  // columns that can reach the output; 0 from here
    // samples above the bit depth (bad input) as DeblockBlendRowU16Narrow takes them: the top
    // bit flipped around a signed saturating add is an unsigned one
    const __m512i top_bit = _mm512_set1_epi16(int16_t(-32768)), vmax = _mm512_set1_epi16(int16_t((1 << bit_depth) - 1));
    const __m128i count = _mm_cvtsi32_si128(bit_depth - 8);
    // The last and first column of every block. Column 0 has no edge on its left, and no
    // edge lies at `width` for the last column to be left of.
    constexpr __mmask32 kFirstColumns = kBlock == 8 ? 0x01010101u : 0x00010001u;
    auto filtered_at = [&](int x) {
        __mmask32 m = kFirstColumns | kFirstColumns << (kBlock - 1);
        if (x == 0) m &= ~__mmask32(1);
        if (x + 32 >= width) m &= first_n(width - 1 - x) | kFirstColumns;
        return m;
    };
    auto blend = [&](int x, int r, __m512i a, __m512i b, __m512i c, __mmask32 filtered) {
        const __m512i f = _mm512_srai_epi16(_mm512_add_epi16(_mm512_add_epi16(a, c), _mm512_slli_epi16(b, 1)), 2);
        const __m512i g = _mm512_sll_epi16(_mm512_mask_blend_epi16(filtered, b, f), count);
        const uint16_t* s = src + r * src_stride + x;
        uint16_t* d = dst + r * dst_stride + x;
        auto add = [&](__m512i sv) {
            const __m512i v = _mm512_xor_si512(_mm512_adds_epi16(_mm512_xor_si512(sv, top_bit), g), top_bit);
            return _mm512_min_epu16(v, vmax);
        };
        if (x + 32 <= width) {
            _mm512_storeu_si512(d, add(_mm512_loadu_si512(s)));
        } else {
            const __mmask32 inside = first_n(width - x);
            _mm512_mask_storeu_epi16(d, inside, add(_mm512_maskz_loadu_epi16(inside, s)));
        }
        PrefetchAhead(ahead.below(r, src_stride, dst_stride), x);
    };
    // The rows of columns x .. x + 31, each assembled by row_at(offset of the row) as 32 bytes
    // and widened; `left` and `right` are the blocks before and after the vector, read where
    // has_left / has_right.
    auto rows_of = [&](int x, auto has_left, auto has_right, const int8_t* left, const int8_t* right,
                       __mmask32 filtered, auto row_at) {
        for (int r = 0; r < rows; r++) {
            const std::ptrdiff_t o = r * pitch;
            const __m512i b = _mm512_cvtepi8_epi16(row_at(o));
            // column x - 1 is the last sample of the block before (zero at column 0), column
            // x + 32 the first of the block after: widened, each 128-bit lane holds them at its
            // top and bottom word
            const __m512i before =
                has_left ? _mm512_cvtepi8_epi16(_mm256_set1_epi64x(qword(left + o + kBlock - 8))) : _mm512_setzero_si512();
            const __m512i after =
                has_right ? _mm512_cvtepi8_epi16(_mm256_set1_epi64x(qword(right + o))) : _mm512_setzero_si512();
            // the row moved one sample right and left across the whole vector: valignq lines up
            // each 128-bit lane with its neighbour lane, vpalignr takes the one word over from it
            const __m512i a = _mm512_alignr_epi8(b, _mm512_alignr_epi64(b, before, 6), 14);
            const __m512i c = _mm512_alignr_epi8(_mm512_alignr_epi64(after, b, 2), b, 2);
            blend(x, r, a, b, c, filtered);
        }
    };
    // Columns x .. x + 31, all before `end`; the block before them (has_left) and the one
    // after (has_right) are read too. A 16x16 block's row is one 16-byte load, and so is a
    // pair of 8x8 blocks where they are `joined`: blocks 0, 1 and blocks 2, 3 each lie side by
    // side in one table (the two halves of a 16x16 block in one interval).
    auto whole = [&](int x, auto has_left, auto has_right) {
        constexpr int kCount = 32 / kBlock;
        const int8_t* const* bl = blocks + x / kBlock;
        const int8_t* p[kCount];
        for (int k = 0; k < kCount; k++) p[k] = bl[k] + offset;
        const int8_t* left = has_left ? bl[-1] + offset : nullptr;
        const int8_t* right = has_right ? bl[kCount] + offset : nullptr;
        const __mmask32 filtered = filtered_at(x);
        auto load16 = [](const int8_t* at) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at)); };
        auto joined_rows = [&](std::ptrdiff_t o) {
            return _mm256_inserti128_si256(_mm256_castsi128_si256(load16(p[0] + o)), load16(p[kCount / 2] + o), 1);
        };
        if constexpr (kBlock == 16) {
            rows_of(x, has_left, has_right, left, right, filtered, joined_rows);
        } else if (p[1] == p[0] + 8 && p[3] == p[2] + 8) {
            rows_of(x, has_left, has_right, left, right, filtered, joined_rows);
        } else {
            rows_of(x, has_left, has_right, left, right, filtered, [&](std::ptrdiff_t o) {
                auto pair = [&](int k) {
                    return _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p[k] + o)),
                                              _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p[k + 1] + o)));
                };
                return _mm256_inserti128_si256(_mm256_castsi128_si256(pair(0)), pair(2), 1);
            });
        }
    };
    // Any other columns (past `end` in part or whole): through a buffer, element by element.
    auto partial = [&](int x) {
        const __mmask32 filtered = filtered_at(x);
        HWY_ALIGN int8_t g[32 + 2];
        auto widened = [&](int at) {
            return _mm512_cvtepi8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(g + at)));
        };
        for (int r = 0; r < rows; r++) {
            GrainAroundColumns<kBlock>(blocks, offset + r * pitch, x, 32, end, g);
            blend(x, r, widened(0), widened(1), widened(2), filtered);
        }
    };
    ForEachVectorOfRow<32>(width, end, whole, partial);
}

}  // namespace avx512

#endif  // HWY_TARGET == HWY_AVX3

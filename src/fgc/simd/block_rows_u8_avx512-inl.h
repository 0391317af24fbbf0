// 8-bit FGC stripe kernels for 8x8 and 16x16 blocks in whole 512-bit vectors, for the AVX3 target of
// fgc_kernels_hwy.cpp; included inside that file's HWY_NAMESPACE, on the AVX3 pass only.
// Twins of the generic forms there (DeblockBlendBlockRowsViaBuffer, BlockSumsU8 plus the
// table look-up), bit-equal to them and to the reference stages (fgc_simd_equivalence_test).
//
// Why a separate form: with 8-sample blocks one 64-bit lane holds one block's row, so a
// vector is eight blocks side by side. Their rows of grain can be assembled in registers
// from the blocks' table pointers and their sums made by vpsadbw in the lanes of their
// pointers, where the generic kernels go through a row buffer and a sums array.
#if HWY_TARGET == HWY_AVX3

namespace avx512 {

// Runs a block-row kernel over columns 0 .. width - 1 in vectors of kColumns:
// whole(x, has_left, has_right) where all of a vector's columns lie before `end` (the grain's
// blocks before and after it are read where they exist), partial(x) for the others. Inlined
// into the kernel: called out of line, the lambdas' vector constants were reloaded through
// their closure on every vector (1080p 8-bit rdd5 1.48x slower).
template <int kColumns, typename Whole, typename Partial>
HWY_INLINE void ForEachVectorOfRow(int width, int end, Whole whole, Partial partial) {
    using No = std::false_type;
    using Yes = std::true_type;
    if (width <= 0) return;
    if (kColumns < end)
        whole(0, No{}, Yes{});
    else if (kColumns == end)
        whole(0, No{}, No{});
    else
        partial(0);
    int x = kColumns;
    for (; x < width && x + kColumns < end; x += kColumns) whole(x, Yes{}, Yes{});
    if (x < width && x + kColumns == end) {
        whole(x, Yes{}, No{});
        x += kColumns;
    }
    for (; x < width; x += kColumns) partial(x);
}

// Grain columns x - 1 .. x + n of one row (offset o in each block's table) element by
// element: zero before column 0 and from `end` on.
template <int kBlock>
inline void GrainAroundColumns(const int8_t* const* blocks, std::ptrdiff_t o, int x, int n, int end, int8_t* g) {
    for (int i = 0; i < n + 2; i++) {
        const int col = x - 1 + i;
        g[i] = col >= 0 && col < end ? blocks[col / kBlock][o + col % kBlock] : int8_t(0);
    }
}

// 8- or 16-sample blocks, 64 columns per vector: each 64- or 128-bit lane is one block's
// row, assembled in registers from the block pointers (vpgatherqq was slower on Zen 5), so
// no row of grain goes through memory; a vector's 8 or 4 pointers are read once for all the
// rows. The neighbours of the [1 2 1] filter are the row shifted by one byte across the
// vector, with the byte that crosses it brought in from the row of the block before or
// after the vector. The arithmetic is DeblockBlendRowU8I8's. (vtm takes 16x16 blocks from
// 1920x1080 up, where the generic form's band copy was a third of the frame on the Zen 5.)
template <int kBlock>
inline void DeblockBlendBlockRows(const uint8_t* src, std::ptrdiff_t src_stride, uint8_t* dst,
                                   std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                   std::ptrdiff_t pitch, int rows, int width, int grain_end,
                                   NextStripeRow<uint8_t> ahead) {
    // columns 0..len-1 of a vector
    auto first_n = [](int len) -> __mmask64 {
        return len <= 0 ? 0 : len >= 64 ? ~__mmask64(0) : (__mmask64(1) << len) - 1;
    };
    auto qword = [](const int8_t* p) {
        int64_t v;
        std::memcpy(&v, p, sizeof(v));
        return v;
    };
    const int end = std::min(grain_end, width + 1);  // columns that can reach the output; 0 from here
    const __m512i flip = _mm512_set1_epi8(0x7F), bias = _mm512_set1_epi8(char(0x80));
    // The last and first column of every block. Column 0 has no edge on its left, and no
    // edge lies at `width` for the last column to be left of.
    constexpr __mmask64 kFirstColumns = kBlock == 8 ? 0x0101010101010101ull : 0x0001000100010001ull;
    auto filtered_at = [&](int x) {
        __mmask64 m = kFirstColumns | kFirstColumns << (kBlock - 1);
        if (x == 0) m &= ~__mmask64(1);
        if (x + 64 >= width) m &= first_n(width - 1 - x) | kFirstColumns;
        return m;
    };
    auto blend = [&](int x, int r, __m512i a, __m512i b, __m512i c, __mmask64 filtered) {
        const __m512i nf = _mm512_avg_epu8(_mm512_avg_epu8(_mm512_xor_si512(a, flip), _mm512_xor_si512(c, flip)),
                                           _mm512_xor_si512(b, flip));
        const __m512i g = _mm512_mask_blend_epi8(filtered, b, _mm512_xor_si512(nf, flip));
        const uint8_t* s = src + r * src_stride + x;
        uint8_t* d = dst + r * dst_stride + x;
        if (x + 64 <= width) {
            _mm512_storeu_si512(d, _mm512_xor_si512(_mm512_adds_epi8(_mm512_xor_si512(_mm512_loadu_si512(s), bias), g),
                                                    bias));
        } else {
            const __mmask64 inside = first_n(width - x);
            const __m512i sv = _mm512_xor_si512(_mm512_maskz_loadu_epi8(inside, s), bias);
            _mm512_mask_storeu_epi8(d, inside, _mm512_xor_si512(_mm512_adds_epi8(sv, g), bias));
        }
        PrefetchAhead(ahead.below(r, src_stride, dst_stride), x);
    };
    // The rows of columns x .. x + 63, each assembled by row_at(offset of the row); `left` and
    // `right` are the blocks before and after the vector, read where has_left / has_right.
    auto rows_of = [&](int x, auto has_left, auto has_right, const int8_t* left, const int8_t* right,
                       __mmask64 filtered, auto row_at) {
        for (int r = 0; r < rows; r++) {
            const std::ptrdiff_t o = r * pitch;
            const __m512i b = row_at(o);
            // column x - 1 is the last byte of the block before (zero at column 0), column x + 64
            // the first byte of the block after
            const __m512i before =
                has_left ? _mm512_set1_epi64(qword(left + o + kBlock - 8)) : _mm512_setzero_si512();
            const __m512i after = has_right ? _mm512_set1_epi64(qword(right + o)) : _mm512_setzero_si512();
            // the row moved one byte right and left across the whole vector: valignq lines up each
            // 128-bit lane with its neighbour lane, vpalignr takes the one byte over from it
            const __m512i a = _mm512_alignr_epi8(b, _mm512_alignr_epi64(b, before, 6), 15);
            const __m512i c = _mm512_alignr_epi8(_mm512_alignr_epi64(after, b, 2), b, 1);
            blend(x, r, a, b, c, filtered);
        }
    };
    // Columns x .. x + 63, all before `end`; the block before them (has_left) and the one
    // after (has_right) are read too. A 16x16 block's row is one 16-byte load. 8x8 blocks are
    // `joined` where each pair of blocks k, k + 1 (k even) lies side by side in one table, 16
    // bytes read at once. That is the common case for luma, where the two 8x8 blocks of a
    // 16x16 block share its offset (clause 7's randomization) and, in one intensity interval,
    // its table; a row then takes 4 loads and 3 shuffles instead of 8 and 7.
    auto whole = [&](int x, auto has_left, auto has_right) {
        constexpr int kCount = 64 / kBlock;
        const int8_t* const* bl = blocks + x / kBlock;
        const int8_t* p[kCount];
        for (int k = 0; k < kCount; k++) p[k] = bl[k] + offset;
        const int8_t* left = has_left ? bl[-1] + offset : nullptr;
        const int8_t* right = has_right ? bl[kCount] + offset : nullptr;
        const __mmask64 filtered = filtered_at(x);
        // the row at offset o from its four quarters of 16 bytes, quarter(q, o)
        auto row_of_quarters = [](std::ptrdiff_t o, auto quarter) {
            const __m256i lo = _mm256_inserti128_si256(_mm256_castsi128_si256(quarter(0, o)), quarter(1, o), 1);
            const __m256i hi = _mm256_inserti128_si256(_mm256_castsi128_si256(quarter(2, o)), quarter(3, o), 1);
            return _mm512_inserti64x4(_mm512_castsi256_si512(lo), hi, 1);
        };
        auto load16 = [](const int8_t* at) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(at)); };
        auto from_quarters = [&](std::ptrdiff_t o) {
            return row_of_quarters(o, [&](int q, std::ptrdiff_t r) { return load16(p[q * kCount / 4] + r); });
        };
        if constexpr (kBlock == 16) {
            rows_of(x, has_left, has_right, left, right, filtered, from_quarters);
        } else if (p[1] == p[0] + 8 && p[3] == p[2] + 8 && p[5] == p[4] + 8 && p[7] == p[6] + 8) {
            rows_of(x, has_left, has_right, left, right, filtered, from_quarters);
        } else {
            rows_of(x, has_left, has_right, left, right, filtered, [&](std::ptrdiff_t o) {
                return row_of_quarters(o, [&](int q, std::ptrdiff_t r) {
                    return _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p[2 * q] + r)),
                                              _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p[2 * q + 1] + r)));
                });
            });
        }
    };
    // Any other columns (past `end` in part or whole): through a buffer, element by element.
    auto partial = [&](int x) {
        const __mmask64 filtered = filtered_at(x);
        HWY_ALIGN int8_t g[64 + 2];
        for (int r = 0; r < rows; r++) {
            GrainAroundColumns<kBlock>(blocks, offset + r * pitch, x, 64, end, g);
            blend(x, r, _mm512_loadu_si512(g), _mm512_loadu_si512(g + 1), _mm512_loadu_si512(g + 2), filtered);
        }
    };
    ForEachVectorOfRow<64>(width, end, whole, partial);
}

// The table pointers of the first whole 8x8 blocks, eight per vector: vpsadbw leaves each
// block row's sum in its 64-bit lane, the lane of the block's pointer; the few look-ups per
// vector are one gather. Returns how many blocks it did (a multiple of 8).
inline int BlockTables8(const uint8_t* src, std::ptrdiff_t stride, int rows, int blocks, int shift,
                        const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out) {
    const __m512i zero = _mm512_setzero_si512(), top = _mm512_set1_epi64(255);
    const __m512i at = _mm512_set1_epi64(reinterpret_cast<int64_t>(base));
    const __m128i count = _mm_cvtsi32_si128(shift);
    int j = 0;
    for (; j + 8 <= blocks; j += 8) {
        __m512i acc = zero;
        for (int y = 0; y < rows; y++)
            acc = _mm512_add_epi64(acc, _mm512_sad_epu8(_mm512_loadu_si512(src + stride * y + 8 * j), zero));
        const __m512i avg = _mm512_min_epu64(_mm512_srl_epi64(acc, count), top);
        const __m256i at_table = _mm256_add_epi32(_mm512_i64gather_epi32(avg, offsets, 4),
                                                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(places + j)));
        _mm512_storeu_si512(out + j, _mm512_add_epi64(_mm512_cvtepi32_epi64(at_table), at));
    }
    return j;
}

}  // namespace avx512

#endif  // HWY_TARGET == HWY_AVX3

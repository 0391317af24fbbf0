// Sums of 8x8 blocks of 16-bit samples for the AVX3 target of fgc_kernels_hwy.cpp; included
// inside that file's HWY_NAMESPACE, on the AVX3 pass only, after the 256-bit form
// (block_sums_u16_avx2-inl.h), which takes the groups of four blocks left after these groups
// of sixteen. Bit-equal to the generic BlockSumsU16 (simd_equivalence_test:
// FgcBlockSums16BitExact).
//
// Why a separate form: the generic one widens 16 samples to 32-bit lanes per vector, which
// at AVX3 hold two 8-sample blocks, so every vector's lanes go through memory and 16 scalar
// adds. Here pmaddwd adds pairs of samples (the same -32768 bias as the 256-bit form, so any
// 16-bit value sums exactly), one 128-bit lane per block; sixteen blocks' lanes are reduced
// together by two rounds of unpack-and-add and put in order by one permute.
#if HWY_TARGET == HWY_AVX3

namespace avx512 {

// The sums of the sixteen 8-sample blocks from `group` (bytes; rows `stride` bytes apart), in
// block order.
inline __m512i SumsOfSixteenBlocks(const uint8_t* group, std::ptrdiff_t stride, int rows) {
    const __m512i flip = _mm512_set1_epi16(int16_t(0x8000)), ones = _mm512_set1_epi16(1);
    // after the reduction lane k holds blocks k, 4 + k, 8 + k, 12 + k
    const __m512i order = _mm512_setr_epi32(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    __m512i acc[4] = {_mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512(), _mm512_setzero_si512()};
    for (int y = 0; y < rows; y++) {
        const uint8_t* row = group + stride * y;
        for (int q = 0; q < 4; q++)
            acc[q] = _mm512_add_epi32(acc[q],
                                      _mm512_madd_epi16(_mm512_xor_si512(_mm512_loadu_si512(row + 64 * q), flip), ones));
    }
    // per lane: (a0+a2, b0+b2, a1+a3, b1+b3), then the same for c and d
    const __m512i ab = _mm512_add_epi32(_mm512_unpacklo_epi32(acc[0], acc[1]), _mm512_unpackhi_epi32(acc[0], acc[1]));
    const __m512i cd = _mm512_add_epi32(_mm512_unpacklo_epi32(acc[2], acc[3]), _mm512_unpackhi_epi32(acc[2], acc[3]));
    const __m512i four = _mm512_add_epi32(_mm512_unpacklo_epi64(ab, cd), _mm512_unpackhi_epi64(ab, cd));
    return _mm512_add_epi32(_mm512_permutexvar_epi32(order, four), _mm512_set1_epi32(rows * 8 * 32768));
}

// The first `blocks` whole 8-sample blocks' sums in groups of sixteen; returns how many it did.
inline int BlockSums8U16(const uint16_t* src, std::ptrdiff_t stride, int rows, int blocks, uint32_t* sums) {
    int j = 0;
    for (; j + 16 <= blocks; j += 16)
        _mm512_storeu_si512(sums + j,
                            SumsOfSixteenBlocks(reinterpret_cast<const uint8_t*>(src + 8 * j), stride, rows));
    return j;
}

// The table pointers of the first whole 8x8 blocks, sixteen per vector (the look-up of
// BlockTablesU16: one 32-bit gather of the intervals' offsets); returns how many it did.
inline int BlockTables8U16(const uint16_t* src, std::ptrdiff_t stride, int rows, int blocks, int shift,
                           const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out) {
    const __m512i top = _mm512_set1_epi32(255), at = _mm512_set1_epi64(reinterpret_cast<int64_t>(base));
    const __m128i count = _mm_cvtsi32_si128(shift);
    int j = 0;
    for (; j + 16 <= blocks; j += 16) {
        const __m512i sums = SumsOfSixteenBlocks(reinterpret_cast<const uint8_t*>(src + 8 * j), stride, rows);
        const __m512i avg = _mm512_min_epu32(_mm512_srl_epi32(sums, count), top);
        const __m512i at_table = _mm512_add_epi32(_mm512_i32gather_epi32(avg, offsets, 4), _mm512_loadu_si512(places + j));
        _mm512_storeu_si512(out + j, _mm512_add_epi64(_mm512_cvtepi32_epi64(_mm512_castsi512_si256(at_table)), at));
        _mm512_storeu_si512(out + j + 8,
                            _mm512_add_epi64(_mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(at_table, 1)), at));
    }
    return j;
}

}  // namespace avx512

#endif  // HWY_TARGET == HWY_AVX3

// The table pointers of whole 8x8 blocks for the AVX2 target of fgc_kernels_hwy.cpp (the
// 256-bit twin of avx512::BlockTables8); included inside that file's HWY_NAMESPACE, on the
// AVX2 pass only. Bit-equal to the generic BlockTablesU8 (fgc_simd_equivalence_test).
//
// Why a separate form: the generic one stores the vpsadbw lanes of 64 blocks to an array and
// looks each block's table up in a scalar loop; here eight blocks' sums stay in registers,
// their averages become one vector of indices and the eight look-ups one gather. On a Zen 3
// (1080p 8-bit rdd5, one thread) the block tables went from 21 % of the profile (sums and
// look-ups) to 18 %; eight scalar look-ups in place of the gather gave the same 18 %: what
// remains is the first read of the picture.
#if HWY_TARGET == HWY_AVX2

namespace avx2 {

// Returns how many blocks it did (a multiple of 8).
inline int BlockTables8(const uint8_t* src, std::ptrdiff_t stride, int rows, int blocks, int shift,
                        const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** out) {
    const __m256i zero = _mm256_setzero_si256(), top = _mm256_set1_epi32(255);
    const __m256i at = _mm256_set1_epi64x(reinterpret_cast<int64_t>(base));
    const __m128i count = _mm_cvtsi32_si128(shift);
    // the 32-bit halves of the two sum vectors' 64-bit lanes in block order: blocks 0-3 are
    // the low halves of `lo`'s lanes, 4-7 of `hi`'s
    const __m256i order = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
    int j = 0;
    for (; j + 8 <= blocks; j += 8) {
        __m256i lo = zero, hi = zero;
        for (int y = 0; y < rows; y++) {
            const uint8_t* row = src + stride * y + 8 * j;
            lo = _mm256_add_epi64(lo, _mm256_sad_epu8(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(row)), zero));
            hi = _mm256_add_epi64(hi,
                                  _mm256_sad_epu8(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 32)), zero));
        }
        // sums of at most 64 * 255 fit the low 32 bits of each lane
        const __m256i sums = _mm256_blend_epi32(_mm256_permutevar8x32_epi32(lo, order),
                                                _mm256_permutevar8x32_epi32(hi, order), 0xF0);
        const __m256i avg = _mm256_min_epu32(_mm256_srl_epi32(sums, count), top);
        const __m256i at_table = _mm256_add_epi32(_mm256_i32gather_epi32(offsets, avg, 4),
                                                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(places + j)));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + j),
                            _mm256_add_epi64(_mm256_cvtepi32_epi64(_mm256_castsi256_si128(at_table)), at));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + j + 4),
                            _mm256_add_epi64(_mm256_cvtepi32_epi64(_mm256_extracti128_si256(at_table, 1)), at));
    }
    return j;
}

}  // namespace avx2

#endif  // HWY_TARGET == HWY_AVX2

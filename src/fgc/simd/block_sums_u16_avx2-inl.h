// Sums of 8x8 blocks of 16-bit samples for the AVX2 target of fgc_kernels_hwy.cpp; included
// inside that file's HWY_NAMESPACE, on the AVX2 pass and on the AVX3 pass (after the 512-bit
// form there, for the groups of four blocks it leaves). Bit-equal to the generic
// BlockSumsU16 (simd_equivalence_test: FgcBlockSums16BitExact).
//
// Why a separate form: the generic one widens every sample to 32 bits (8 per vector) and
// reduces each block's vector across its lanes; pmaddwd adds pairs of 16-bit samples into
// 32-bit lanes, 16 samples (two blocks) per vector, and two hadds reduce four blocks at once.
// pmaddwd multiplies signed words, so the samples are biased by -32768 first (any 16-bit
// value, not only those within the bit depth, keeps its exact sum) and the bias is added back
// per block. On a Zen 3 (1080p 10-bit rdd5, one thread) the block sums were 24 % of the
// profile, and the frame took 0.83-1.08 ms against 0.99-1.34 (4 interleaved rounds). The same
// for 16x16 blocks (one vector per block row, three hadds for four blocks) was slower than
// the generic form (25 % of vtm's 10-bit profile against 20 %) and is not used.
#if HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3

namespace avx2 {

// The first `blocks` whole 8-sample blocks' sums in groups of four; returns how many it did.
inline int BlockSums8U16(const uint16_t* src, std::ptrdiff_t stride, int rows, int blocks, uint32_t* sums) {
    const __m256i flip = _mm256_set1_epi16(int16_t(0x8000)), ones = _mm256_set1_epi16(1);
    // after two hadds the 32-bit lanes hold blocks [0 2 0 2 | 1 3 1 3]
    const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 0, 4, 1, 5);
    const __m128i bias = _mm_set1_epi32(rows * 8 * 32768);
    int j = 0;
    for (; j + 4 <= blocks; j += 4) {
        __m256i a = _mm256_setzero_si256(), b = _mm256_setzero_si256();
        for (int y = 0; y < rows; y++) {
            const auto* row = reinterpret_cast<const __m256i*>(reinterpret_cast<const uint8_t*>(src) + stride * y +
                                                               16 * j);
            a = _mm256_add_epi32(a, _mm256_madd_epi16(_mm256_xor_si256(_mm256_loadu_si256(row), flip), ones));
            b = _mm256_add_epi32(b, _mm256_madd_epi16(_mm256_xor_si256(_mm256_loadu_si256(row + 1), flip), ones));
        }
        const __m256i h = _mm256_hadd_epi32(a, b);
        const __m256i four = _mm256_permutevar8x32_epi32(_mm256_hadd_epi32(h, h), order);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(sums + j), _mm_add_epi32(_mm256_castsi256_si128(four), bias));
    }
    return j;
}

}  // namespace avx2

#endif  // HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3

// 8-bit AV1 noise application (AV1 7.18.3.5) in whole 512-bit vectors, for the AVX3 target
// of av1_kernels_hwy.cpp on CPUs with AVX512-VBMI. Twins of blend_luma_row / blend_chroma_row
// (grain_blending.hpp), bit-equal to them; included inside that file's HWY_NAMESPACE, on the
// AVX3 pass only.
//
// Why a separate form: the generic kernels keep 16-bit lanes at 16 per vector (a block row is
// whole vectors everywhere) and look the 256-entry ScalingLut up by chains of 16-byte shuffles.
// With VBMI two two-table byte permutes (vpermi2b, 128 entries each) and the index's top bit
// look 64 samples up at once, so a vector can hold 64 samples: two 32-wide luma blocks or four
// 16-wide subsampled chroma blocks of one row. The 16-bit arithmetic then works on the
// samples in the order byte unpacking gives (the low and the high 8 bytes of every 128-bit
// lane), and the noise blocks are shuffled into that same order, so that the final unsigned
// saturating pack puts the samples back in place with no lane-crossing fix-up.
//
// The horizontal overlap (overlap_flag) changes the first two noise samples of every block
// but the first: faded in the noise vectors, all of a vector's blocks at once (FadeFirstPairs).
//
// Luma rows whose noise also comes as bytes (BlockNoiseRow::byte_blocks: 8-bit grain fits
// int8) never leave byte order: ByteNoiseOf64 and AddByteNoise64, with fewer operations and
// half the shuffles of the 16-bit form (docs/performance-notes.md gives the measurements).
#if HWY_TARGET == HWY_AVX3

// Highway's AVX3 target plus VBMI (vpermi2b); these functions are only called after
// HasAvx512Vbmi().
#define FG_AVX512_VBMI __attribute__((target(HWY_TARGET_STR ",avx512vbmi")))

namespace avx512 {

// Whether the CPU has AVX512-VBMI: Highway 1.0's AVX3 target does not require it (Skylake
// servers lack it), and its AVX3_DL target is not compiled, so the AVX3 kernels check.
// FILMGRAIN_NO_AVX512VBMI (any value) makes a VBMI machine take the path such CPUs take, so
// that the suite runs it (tests/CMakeLists.txt); it is read once, like the CPU itself.
inline bool HasAvx512Vbmi() {
    static const bool has = __builtin_cpu_supports("avx512vbmi") && !std::getenv("FILMGRAIN_NO_AVX512VBMI");
    return has;
}

// The 256-byte ScalingLut in four registers.
struct ByteLut {
    __m512i t0, t1, t2, t3;
};
FG_AVX512_VBMI inline ByteLut LoadByteLut(const uint8_t* lut) {
    return {_mm512_loadu_si512(lut), _mm512_loadu_si512(lut + 64), _mm512_loadu_si512(lut + 128),
            _mm512_loadu_si512(lut + 192)};
}
// lut[index] for 64 byte indices: bits 0-6 pick within each half, bit 7 the half.
FG_AVX512_VBMI inline __m512i LookUpBytes(const ByteLut& lut, __m512i index) {
    const __m512i low = _mm512_permutex2var_epi8(lut.t0, index, lut.t1);
    const __m512i high = _mm512_permutex2var_epi8(lut.t2, index, lut.t3);
    return _mm512_mask_mov_epi8(low, _mm512_movepi8_mask(index), high);
}

// How a row's blocks overlap horizontally (7.18.3.5, overlap_flag): not at all, by seams the
// caller made (BlockNoiseRow::seams), or faded here (BlockNoiseRow::fade).
enum class Overlap { kNone, kGivenSeams, kFade };

// The fade of a block's first two noise samples with columns block_width and block_width + 1
// of the block to its left: clamp((left * fade_old[k] + own * fade_new[k] + 16) >> 5). The sums
// fit 16-bit lanes at 8 bits (|noise| <= 128, weights summing to at most 45) and Round2 by 5 is
// a rounding high multiply by 1 << 10. (The subsampled weights (0, 32) of the second sample
// give back the block's own.) Faded in the vectors themselves, two or four blocks at a time:
// making them per row apart needs the left pairs gathered, which cost more (a gathered sample
// per cycle) than the fade's few operations.
struct SeamFade {
    __m512i w_old, w_new, round, gmin, gmax;
};
FG_AVX512_VBMI inline SeamFade MakeSeamFade(const BlockNoiseRow& row) {
    auto pair = [](int16_t a, int16_t b) { return int32_t(uint32_t(uint16_t(a)) | uint32_t(uint16_t(b)) << 16); };
    return {_mm512_set1_epi32(pair(row.fade_old[0], row.fade_old[1])),
            _mm512_set1_epi32(pair(row.fade_new[0], row.fade_new[1])), _mm512_set1_epi16(1 << 10),
            _mm512_set1_epi16(row.gmin), _mm512_set1_epi16(row.gmax)};
}
// The overlap columns of the blocks whose rows start at `p` and `q` (their samples
// block_width and block_width + 1) as 32-bit lanes 0-7 and 8-15.
FG_AVX512_VBMI inline __m512i LeftPairs(const int16_t* p, const int16_t* q, int block_width) {
    int32_t a, b;
    std::memcpy(&a, p + block_width, sizeof a);
    std::memcpy(&b, q + block_width, sizeof b);
    return _mm512_mask_set1_epi32(_mm512_set1_epi32(a), 0xFF00, b);
}
// The fade of every 32-bit lane of `own` with the same lane of `left`.
FG_AVX512_VBMI inline __m512i FadePairs(__m512i own, __m512i left, const SeamFade& f) {
    const __m512i sum = _mm512_add_epi16(_mm512_mullo_epi16(left, f.w_old), _mm512_mullo_epi16(own, f.w_new));
    return _mm512_min_epi16(_mm512_max_epi16(_mm512_mulhrs_epi16(sum, f.round), f.gmin), f.gmax);
}
// `noise` with its 32-bit lanes `at` (a block's first two samples each) faded with `left`.
FG_AVX512_VBMI inline __m512i FadeFirstPairs(__m512i noise, __m512i left, __mmask16 at, const SeamFade& f) {
    return _mm512_mask_mov_epi32(noise, at, FadePairs(noise, left, f));
}
// Four 16-wide blocks in sample order (blocks 0 and 1 start at 32-bit lanes 0 and 8 of `low`,
// blocks 2 and 3 of `high`), faded in one vector: the four first pairs gathered into lanes 0,
// 8, 4 and 12 by one permute, the left pairs of blocks[-1..2] broadcast there. Block 0 keeps
// its own where it is the row's first (`first_of_row`).
FG_AVX512_VBMI inline void FadeFourBlocks(const int16_t* const* blocks, bool first_of_row, const SeamFade& f,
                                          __m512i& low, __m512i& high) {
    const __m512i gather = _mm512_set_epi32(0, 0, 0, 24, 0, 0, 0, 8, 0, 0, 0, 16, 0, 0, 0, 0);
    const __m512i own = _mm512_permutex2var_epi32(low, gather, high);
    int32_t l[4];
    for (int k = 0; k < 4; ++k) std::memcpy(&l[k], blocks[k - 1] + 16, sizeof l[k]);
    __m512i left = _mm512_set1_epi32(l[0]);
    left = _mm512_mask_set1_epi32(left, 0xFF00, l[1]);
    left = _mm512_mask_set1_epi32(left, 0x00F0, l[2]);
    left = _mm512_mask_set1_epi32(left, 0xF000, l[3]);
    const __m512i faded = FadePairs(own, left, f);
    low = _mm512_mask_permutexvar_epi32(low, first_of_row ? 0x0100 : 0x0101,
                                        _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 8, 0, 0, 0, 0, 0, 0, 0, 0), faded);
    high = _mm512_mask_permutexvar_epi32(high, 0x0101,
                                         _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 12, 0, 0, 0, 0, 0, 0, 0, 4), faded);
}

// Noise of 64 samples from blocks[0] on (two 32-wide or four 16-wide blocks), in one of two
// orders of 16-bit lanes. Unpack order (kUnpackOrder): `low` holds samples 0-7, 16-23, 32-39
// and 48-55, `high` the others, as unpacking the bytes of a vector gives them. Sample order:
// `low` samples 0-31, `high` 32-63. With seams, the first two samples of each block are
// replaced by seams[0..] (one per block).
template <int kBlockWidth, bool kUnpackOrder, bool kSeams>
FG_AVX512_VBMI inline void NoiseOf64(const int16_t* const* blocks, const uint32_t* seams, __m512i& low,
                                     __m512i& high) {
    __m512i a, b;
    if constexpr (kBlockWidth == 32) {
        a = _mm512_loadu_si512(blocks[0]);
        b = _mm512_loadu_si512(blocks[1]);
    } else {
        auto two = [](const int16_t* p, const int16_t* q) FG_AVX512_VBMI {
            return _mm512_inserti64x4(_mm512_castsi256_si512(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))),
                                      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q)), 1);
        };
        a = two(blocks[0], blocks[1]);
        b = two(blocks[2], blocks[3]);
    }
    if constexpr (kUnpackOrder) {
        low = _mm512_shuffle_i64x2(a, b, _MM_SHUFFLE(2, 0, 2, 0));
        high = _mm512_shuffle_i64x2(a, b, _MM_SHUFFLE(3, 1, 3, 1));
    } else {
        low = a;
        high = b;
    }
    if constexpr (kSeams) {
        // Where each block starts, in 32-bit lanes: in unpack order all in `low`, at 0 and 8
        // (two blocks) or 0, 4, 8, 12 (four); in sample order at 0 (and 8) of each vector.
        const __m128i* at = reinterpret_cast<const __m128i*>(seams);  // one per block, no more
        const __m512i from = _mm512_castsi128_si512(kBlockWidth == 32 ? _mm_loadl_epi64(at) : _mm_loadu_si128(at));
        if constexpr (kUnpackOrder && kBlockWidth == 32) {
            low = _mm512_mask_permutexvar_epi32(low, 0x0101, _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0), from);
        } else if constexpr (kUnpackOrder) {
            low = _mm512_mask_permutexvar_epi32(low, 0x1111, _mm512_set_epi32(0, 0, 0, 3, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0, 0), from);
        } else if constexpr (kBlockWidth == 32) {
            low = _mm512_mask_permutexvar_epi32(low, 0x0001, _mm512_setzero_si512(), from);
            high = _mm512_mask_permutexvar_epi32(high, 0x0001, _mm512_set1_epi32(1), from);
        } else {
            low = _mm512_mask_permutexvar_epi32(low, 0x0101, _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0), from);
            high = _mm512_mask_permutexvar_epi32(high, 0x0101, _mm512_set_epi32(0, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 2), from);
        }
    }
}

// NoiseOf64 in sample order with the row's horizontal overlap: the given seams, or the fade
// of each block's first pair (blocks start at 32-bit lane 0 of each vector, and 8 with four
// 16-wide blocks); the row's first block (`first_of_row`) has no left. The 8-bit chroma rows,
// the 10-bit rows and the cross-faded rows take their noise so. (At 10 bits |noise| <= 512:
// the fade's sums still fit 16-bit lanes.)
template <int kBlockWidth, Overlap kOverlap>
FG_AVX512_VBMI HWY_INLINE void OverlappedNoiseOf64(const int16_t* const* blocks, const uint32_t* seams,
                                                   bool first_of_row, const SeamFade& fade, __m512i& low,
                                                   __m512i& high) {
    NoiseOf64<kBlockWidth, false, kOverlap == Overlap::kGivenSeams>(blocks, seams, low, high);
    if constexpr (kOverlap == Overlap::kFade) {
        if constexpr (kBlockWidth == 16) {
            FadeFourBlocks(blocks, first_of_row, fade, low, high);
        } else {
            // blocks[-1] is block 0's own where it has no left
            low = FadeFirstPairs(low, LeftPairs(blocks[-1], blocks[-1], kBlockWidth), first_of_row ? 0 : 0x0001,
                                 fade);
            high = FadeFirstPairs(high, LeftPairs(blocks[0], blocks[0], kBlockWidth), 0x0001, fade);
        }
    }
}

// What a row's 64-sample steps share: the LUT, the q15 shift of the scales (or, for byte
// noise, the q15 multiplier 1 << (15 - shift) of the exact products) and the clip.
struct BlendConstants {
    ByteLut lut;
    __m128i up_shift;
    __m512i shift_multiplier, min_value, max_value;
};

// clip(src + Round2(lut[index] * noise, shift)) of 64 samples as bytes in sample order. The
// scaling indices come packed by _mm512_packus_epi16 from 16-bit lanes in some order, and
// src, noise and the result are in that order: unpacking the looked-up bytes gives back the
// order the indices had before packing. (In unpack order the final pack restores sample
// order; in sample order it leaves the 128-bit lanes interleaved, which one permute fixes.)
template <bool kClip, bool kUnpackOrder>
FG_AVX512_VBMI inline __m512i AddNoise64(const BlendConstants& c, __m512i packed_index, __m512i src_low,
                                         __m512i src_high, __m512i noise_low, __m512i noise_high) {
    const __m512i zero = _mm512_setzero_si512();
    const __m512i scale = LookUpBytes(c.lut, packed_index);
    const __m512i scale_low = _mm512_sll_epi16(_mm512_unpacklo_epi8(scale, zero), c.up_shift);
    const __m512i scale_high = _mm512_sll_epi16(_mm512_unpackhi_epi8(scale, zero), c.up_shift);
    const __m512i low = _mm512_add_epi16(src_low, _mm512_mulhrs_epi16(scale_low, noise_low));
    const __m512i high = _mm512_add_epi16(src_high, _mm512_mulhrs_epi16(scale_high, noise_high));
    __m512i out = _mm512_packus_epi16(low, high);  // 0..255 first: no clip range lies outside it
    if constexpr (!kUnpackOrder) out = _mm512_permutexvar_epi64(_mm512_set_epi64(7, 5, 3, 1, 6, 4, 2, 0), out);
    if constexpr (kClip) out = _mm512_min_epu8(_mm512_max_epu8(out, c.min_value), c.max_value);
    return out;
}

// The blocks of the 64 samples from x on and the one on their left, into at[0..64 / kBlockWidth];
// returns at + 1, so that [-1] is the left one (block 0's own where x is the row's start).
template <int kBlockWidth>
FG_AVX512_VBMI HWY_INLINE const int16_t* const* StepBlocks(const BlockNoiseRow& row, int x, const int16_t* (&at)[5]) {
    const int b = x / kBlockWidth;  // a constant width: a shift, not a division
    for (int k = -1; k < 64 / kBlockWidth; ++k) at[k + 1] = row.block(b + k < 0 ? 0 : b + k);
    return at + 1;
}

// Drives a row: step(x, blocks, given seams from x's block or null) for every whole
// 64 samples up to `vector_end`, then tail(x, seams of x's block and on, or null) once for the
// samples after them, if any (faded here when the steps fade them).
template <int kBlockWidth, Overlap kOverlap, class Step, class Tail>
FG_AVX512_VBMI inline void ForEach64(const BlockNoiseRow& row, int width, int vector_end, Step&& step, Tail&& tail) {
    constexpr int bw = kBlockWidth;  // a constant: the block of x is a shift, not a division
    const int main_end = vector_end / 64 * 64;
    int x = 0;
    for (; x < main_end; x += 64) {
        const int16_t* blocks[5];
        step(x, StepBlocks<bw>(row, x, blocks), kOverlap == Overlap::kGivenSeams ? row.seams + x / bw : nullptr);
    }
    if (x >= width) return;
    uint32_t faded[64 / 16 + 1];
    const uint32_t* seams = nullptr;
    if constexpr (kOverlap == Overlap::kGivenSeams) seams = row.seams + x / bw;
    if constexpr (kOverlap == Overlap::kFade) {
        for (int b = x / bw, k = 0; b * bw < width; ++b, ++k)
            faded[k] = uint32_t(uint16_t(row.at(b * bw))) | uint32_t(uint16_t(row.at(b * bw + 1))) << 16;
        seams = faded;
    }
    tail(x, seams);
}

// The row from x on as the generic kernels take it: its blocks from x's, their seams given.
inline BlockNoiseRow RowFrom(const BlockNoiseRow& row, int x, const uint32_t* seams) {
    BlockNoiseRow tail = row;
    tail.blocks = row.blocks + x / row.block_width;
    tail.seams = seams;
    tail.fade = false;
    return tail;
}

FG_AVX512_VBMI inline BlendConstants MakeConstants(const ScalingLookup& scaling, int scaling_shift, int min_value,
                                                   int max_value) {
    return {LoadByteLut(scaling.table8().data()), _mm_cvtsi32_si128(15 - scaling_shift),
            _mm512_set1_epi16(int16_t(1 << (15 - scaling_shift))), _mm512_set1_epi8(char(min_value)),
            _mm512_set1_epi8(char(max_value))};
}

// Byte noise (BlockNoiseRow::byte_blocks), luma: the 64 samples of blocks b and b + 1 are one
// vector of int8 noise in sample order, loaded as two 32-byte halves.
//
// The seams: a block's first two samples fade with columns 32 and 33 of its left block. Those
// two columns of block b - 1 and of block b, loaded as the first bytes of each half (the same
// row of each block, 32 bytes on), interleave byte by byte with the own noise, so that one
// unsigned x signed byte multiply-add by the (old, new) weight pairs makes each weighted sum
// in a 16-bit lane (at most 45 * 128: no saturation); the rounding high multiply by 1 << 10
// is Round2 by 5, and the signed saturating pack back to bytes is the clamp to -128..127,
// GrainMin and GrainMax at 8 bits.
struct ByteSeamFade {
    __m512i weights, round;
};
FG_AVX512_VBMI inline ByteSeamFade MakeByteSeamFade(const BlockNoiseRow& row) {
    const uint32_t w = uint32_t(uint8_t(row.fade_old[0])) | uint32_t(uint8_t(row.fade_new[0])) << 8 |
                       uint32_t(uint8_t(row.fade_old[1])) << 16 | uint32_t(uint8_t(row.fade_new[1])) << 24;
    return {_mm512_set1_epi32(int32_t(w)), _mm512_set1_epi16(1 << 10)};
}
template <bool kFade>
FG_AVX512_VBMI inline __m512i ByteNoiseOf64(const int8_t* left, const int8_t* own, const int8_t* next,
                                            __mmask64 seams, const ByteSeamFade& f) {
    auto halves = [](const int8_t* a, const int8_t* b) FG_AVX512_VBMI {
        return _mm512_inserti64x4(_mm512_castsi256_si512(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(a))),
                                  _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b)), 1);
    };
    const __m512i noise = halves(own, next);
    if constexpr (!kFade) return noise;
    const __m512i columns = halves(left + 32, own + 32);  // bytes 0-1 and 32-33 used
    const __m512i sums = _mm512_maddubs_epi16(f.weights, _mm512_unpacklo_epi8(columns, noise));
    const __m512i faded = _mm512_mulhrs_epi16(sums, f.round);
    return _mm512_mask_mov_epi8(noise, seams, _mm512_packs_epi16(faded, faded));
}

// clip(src + Round2(lut[src] * noise, shift)) of 64 samples, the noise as int8 in sample order,
// without leaving byte order. The unsigned x signed byte multiply-add of the scales with the
// noise's even bytes (odd ones zeroed) is scale * noise of the even samples in 16-bit lanes,
// with the odd bytes kept the odd samples' (at most 255 * 128: no saturation); the rounding high
// multiply by 1 << (15 - shift) is Round2 by shift. Since shift >= 8 that is within -127..127, so
// the low byte of each lane is the whole term, and the odd samples' terms shifted up into the
// high bytes complete the 64 terms as bytes. src + term clipped to 0..255 is then one signed
// saturating byte add of both with src biased by 128 (and the bias taken off again).
template <bool kClip>
FG_AVX512_VBMI inline __m512i AddByteNoise64(const BlendConstants& c, __m512i src, __m512i noise) {
    constexpr __mmask64 kEven = 0x5555555555555555ull;
    const __m512i scale = LookUpBytes(c.lut, src);
    auto terms = [&](__mmask64 samples) FG_AVX512_VBMI {
        return _mm512_mulhrs_epi16(_mm512_maddubs_epi16(scale, _mm512_maskz_mov_epi8(samples, noise)),
                                   c.shift_multiplier);
    };
    const __m512i term = _mm512_mask_mov_epi8(terms(kEven), ~kEven, _mm512_slli_epi16(terms(~kEven), 8));
    const __m512i bias = _mm512_set1_epi8(char(0x80));
    __m512i out = _mm512_xor_si512(_mm512_adds_epi8(_mm512_xor_si512(src, bias), term), bias);
    if constexpr (kClip) out = _mm512_min_epu8(_mm512_max_epu8(out, c.min_value), c.max_value);
    return out;
}

// Twin of blend_luma_row at 8 bits for rows.count rows (PlaneRows); `rest(r, x, seams)` blends
// samples [x, width) of row r the generic way. Unpack order: the samples themselves are the
// indices, and the noise shuffles cost what a lane-restoring permute would.
// With kBytes (byte_blocks set; no given seams) the steps read the noise as bytes.
template <Overlap kOverlap, bool kClip, bool kBytes, class Rest>
FG_AVX512_VBMI void LumaRows(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& first_row,
                             int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                             Rest&& rest) {
    // made once for the rows, in registers
    const BlendConstants c = MakeConstants(scaling, scaling_shift, min_value, max_value);
    const SeamFade fade = MakeSeamFade(first_row);
    const ByteSeamFade byte_fade = MakeByteSeamFade(first_row);
    const __m512i zero = _mm512_setzero_si512();
    BlockNoiseRow row = first_row;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step) {
        const uint8_t* s = src + r * rows.src_stride;
        uint8_t* d = dst + r * rows.dst_stride;
        ForEach64<32, kOverlap>(
            row, width, width,
            [&](int x, const int16_t* const* blocks, const uint32_t* seams) FG_AVX512_VBMI {
                if constexpr (kBytes) {
                    static_assert(kOverlap != Overlap::kGivenSeams);
                    // the seams of both halves; the row's first block has no left
                    const int b = x / 32;
                    const __m512i noise = ByteNoiseOf64<kOverlap == Overlap::kFade>(
                        row.byte_block(b ? b - 1 : 0), row.byte_block(b), row.byte_block(b + 1),
                        x ? 0x0000000300000003ull : 0x0000000300000000ull, byte_fade);
                    _mm512_storeu_si512(d + x, AddByteNoise64<kClip>(c, _mm512_loadu_si512(s + x), noise));
                    return;
                }
                __m512i noise_low, noise_high;
                NoiseOf64<32, true, kOverlap == Overlap::kGivenSeams>(blocks, seams, noise_low, noise_high);
                if constexpr (kOverlap == Overlap::kFade) {
                    // both blocks start in noise_low, at 32-bit lanes 0 and 8; the row's first has no left
                    const __m512i left = LeftPairs(blocks[-1], blocks[0], 32);
                    noise_low = FadeFirstPairs(noise_low, left, x ? 0x0101 : 0x0100, fade);
                }
                const __m512i v = _mm512_loadu_si512(s + x);
                _mm512_storeu_si512(d + x, AddNoise64<kClip, true>(c, v, _mm512_unpacklo_epi8(v, zero),
                                                                   _mm512_unpackhi_epi8(v, zero), noise_low,
                                                                   noise_high));
            },
            [&](int x, const uint32_t* seams) { rest(r, row, x, seams); });
    }
}

// The 64 chroma scaling indices (`merged`, chroma_scaling_index) from chroma x on, in sample
// order in 16-bit lanes (samples 0-31, 32-63); src_low / src_high are the chroma samples so.
template <bool kSubsampled, bool kFromLuma>
FG_AVX512_VBMI inline void ChromaIndices64(const uint8_t* luma, int x, __m512i src_low, __m512i src_high,
                                           __m512i mults, __m512i offset, __m512i& low, __m512i& high) {
    if constexpr (kSubsampled) {
        // pair sums by a multiply-add with ones; the rounding average with 0 is
        // (sum + 1) >> 1, co_sited_luma's
        const __m512i ones = _mm512_set1_epi8(1), zero = _mm512_setzero_si512();
        low = _mm512_avg_epu16(_mm512_maddubs_epi16(_mm512_loadu_si512(luma + 2 * x), ones), zero);
        high = _mm512_avg_epu16(_mm512_maddubs_epi16(_mm512_loadu_si512(luma + 2 * x + 64), ones), zero);
    } else {
        low = _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(luma + x)));
        high = _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(luma + x + 32)));
    }
    if constexpr (!kFromLuma) {
        // (luma, chroma) as the two bytes of each 16-bit lane, one unsigned x signed byte
        // multiply-add: its int16 saturation only happens where the index is clipped anyway
        // (32767 >> 6 = 511 and -32768 >> 6 = -512 stay outside 0..255 after any offset in
        // -256..255), and the narrowing pack's unsigned saturation is the clip.
        auto merged = [&](__m512i avg, __m512i chroma) FG_AVX512_VBMI {
            const __m512i pairs = _mm512_or_si512(avg, _mm512_slli_epi16(chroma, 8));
            return _mm512_add_epi16(_mm512_srai_epi16(_mm512_maddubs_epi16(pairs, mults), 6), offset);
        };
        low = merged(low, src_low);
        high = merged(high, src_high);
    }
}

// Twin of blend_chroma_row at 8 bits for rows.count rows (PlaneRows); `rest(r, row, x, seams)`
// blends samples [x, width) of row r the generic way. Sample order: the co-sited luma averages
// come out so, and putting them in unpack order would cost two shuffles more than the one
// permute that restores the output's lanes.
template <bool kSubsampled, bool kFromLuma, Overlap kOverlap, bool kClip, class Rest>
FG_AVX512_VBMI void ChromaRows(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                               const PlaneRows& rows, const BlockNoiseRow& first_row, int width,
                               const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                               int min_value, int max_value, Rest&& rest) {
    const BlendConstants c = MakeConstants(scaling, scaling_shift, min_value, max_value);
    const SeamFade fade = MakeSeamFade(first_row);
    const __m512i mults = _mm512_set1_epi16(int16_t(uint16_t(uint8_t(index.luma_mult)) | uint16_t(uint8_t(index.mult)) << 8));
    const __m512i offset = _mm512_set1_epi16(int16_t(index.offset));
    // The last column of an odd-width subsampled row pairs the last luma sample with itself.
    const int vector_end = kSubsampled && (luma_width & 1) ? width - 1 : width;
    constexpr int bw = kSubsampled ? 16 : 32;
    BlockNoiseRow row = first_row;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step) {
        const uint8_t* s = src + r * rows.src_stride;
        const uint8_t* l = luma + r * rows.luma_stride;
        uint8_t* d = dst + r * rows.dst_stride;
        ForEach64<bw, kOverlap>(
            row, width, vector_end,
            [&](int x, const int16_t* const* blocks, const uint32_t* seams) FG_AVX512_VBMI {
                __m512i noise_low, noise_high, index_low, index_high;
                OverlappedNoiseOf64<bw, kOverlap>(blocks, seams, x == 0, fade, noise_low, noise_high);
                const __m512i s_low = _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + x)));
                const __m512i s_high =
                    _mm512_cvtepu8_epi16(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(s + x + 32)));
                ChromaIndices64<kSubsampled, kFromLuma>(l, x, s_low, s_high, mults, offset, index_low, index_high);
                _mm512_storeu_si512(d + x, AddNoise64<kClip, false>(c, _mm512_packus_epi16(index_low, index_high),
                                                                    s_low, s_high, noise_low, noise_high));
            },
            [&](int x, const uint32_t* seams) { rest(r, row, x, seams); });
    }
}

// The noise of samples [x, x + 64) of a row whose horizontal overlap is faded in the kernel
// (fade) or absent, in sample order (as NoiseOf64), faded.
template <int kBlockWidth, bool kFade>
FG_AVX512_VBMI inline void FadedNoiseOf64(const BlockNoiseRow& row, int x, const SeamFade& fade, __m512i& low,
                                          __m512i& high) {
    const int16_t* at[5];
    OverlappedNoiseOf64<kBlockWidth, kFade ? Overlap::kFade : Overlap::kNone>(StepBlocks<kBlockWidth>(row, x, at),
                                                                            nullptr, x == 0, fade, low, high);
}

// Twin of assemble_cross_faded_row up to 10 bits (where the weighted sums fit 16-bit lanes):
// both rows' noise 64 samples at a time, then the vertical fade; `rest(x)` assembles the
// samples from x on the generic way.
template <int kBlockWidth, bool kFade, class Rest>
FG_AVX512_VBMI void CrossFadedRow(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise, int width,
                                  int old_weight, int new_weight, int16_t* out, Rest&& rest) {
    const BlockNoiseRow above = old_noise, own = new_noise;  // local: the stores cannot alias them
    const SeamFade fade_above = MakeSeamFade(above), fade_own = MakeSeamFade(own);
    const __m512i w_old = _mm512_set1_epi16(int16_t(old_weight)), w_new = _mm512_set1_epi16(int16_t(new_weight));
    const __m512i round = _mm512_set1_epi16(1 << 10);
    const __m512i gmin = _mm512_set1_epi16(own.gmin), gmax = _mm512_set1_epi16(own.gmax);
    auto vertical = [&](__m512i a, __m512i o) FG_AVX512_VBMI {
        const __m512i sum = _mm512_add_epi16(_mm512_mullo_epi16(a, w_old), _mm512_mullo_epi16(o, w_new));
        return _mm512_min_epi16(_mm512_max_epi16(_mm512_mulhrs_epi16(sum, round), gmin), gmax);
    };
    int x = 0;
    for (; x + 64 <= width; x += 64) {
        __m512i a_low, a_high, o_low, o_high;
        FadedNoiseOf64<kBlockWidth, kFade>(above, x, fade_above, a_low, a_high);
        FadedNoiseOf64<kBlockWidth, kFade>(own, x, fade_own, o_low, o_high);
        _mm512_storeu_si512(out + x, vertical(a_low, o_low));
        _mm512_storeu_si512(out + x + 32, vertical(a_high, o_high));
    }
    if (x < width) rest(x);
}

// The template arguments of LumaRow / ChromaRow from run-time flags: each combination is
// its own loop, so that no step tests them.
template <class F>
FG_AVX512_VBMI HWY_INLINE void WithFlag(bool flag, F&& f) {
    if (flag)
        f(std::true_type());
    else
        f(std::false_type());
}
template <class F>
FG_AVX512_VBMI HWY_INLINE void WithOverlap(const BlockNoiseRow& row, F&& f) {
    if (row.seams)
        f(std::integral_constant<Overlap, Overlap::kGivenSeams>());
    else if (row.fade)
        f(std::integral_constant<Overlap, Overlap::kFade>());
    else
        f(std::integral_constant<Overlap, Overlap::kNone>());
}

}  // namespace avx512

#endif  // HWY_TARGET == HWY_AVX3

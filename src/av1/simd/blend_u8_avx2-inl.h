// 8-bit AV1 noise application (AV1 7.18.3.5) 64 samples per step, for the AVX2 target of
// av1_kernels_hwy.cpp: twins of blend_luma_row / blend_chroma_row (grain_blending.hpp),
// bit-equal to them; included inside that file's HWY_NAMESPACE, on the AVX2 pass only.
//
// Why a separate form: the generic kernels make a chunk's scaling indices, then its scales
// (LookUpScaling8), then blend, each pass through a buffer, and the blend loads every sample
// again. Here one step does all of it in registers, as the 512-bit VBMI form
// (blend_u8_avx512-inl.h) does: the sample bytes are the luma indices, the chroma indices
// are packed to bytes from the 16-bit lanes they are computed in, the LUT is looked up by
// the generic kernels' shuffle rows (two 32-byte vectors sharing one three-row test,
// LookUpPair), and the scales are unpacked from the looked-up bytes. AVX2 unpacks and packs
// within 128-bit lanes, so luma works in unpack order (the 16-bit lanes hold samples 0-7 and
// 16-23, then 8-15 and 24-31; the noise is loaded in that order and the final pack restores
// the samples' order), and chroma in sample order (its indices come out of the co-sited luma
// so; one permute restores the output). The horizontal overlap of a step's blocks is faded
// in one 128-bit vector of their first pairs (FadeFirstPairs). Luma rows that also come as
// int8 noise (BlockNoiseRow::byte_blocks) stay in byte order instead: a 32-sample vector is
// one block's row, one load, its seam faded as byte pairs (FadedByteNoise32) and its terms
// made as bytes (AddByteNoise32), as in the VBMI form.
#if HWY_TARGET == HWY_AVX2

namespace avx2 {

// How a row's blocks overlap horizontally (7.18.3.5, overlap_flag): not at all, by seams the
// caller made (BlockNoiseRow::seams), or faded here (BlockNoiseRow::fade).
enum class Overlap { kNone, kGivenSeams, kFade };

// What a row's steps share: the LUT's shuffle rows, the q15 shift of the scales (or, for byte
// noise, the multiplier that is Round2 by shift), the clip and the overlap fade's weights (as
// FadeConstantsOf, in 32-bit pairs; for byte noise as the (old, new) byte pairs of the first two
// columns, then (0, 32) pairs, which keep a column as it is).
struct StepConstants {
    ShuffleRows<D8> rows;
    __m128i up_shift;
    __m256i shift_multiplier;
    __m256i min_value, max_value;
    __m256i w_old, w_new, round, gmin, gmax;
    __m128i byte_fade_weights;
};

inline StepConstants MakeStepConstants(const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                                       const BlockNoiseRow& row) {
    auto pair = [](int16_t a, int16_t b) { return int32_t(uint32_t(uint16_t(a)) | uint32_t(uint16_t(b)) << 16); };
    auto bytes = [](int a, int b, int c, int d) {
        return int32_t(uint32_t(uint8_t(a)) | uint32_t(uint8_t(b)) << 8 | uint32_t(uint8_t(c)) << 16 |
                       uint32_t(uint8_t(d)) << 24);
    };
    const int32_t keep = bytes(0, 32, 0, 32);
    return {ShuffleRows<D8>(scaling.table8().data(), scaling.lut8_chain()),
            _mm_cvtsi32_si128(15 - scaling_shift),
            _mm256_set1_epi16(int16_t(1 << (15 - scaling_shift))),
            _mm256_set1_epi8(char(min_value)),
            _mm256_set1_epi8(char(max_value)),
            _mm256_set1_epi32(pair(row.fade_old[0], row.fade_old[1])),
            _mm256_set1_epi32(pair(row.fade_new[0], row.fade_new[1])),
            _mm256_set1_epi16(1 << 10),
            _mm256_set1_epi16(row.gmin),
            _mm256_set1_epi16(row.gmax),
            _mm_set_epi32(keep, keep, keep,
                          bytes(row.fade_old[0], row.fade_new[0], row.fade_old[1], row.fade_new[1]))};
}

// `noise` with its 32-bit lane 0 (a block's first two samples) replaced by the fade with the
// block to the left, whose row starts at `left`: clamp((left * fade_old[k] + own * fade_new[k]
// + 16) >> 5). The sums fit 16-bit lanes at 8 bits (|noise| <= 128, weights summing to at most
// 45); Round2 by 5 is a rounding high multiply by 1 << 10.
HWY_INLINE __m256i FadeFirstPair(__m256i noise, const int16_t* left, int block_width, const StepConstants& c) {
    int32_t pair;
    std::memcpy(&pair, left + block_width, sizeof pair);
    const __m256i sum = _mm256_add_epi16(_mm256_mullo_epi16(_mm256_set1_epi32(pair), c.w_old),
                                         _mm256_mullo_epi16(noise, c.w_new));
    const __m256i faded = _mm256_min_epi16(_mm256_max_epi16(_mm256_mulhrs_epi16(sum, c.round), c.gmin), c.gmax);
    return _mm256_blend_epi32(noise, faded, 0x01);
}
// `noise` with its 32-bit lane 0 replaced by a given seam.
HWY_INLINE __m256i SeamFirstPair(__m256i noise, uint32_t seam) {
    return _mm256_blend_epi32(noise, _mm256_set1_epi32(int32_t(seam)), 0x01);
}

// The block starting in lane 0 of `noise`, overlapped with its left neighbour: block b of the
// row, x its first sample.
template <Overlap kOverlap, int kBlockWidth>
HWY_INLINE __m256i OverlapFirstPair(__m256i noise, const BlockNoiseRow& row, int b, int x, const StepConstants& c) {
    if constexpr (kOverlap == Overlap::kGivenSeams) return SeamFirstPair(noise, row.seams[b]);
    if constexpr (kOverlap == Overlap::kFade) {
        if (x > 0) return FadeFirstPair(noise, row.block(b - 1), kBlockWidth, c);
    }
    return noise;
}

// The first pairs of kBlocks (2 or 4) blocks, each in 32-bit lane 0 of its noise vector,
// overlapped with their left neighbours (whose rows start at left[k]) in one 128-bit fade,
// as FadeFirstPair: the fade's operations once for a step instead of once per block. Block 0
// keeps its own where it is the row's first (`keep_first`).
template <int kBlocks>
HWY_INLINE void FadeFirstPairs(__m256i* const (&noise)[kBlocks], const int16_t* const (&left)[kBlocks],
                               int block_width, bool keep_first, const StepConstants& c) {
    __m128i own = _mm256_castsi256_si128(_mm256_unpacklo_epi32(*noise[0], *noise[1]));  // dwords: block 0, 1
    if constexpr (kBlocks == 4)
        own = _mm_unpacklo_epi64(own, _mm256_castsi256_si128(_mm256_unpacklo_epi32(*noise[2], *noise[3])));
    int32_t pair;
    std::memcpy(&pair, left[0] + block_width, sizeof pair);
    __m128i lefts = _mm_cvtsi32_si128(pair);
    std::memcpy(&pair, left[1] + block_width, sizeof pair);
    lefts = _mm_insert_epi32(lefts, pair, 1);
    if constexpr (kBlocks == 4) {
        std::memcpy(&pair, left[2] + block_width, sizeof pair);
        lefts = _mm_insert_epi32(lefts, pair, 2);
        std::memcpy(&pair, left[3] + block_width, sizeof pair);
        lefts = _mm_insert_epi32(lefts, pair, 3);
    }
    const __m128i sum = _mm_add_epi16(_mm_mullo_epi16(lefts, _mm256_castsi256_si128(c.w_old)),
                                      _mm_mullo_epi16(own, _mm256_castsi256_si128(c.w_new)));
    __m128i faded = _mm_mulhrs_epi16(sum, _mm256_castsi256_si128(c.round));
    faded = _mm_min_epi16(_mm_max_epi16(faded, _mm256_castsi256_si128(c.gmin)), _mm256_castsi256_si128(c.gmax));
    if (keep_first) faded = _mm_blend_epi32(faded, own, 0x1);
    *noise[0] = _mm256_blend_epi32(*noise[0], _mm256_castsi128_si256(faded), 0x01);
    *noise[1] = _mm256_blend_epi32(*noise[1], _mm256_castsi128_si256(_mm_shuffle_epi32(faded, 0x55)), 0x01);
    if constexpr (kBlocks == 4) {
        *noise[2] = _mm256_blend_epi32(*noise[2], _mm256_castsi128_si256(_mm_shuffle_epi32(faded, 0xAA)), 0x01);
        *noise[3] = _mm256_blend_epi32(*noise[3], _mm256_castsi128_si256(_mm_shuffle_epi32(faded, 0xFF)), 0x01);
    }
}

HWY_INLINE __m128i Load128(const void* p) { return _mm_loadu_si128(static_cast<const __m128i*>(p)); }
HWY_INLINE __m256i Load256(const void* p) { return _mm256_loadu_si256(static_cast<const __m256i*>(p)); }

// clip(src + Round2(scale * noise, shift)) of 32 samples, `scale` the looked-up bytes of
// indices packed (packus) from the 16-bit lanes that src, noise and the result use:
// unpacking them gives back that order. In unpack order the final pack restores the
// samples' order; in sample order one permute does.
template <bool kClip, bool kUnpackOrder>
HWY_INLINE __m256i AddScaledNoise32(const StepConstants& c, __m256i scale, __m256i src_low, __m256i src_high,
                                    __m256i noise_low, __m256i noise_high) {
    const __m256i zero = _mm256_setzero_si256();
    const __m256i scale_low = _mm256_sll_epi16(_mm256_unpacklo_epi8(scale, zero), c.up_shift);
    const __m256i scale_high = _mm256_sll_epi16(_mm256_unpackhi_epi8(scale, zero), c.up_shift);
    const __m256i low = _mm256_add_epi16(src_low, _mm256_mulhrs_epi16(scale_low, noise_low));
    const __m256i high = _mm256_add_epi16(src_high, _mm256_mulhrs_epi16(scale_high, noise_high));
    __m256i out = _mm256_packus_epi16(low, high);  // 0..255 first: no clip range lies outside it
    if constexpr (!kUnpackOrder) out = _mm256_permute4x64_epi64(out, 0xD8);
    if constexpr (kClip) out = _mm256_min_epu8(_mm256_max_epu8(out, c.min_value), c.max_value);
    return out;
}

// The scales of one or two vectors of 32 byte indices: two share LookUpPair's three-row test
// (decoded pictures are locally smooth), one takes LookUpVector's.
HWY_INLINE __m256i LookUp32(const StepConstants& c, __m256i index) {
    hn::Vec<D8> scale[1];
    const ShuffleRows<D8>* const tables[1] = {&c.rows};
    LookUpVector<1>(D8(), hn::Vec<D8>{index}, tables, scale);
    return scale[0].raw;
}
HWY_INLINE void LookUp64(const StepConstants& c, __m256i index_a, __m256i index_b, __m256i& scale_a,
                         __m256i& scale_b) {
    hn::Vec<D8> a, b;
    LookUpPair(hn::Vec<D8>{index_a}, hn::Vec<D8>{index_b}, (_mm256_cvtsi256_si32(index_a) & 0xFF) >> 4, c.rows, a, b);
    scale_a = a.raw;
    scale_b = b.raw;
}

// Byte noise (BlockNoiseRow::byte_blocks), luma: a 32-sample vector is one block's row of int8
// noise in sample order, one load. Its first two samples fade with columns 32 and 33 of the
// left block (`left`, the same row): those interleave byte by byte with the own noise, so that
// one unsigned x signed byte multiply-add by the (old, new) weight pairs makes each weighted sum
// in a 16-bit lane (at most 45 * 128), the rounding high multiply by 1 << 10 is Round2 by 5 and
// the signed saturating pack is the clamp to -128..127 (GrainMin, GrainMax at 8 bits). The
// other pairs weigh (0, 32), which gives the own noise back, so the 32-bit lane of the first
// four bytes is replaced whole.
HWY_INLINE __m256i FadedByteNoise32(const int8_t* left, __m256i own, const StepConstants& c) {
    const __m128i pairs = _mm_unpacklo_epi8(Load128(left + 32), _mm256_castsi256_si128(own));
    const __m128i faded = _mm_mulhrs_epi16(_mm_maddubs_epi16(c.byte_fade_weights, pairs),
                                           _mm256_castsi256_si128(c.round));
    return _mm256_blend_epi32(own, _mm256_castsi128_si256(_mm_packs_epi16(faded, faded)), 0x01);
}

// clip(src + Round2(scale * noise, shift)) of 32 samples in byte order, the noise as int8, as
// the VBMI form's AddByteNoise64 (blend_u8_avx512-inl.h) argues: the scales times the even
// noise bytes (odd ones zeroed) and times the odd ones are exact products in 16-bit lanes
// (at most 255 * 128), the rounding high multiply by 1 << (15 - shift) is Round2 by shift,
// within -127..127 at shift >= 8, so the even terms' low bytes and the odd terms shifted into
// the high bytes are all 32 terms as bytes; src + term clipped to 0..255 is one signed
// saturating add with src biased by 128.
template <bool kClip>
HWY_INLINE __m256i AddByteNoise32(const StepConstants& c, __m256i src, __m256i scale, __m256i noise) {
    const __m256i even = _mm256_set1_epi16(0x00FF);
    const __m256i even_terms =
        _mm256_mulhrs_epi16(_mm256_maddubs_epi16(scale, _mm256_and_si256(noise, even)), c.shift_multiplier);
    const __m256i odd_terms =
        _mm256_mulhrs_epi16(_mm256_maddubs_epi16(scale, _mm256_andnot_si256(even, noise)), c.shift_multiplier);
    const __m256i terms = _mm256_blendv_epi8(_mm256_slli_epi16(odd_terms, 8), even_terms, even);
    const __m256i bias = _mm256_set1_epi8(char(0x80));
    __m256i out = _mm256_xor_si256(_mm256_adds_epi8(_mm256_xor_si256(src, bias), terms), bias);
    if constexpr (kClip) out = _mm256_min_epu8(_mm256_max_epu8(out, c.min_value), c.max_value);
    return out;
}

// Drives a row: step(x, std::integral_constant<int, 64 or 32>) for every whole 64 samples up
// to `vector_end` and one 32 after them where it fits, then tail(x) once for the samples
// after them, if any.
template <class Step, class Tail>
HWY_INLINE void ForEachStep(int width, int vector_end, Step&& step, Tail&& tail) {
    int x = 0;
    for (; x + 64 <= vector_end; x += 64) step(x, std::integral_constant<int, 64>());
    if (x + 32 <= vector_end) {
        step(x, std::integral_constant<int, 32>());
        x += 32;
    }
    if (x < width) tail(x);
}

// blend_luma_row's 8-bit AVX2 form over rows.count rows, in unpack order (the sample bytes
// are the indices; loading the noise so costs what a lane-restoring permute would);
// `rest(r, row, x)` takes each row's samples after the last whole 32.
// With kBytes (byte_blocks set; no given seams) the steps read the noise as bytes and stay in
// sample order.
template <Overlap kOverlap, bool kClip, bool kBytes, class Rest>
void LumaRows(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& first_row, int width,
              const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value, Rest&& rest) {
    const StepConstants c = MakeStepConstants(scaling, scaling_shift, min_value, max_value, first_row);
    const __m256i zero = _mm256_setzero_si256();
    BlockNoiseRow row = first_row;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step) {
        const uint8_t* s = src + r * rows.src_stride;
        uint8_t* d = dst + r * rows.dst_stride;
        // block x / 32's noise in unpack order (samples 0-7 and 16-23, then 8-15 and 24-31), its
        // first pair not yet overlapped
        struct Noise {
            __m256i low, high;
        };
        auto noise_at = [&](int x) FG_INLINE_LAMBDA {
            const int16_t* p = row.block(x / 32);
            return Noise{_mm256_inserti128_si256(_mm256_castsi128_si256(Load128(p)), Load128(p + 16), 1),
                         _mm256_inserti128_si256(_mm256_castsi128_si256(Load128(p + 8)), Load128(p + 24), 1)};
        };
        using BlockNoise = std::conditional_t<kBytes, __m256i, Noise>;
        // The noise of kBlocks blocks from block x / 32 on, each overlapped with its left
        // neighbour (the row's first has none).
        auto step_noise = [&]<int kBlocks>(int x, BlockNoise(&n)[kBlocks]) FG_INLINE_LAMBDA {
            const int b = x / 32;
            if constexpr (kBytes) {
                static_assert(kOverlap != Overlap::kGivenSeams);
                for (int k = 0; k < kBlocks; ++k) {
                    n[k] = Load256(row.byte_block(b + k));
                    if constexpr (kOverlap == Overlap::kFade)
                        if (k > 0 || x > 0) n[k] = FadedByteNoise32(row.byte_block(b + k - 1), n[k], c);
                }
            } else {
                for (int k = 0; k < kBlocks; ++k) n[k] = noise_at(x + 32 * k);
                if constexpr (kOverlap == Overlap::kFade && kBlocks == 2) {
                    FadeFirstPairs<2>({&n[0].low, &n[1].low}, {row.block(b > 0 ? b - 1 : 0), row.block(b)}, 32,
                                      x == 0, c);
                } else {
                    for (int k = 0; k < kBlocks; ++k)
                        n[k].low = OverlapFirstPair<kOverlap, 32>(n[k].low, row, b + k, x + 32 * k, c);
                }
            }
        };
        auto blend_block = [&](int x, __m256i v, __m256i scale, const BlockNoise& noise) FG_INLINE_LAMBDA {
            __m256i out;
            if constexpr (kBytes)
                out = AddByteNoise32<kClip>(c, v, scale, noise);
            else
                out = AddScaledNoise32<kClip, true>(c, scale, _mm256_unpacklo_epi8(v, zero),
                                                    _mm256_unpackhi_epi8(v, zero), noise.low, noise.high);
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + x), out);
        };
        ForEachStep(
            width, width,
            [&](int x, auto samples) FG_INLINE_LAMBDA {
                constexpr int kBlocks = decltype(samples)::value / 32;
                BlockNoise n[kBlocks];
                const __m256i v = Load256(s + x);
                if constexpr (kBlocks == 2) {
                    const __m256i w = Load256(s + x + 32);  // before the first store: in place
                    step_noise(x, n);
                    __m256i scale_v, scale_w;
                    LookUp64(c, v, w, scale_v, scale_w);
                    blend_block(x, v, scale_v, n[0]);
                    blend_block(x + 32, w, scale_w, n[1]);
                } else {
                    step_noise(x, n);
                    blend_block(x, v, LookUp32(c, v), n[0]);
                }
            },
            [&](int x) { rest(r, row, x); });
    }
}

// The 32 chroma scaling indices (`merged`, chroma_scaling_index) from chroma x on, in sample
// order in 16-bit lanes (samples 0-15, 16-31); src_low / src_high are the chroma samples so.
template <bool kSubsampled, bool kFromLuma>
HWY_INLINE void ChromaIndices32(const uint8_t* luma, int x, __m256i src_low, __m256i src_high, __m256i mults,
                                __m256i offset, __m256i& low, __m256i& high) {
    if constexpr (kSubsampled) {
        // pair sums by a multiply-add with ones; the rounding average with 0 is
        // (sum + 1) >> 1, co_sited_luma's
        const __m256i ones = _mm256_set1_epi8(1), zero = _mm256_setzero_si256();
        low = _mm256_avg_epu16(_mm256_maddubs_epi16(Load256(luma + 2 * x), ones), zero);
        high = _mm256_avg_epu16(_mm256_maddubs_epi16(Load256(luma + 2 * x + 32), ones), zero);
    } else {
        low = _mm256_cvtepu8_epi16(Load128(luma + x));
        high = _mm256_cvtepu8_epi16(Load128(luma + x + 16));
    }
    if constexpr (!kFromLuma) {
        // one pmaddubsw of (luma, chroma) byte pairs, exact wherever the index is not
        // clipped, as ChromaIndices64 argues (blend_u8_avx512-inl.h)
        auto merged = [&](__m256i avg, __m256i chroma) FG_INLINE_LAMBDA {
            const __m256i pairs = _mm256_or_si256(avg, _mm256_slli_epi16(chroma, 8));
            return _mm256_add_epi16(_mm256_srai_epi16(_mm256_maddubs_epi16(pairs, mults), 6), offset);
        };
        low = merged(low, src_low);
        high = merged(high, src_high);
    }
}

// blend_chroma_row's 8-bit AVX2 form over rows.count rows, in sample order (see the top);
// `rest(r, row, x)` takes each row's samples after the last whole 32.
template <bool kSubsampled, bool kFromLuma, Overlap kOverlap, bool kClip, class Rest>
void ChromaRows(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width, const PlaneRows& rows,
                const BlockNoiseRow& first_row, int width, const ChromaScalingIndex& index,
                const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value, Rest&& rest) {
    const StepConstants c = MakeStepConstants(scaling, scaling_shift, min_value, max_value, first_row);
    const __m256i mults =
        _mm256_set1_epi16(int16_t(uint16_t(uint8_t(index.luma_mult)) | uint16_t(uint8_t(index.mult)) << 8));
    const __m256i offset = _mm256_set1_epi16(int16_t(index.offset));
    // The last column of an odd-width subsampled row pairs the last luma sample with itself.
    const int vector_end = kSubsampled && (luma_width & 1) ? width - 1 : width;
    constexpr int bw = kSubsampled ? 16 : 32;
    BlockNoiseRow row = first_row;
    for (int r = 0; r < rows.count; ++r, row.row_offset += rows.noise_step) {
        const uint8_t* s = src + r * rows.src_stride;
        const uint8_t* l = luma + r * rows.luma_stride;
        uint8_t* d = dst + r * rows.dst_stride;
        // samples [x, x + 32): their source in sample order and their packed indices
        struct Samples {
            __m256i low, high, index;
        };
        auto samples_at = [&](int x) FG_INLINE_LAMBDA {
            Samples v{_mm256_cvtepu8_epi16(Load128(s + x)), _mm256_cvtepu8_epi16(Load128(s + x + 16)), {}};
            __m256i index_low, index_high;
            ChromaIndices32<kSubsampled, kFromLuma>(l, x, v.low, v.high, mults, offset, index_low, index_high);
            v.index = _mm256_packus_epi16(index_low, index_high);
            return v;
        };
        // the noise of samples [x, x + 32) in sample order, the first pairs of its blocks not
        // yet overlapped
        struct Noise {
            __m256i low, high;
        };
        auto noise_at = [&](int x) FG_INLINE_LAMBDA {
            const int b = x / bw;
            return kSubsampled ? Noise{Load256(row.block(b)), Load256(row.block(b + 1))}
                               : Noise{Load256(row.block(b)), Load256(row.block(b) + 16)};
        };
        // The first pairs of the blocks of samples [x, x + 32): one by one.
        auto overlap = [&](int x, Noise& n) FG_INLINE_LAMBDA {
            const int b = x / bw;
            n.low = OverlapFirstPair<kOverlap, bw>(n.low, row, b, x, c);
            if constexpr (kSubsampled) n.high = OverlapFirstPair<kOverlap, bw>(n.high, row, b + 1, x + bw, c);
        };
        auto blend = [&](int x, const Samples& v, __m256i scale, const Noise& n) FG_INLINE_LAMBDA {
            _mm256_storeu_si256(reinterpret_cast<__m256i*>(d + x),
                                AddScaledNoise32<kClip, false>(c, scale, v.low, v.high, n.low, n.high));
        };
        ForEachStep(
            width, vector_end,
            [&](int x, auto count) FG_INLINE_LAMBDA {
                const Samples v = samples_at(x);
                Noise nv = noise_at(x);
                if constexpr (decltype(count)::value == 64) {
                    const Samples w = samples_at(x + 32);  // before the first store: in place
                    Noise nw = noise_at(x + 32);
                    if constexpr (kOverlap == Overlap::kFade) {
                        const int b = x / bw;
                        if constexpr (kSubsampled)
                            FadeFirstPairs<4>({&nv.low, &nv.high, &nw.low, &nw.high},
                                              {row.block(b > 0 ? b - 1 : 0), row.block(b), row.block(b + 1),
                                               row.block(b + 2)},
                                              bw, x == 0, c);
                        else
                            FadeFirstPairs<2>({&nv.low, &nw.low}, {row.block(b > 0 ? b - 1 : 0), row.block(b)}, bw,
                                              x == 0, c);
                    } else {
                        overlap(x, nv);
                        overlap(x + 32, nw);
                    }
                    __m256i scale_v, scale_w;
                    LookUp64(c, v.index, w.index, scale_v, scale_w);
                    blend(x, v, scale_v, nv);
                    blend(x + 32, w, scale_w, nw);
                } else {
                    overlap(x, nv);
                    blend(x, v, LookUp32(c, v.index), nv);
                }
            },
            [&](int x) { rest(r, row, x); });
    }
}

// The template arguments of LumaRows / ChromaRows from run-time flags: each combination is
// its own loop, so that no step tests them.
template <class F>
HWY_INLINE void WithFlag(bool flag, F&& f) {
    if (flag)
        f(std::true_type());
    else
        f(std::false_type());
}
template <class F>
HWY_INLINE void WithOverlap(const BlockNoiseRow& row, F&& f) {
    if (row.seams)
        f(std::integral_constant<Overlap, Overlap::kGivenSeams>());
    else if (row.fade)
        f(std::integral_constant<Overlap, Overlap::kFade>());
    else
        f(std::integral_constant<Overlap, Overlap::kNone>());
}

}  // namespace avx2

#endif  // HWY_TARGET == HWY_AVX2

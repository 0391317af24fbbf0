// 10-bit AV1 noise application (AV1 7.18.3.5) 64 samples per step, for the AVX2 target of
// av1_kernels_hwy.cpp: twins of blend_luma_row and blend_chroma_row (chroma with unsubsampled
// or shared co-sited luma), bit-equal to them; included inside that file's HWY_NAMESPACE after
// InterpolatedScales and blend_u8_avx2-inl.h, on the AVX2 pass only.
//
// Why a separate form: the generic kernels look a chunk's scales up into a buffer
// (InterpolatedScales) and blend in a second pass that loads every sample again. Here a step
// keeps its indices, scales and sums in registers, and looks its scales up by byte shuffles
// over the rows of the full-range table its indices span (Scales10); a step holding a sample
// above 10 bits is left to the caller's scalar form (AnyAbove10Bits), so the samples a step
// blends are within the table as they are, and only merged chroma indices need clipping.
// 16-bit lanes hold samples in order throughout (the byte packing pairs lanes, never crosses
// them), so no permutes are needed.
#if HWY_TARGET == HWY_AVX2

namespace avx2 {

// What a 10-bit row's steps share besides the 8-bit StepConstants' fade weights: the scaling
// function and the look-up's and blend's constants.
struct Step10Constants {
    const ScalingLookup* scaling;
    const uint8_t* full_table;  // scaling->full_table()
    int scaling_shift;
    __m256i nibble, low_byte, one8, two, last;
    __m256i min_value, max_value;
    __m128i up_shift;
};

inline Step10Constants MakeStep10Constants(const ScalingLookup& scaling, int scaling_shift, int min_value,
                                           int max_value) {
    return {&scaling,
            scaling.full_table(),
            scaling_shift,
            _mm256_set1_epi16(15),
            _mm256_set1_epi16(0xFF),
            _mm256_set1_epi8(1),
            _mm256_set1_epi16(2),
            _mm256_set1_epi16(1023),
            _mm256_set1_epi16(int16_t(min_value)),
            _mm256_set1_epi16(int16_t(max_value)),
            _mm_cvtsi32_si128(15 - scaling_shift)};
}

// InterpolatedScales for the steps whose indices span more rows than Scales10 shuffles, out
// of line and with its own state: inlined, its state took the kernel's registers, which
// then spilled its scales and constants to the stack.
template <int kCount>
HWY_NOINLINE void LookUpOutOfLine(const ScalingLookup& scaling, int scaling_shift, const uint16_t* index,
                                  int16_t* scale) {
    InterpolatedScales scales(scaling, 10, scaling_shift);
    scales.LookUp(index, kCount);
    for (int k = 0; k < kCount; k += 16) _mm256_store_si256(reinterpret_cast<__m256i*>(scale + k), scales.At(k).raw);
}

// The q15 scales of kVectors (2 or 4) vectors of indices (0..1023, sample order) into
// scale[]. Decoded pictures are locally smooth: the indices of a step mostly lie within a
// few of the full table's 16-entry rows (on the 10-bit benchmark stream, within 3 rows for
// 72 % of the 64-sample steps, within 8 for 88 %, within 16 for 95 %, within 32 for 99.7 %).
// Those rows, from the step's lowest on, are looked up by byte shuffles on each index's low
// nibble, and each index keeps the one of its row (a compare and blend per row, 7
// operations a row for 64 samples). Steps spanning more rows (noise-like content) take
// InterpolatedScales' spec form, whose cost does not grow with the span.
// The last row from which three rows of the 10-bit table (64 rows of 16) are whole.
constexpr int kLastThreeRowBase = 1023 / 16 - 2;

template <int kVectors>
HWY_INLINE void Scales10(const Step10Constants& c, const __m256i (&index)[kVectors], __m256i (&scale)[kVectors]) {
    __m256i row[kVectors];
    for (int g = 0; g < kVectors; ++g) row[g] = _mm256_srli_epi16(index[g], 4);
    // rows [base, base + count) of the table, count >= span
    auto by_rows = [&](int base, auto count) FG_INLINE_LAMBDA {
        constexpr int kPairs = kVectors / 2;
        const __m256i base16 = _mm256_set1_epi16(int16_t(base));
        __m256i low[kPairs], rel[kPairs], picked[kPairs];
        const uint8_t* table = c.full_table + 16 * base;
        const __m256i first_row =
            _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(table)));
        for (int p = 0; p < kPairs; ++p) {
            // the pair's low nibbles and rows (relative to the base) as the even and odd
            // bytes of one vector
            low[p] = _mm256_or_si256(_mm256_and_si256(index[2 * p], c.nibble),
                                     _mm256_slli_epi16(_mm256_and_si256(index[2 * p + 1], c.nibble), 8));
            rel[p] = _mm256_or_si256(_mm256_sub_epi16(row[2 * p], base16),
                                     _mm256_slli_epi16(_mm256_sub_epi16(row[2 * p + 1], base16), 8));
            picked[p] = _mm256_shuffle_epi8(first_row, low[p]);
        }
        __m256i j = _mm256_setzero_si256();
        for (int k = 1; k < int(count); ++k) {
            j = _mm256_add_epi8(j, c.one8);
            const __m256i entries =
                _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(table + 16 * k)));
            for (int p = 0; p < kPairs; ++p)
                picked[p] = _mm256_blendv_epi8(picked[p], _mm256_shuffle_epi8(entries, low[p]),
                                               _mm256_cmpeq_epi8(rel[p], j));
        }
        for (int p = 0; p < kPairs; ++p) {
            scale[2 * p] = _mm256_sll_epi16(_mm256_and_si256(picked[p], c.low_byte), c.up_shift);
            scale[2 * p + 1] = _mm256_sll_epi16(_mm256_srli_epi16(picked[p], 8), c.up_shift);
        }
    };
    // The common case, all in the three rows around the first sample's (a cheaper test than
    // the span's), takes a fixed three rows: no loop whose count changes from step to step.
    {
        const int row0 = (_mm256_cvtsi256_si32(index[0]) & 0xFFFF) >> 4;
        const __m256i below = _mm256_set1_epi16(int16_t(row0 - 1));  // wraps below 0
        __m256i top = _mm256_sub_epi16(row[0], below);
        for (int g = 1; g < kVectors; ++g) top = _mm256_max_epu16(top, _mm256_sub_epi16(row[g], below));
        const __m256i beyond = _mm256_subs_epu16(top, c.two);
        if (_mm256_testz_si256(beyond, beyond))
            return by_rows(std::clamp(row0 - 1, 0, kLastThreeRowBase), std::integral_constant<int, 3>());
    }
    __m256i lowest = row[0], highest = row[0];
    for (int g = 1; g < kVectors; ++g) {
        lowest = _mm256_min_epu16(lowest, row[g]);
        highest = _mm256_max_epu16(highest, row[g]);
    }
    // horizontal minimum and maximum (phminposuw; the maximum as the minimum of the complement)
    const __m128i low128 = _mm_min_epu16(_mm256_castsi256_si128(lowest), _mm256_extracti128_si256(lowest, 1));
    const __m128i high128 = _mm_max_epu16(_mm256_castsi256_si128(highest), _mm256_extracti128_si256(highest, 1));
    const int first = _mm_cvtsi128_si32(_mm_minpos_epu16(low128)) & 0xFFFF;
    const __m128i high_complement = _mm_xor_si128(high128, _mm_set1_epi32(-1));
    const int last = 0xFFFF - (_mm_cvtsi128_si32(_mm_minpos_epu16(high_complement)) & 0xFFFF);
    const int span = last - first + 1;
    if (span <= 3) return by_rows(std::min(first, kLastThreeRowBase), std::integral_constant<int, 3>());
    if (span <= 32) return by_rows(first, span);
    HWY_ALIGN uint16_t stored[16 * kVectors];
    HWY_ALIGN int16_t scales[16 * kVectors];
    for (int g = 0; g < kVectors; ++g) _mm256_store_si256(reinterpret_cast<__m256i*>(stored + 16 * g), index[g]);
    LookUpOutOfLine<16 * kVectors>(*c.scaling, c.scaling_shift, stored, scales);
    for (int g = 0; g < kVectors; ++g) scale[g] = _mm256_load_si256(reinterpret_cast<const __m256i*>(scales + 16 * g));
}

// Whether a sample of the OR of a step's samples lies above 10 bits (bad input): the 16-bit
// arithmetic here (pair sums, multiply-adds, the saturating sum) holds the spec's integers
// only below 2^14, so such a step writes nothing and sets `skipped`, for the caller to blend
// it the scalar way (its samples still there, in place too).
HWY_INLINE bool AnyAbove10Bits(__m256i any) { return !_mm256_testz_si256(any, _mm256_set1_epi16(int16_t(0xFC00))); }

// clip(src + Round2(scale * noise, shift)) of 16 samples into dst (samples within 10 bits
// here: steps holding others are left out, AnyAbove10Bits).
HWY_INLINE void StoreBlended10(const Step10Constants& c, uint16_t* dst, __m256i src, __m256i scale, __m256i noise) {
    const __m256i v = _mm256_adds_epi16(src, _mm256_mulhrs_epi16(scale, noise));
    const __m256i clipped = _mm256_min_epi16(_mm256_max_epi16(v, c.min_value), c.max_value);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), clipped);
}

// The noise of samples [x, x + 16 * kVectors) of a row of kBlockWidth-sample blocks (16 or
// 32), in sample order, the first pair of each block overlapped with its left neighbour:
// faded jointly (FadeFirstPairs) for a 64-sample step, else one by one.
template <int kBlockWidth, Overlap kOverlap, int kVectors>
HWY_INLINE void Noise10(const BlockNoiseRow& row, int x, const StepConstants& fade, __m256i (&noise)[kVectors]) {
    constexpr int kPerBlock = kBlockWidth / 16;  // vectors per block
    const int b = x / kBlockWidth;
    for (int g = 0; g < kVectors; ++g) noise[g] = Load256(row.block(b + g / kPerBlock) + 16 * (g % kPerBlock));
    if constexpr (kOverlap == Overlap::kFade && kVectors == 4) {
        const int16_t* left0 = row.block(b > 0 ? b - 1 : 0);
        if constexpr (kPerBlock == 1)
            FadeFirstPairs<4>({&noise[0], &noise[1], &noise[2], &noise[3]},
                              {left0, row.block(b), row.block(b + 1), row.block(b + 2)}, kBlockWidth, x == 0, fade);
        else
            FadeFirstPairs<2>({&noise[0], &noise[2]}, {left0, row.block(b)}, kBlockWidth, x == 0, fade);
    } else {
        for (int g = 0; g < kVectors; g += kPerBlock)
            noise[g] = OverlapFirstPair<kOverlap, kBlockWidth>(noise[g], row, b + g / kPerBlock,
                                                               x + 16 * g, fade);
    }
}

// The rest of a step whose samples v and scaling indices are loaded: its noise, scales and
// blended output.
template <int kBlockWidth, Overlap kOverlap, int kVectors>
HWY_INLINE void BlendStep10(const StepConstants& fade, const Step10Constants& c, const BlockNoiseRow& row, int x,
                            const __m256i (&v)[kVectors], const __m256i (&index)[kVectors], uint16_t* dst) {
    __m256i scale[kVectors], noise[kVectors];
    Noise10<kBlockWidth, kOverlap, kVectors>(row, x, fade, noise);
    Scales10<kVectors>(c, index, scale);
    for (int g = 0; g < kVectors; ++g) StoreBlended10(c, dst + x + 16 * g, v[g], scale[g], noise[g]);
}

// How many vectors a step's array holds.
template <int kVectors>
constexpr int VectorsOf(const __m256i (&)[kVectors]) {
    return kVectors;
}

// The steps of a 10-bit row (ForEachStep, 64 samples then 32): load(x, v, index) loads a
// step's samples and scaling indices, all before the first store (in place), and returns the
// OR of every sample it read; a step holding one above 10 bits is left out and sets `skipped`
// (AnyAbove10Bits), the others go to blend(x, v, index). `ahead`: PrefetchSourceAhead's row.
template <class Load, class Blend, class Rest>
HWY_INLINE void ForEachStep10(int width, const uint16_t* ahead, bool& skipped, Load&& load, Blend&& blend,
                              Rest&& rest) {
    ForEachStep(
        width, width,
        [&](int x, auto samples) FG_INLINE_LAMBDA {
            constexpr int kVectors = decltype(samples)::value / 16;
            PrefetchSourceAhead<16 * kVectors>(ahead ? ahead + x : nullptr);
            __m256i v[kVectors], index[kVectors];
            if (AnyAbove10Bits(load(x, v, index))) {
                skipped = true;
                return;
            }
            blend(x, v, index);
        },
        rest);
}

// One row of blend_luma_row at 10 bits: the samples are their own indices. With kCoSited,
// also co_sited_luma_row of the clean samples into co_sited (CoSitedLumaRowU16's arithmetic:
// pair sums by a multiply-add with ones, halved with rounding by a rounding high multiply by
// 1 << 14). `rest(x)` takes the samples after the last whole 32; `skipped`: a step holding a
// sample above 10 bits was left out, co-sited luma included; `ahead`: PrefetchSourceAhead's
// row.
template <Overlap kOverlap, bool kCoSited, class Rest>
HWY_INLINE void Luma10RowSteps(const StepConstants& fade, const Step10Constants& c, const uint16_t* src,
                               uint16_t* dst, const BlockNoiseRow& row, int width, uint16_t* co_sited,
                               const uint16_t* ahead, bool& skipped, Rest&& rest) {
    ForEachStep10(
        width, ahead, skipped,
        [&](int x, auto& v, auto& index) FG_INLINE_LAMBDA {
            __m256i any = _mm256_setzero_si256();
            for (int g = 0; g < VectorsOf(v); ++g) {
                v[g] = Load256(src + x + 16 * g);
                index[g] = v[g];  // within the table wherever the step is blended (AnyAbove10Bits)
                any = _mm256_or_si256(any, v[g]);
            }
            return any;
        },
        [&](int x, const auto& v, const auto& index) FG_INLINE_LAMBDA {
            if constexpr (kCoSited) {
                // (sums of two samples below 2^15 fit int16)
                const __m256i ones = _mm256_set1_epi16(1), half = _mm256_set1_epi16(1 << 14);
                for (int g = 0; g < VectorsOf(v); g += 2) {
                    const __m256i sums =
                        _mm256_packs_epi32(_mm256_madd_epi16(v[g], ones), _mm256_madd_epi16(v[g + 1], ones));
                    _mm256_storeu_si256(reinterpret_cast<__m256i*>(co_sited + x / 2 + 8 * g),
                                        _mm256_mulhrs_epi16(_mm256_permute4x64_epi64(sums, 0xD8), half));
                }
            }
            BlendStep10<32, kOverlap>(fade, c, row, x, v, index, dst);
        },
        rest);
}

// blend_luma_row at 10 bits for rows.count rows (PlaneRows), each row's co-sited luma where
// co_sited.row(r) gives one; `rest(r, row, x, co_sited_row)` takes a row's samples after the
// last whole 32, `left_out(r, row, vector_end)` as ForEachRow10.
template <Overlap kOverlap, class Rest, class LeftOut>
void Luma10Rows(const uint16_t* src, uint16_t* dst, const PlaneRows& rows, const BlockNoiseRow& first_row,
                int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                const CoSitedRows& co_sited, Rest&& rest, LeftOut&& left_out) {
    const StepConstants fade = MakeStepConstants(scaling, scaling_shift, min_value, max_value, first_row);
    const Step10Constants c = MakeStep10Constants(scaling, scaling_shift, min_value, max_value);
    auto row_steps = [&](int r, const BlockNoiseRow& row, const uint16_t* s, uint16_t* d, const uint16_t* ahead,
                         bool& skipped) FG_INLINE_LAMBDA {
        uint16_t* out = co_sited.row(r);
        int vector_end = width;
        auto row_rest = [&](int x) {
            vector_end = x;
            rest(r, row, x, out);
        };
        if (out)
            Luma10RowSteps<kOverlap, true>(fade, c, s, d, row, width, out, ahead, skipped, row_rest);
        else
            Luma10RowSteps<kOverlap, false>(fade, c, s, d, row, width, nullptr, ahead, skipped, row_rest);
        return vector_end;
    };
    ForEachRow10(src, dst, rows, first_row, row_steps, left_out);
}

// blend_chroma_row at 10 bits with unsubsampled luma (the synthesis hands subsampled chroma
// its shared co-sited luma rows so) for rows.count rows, row r's luma at
// luma + r * rows.luma_stride. The index of chroma_scaling_index is the luma itself
// or (luma * luma_mult + chroma * mult) >> 6 plus the offset, clipped: one multiply-add of
// interleaved (luma, chroma) pairs into 32-bit lanes (it needs 19 bits), whose pack back to
// 16 bits restores the order the in-lane interleave split. `rest(r, row, x)` blends a row's
// samples after the last whole 32; a step whose chroma or luma holds a sample above 10 bits
// is left out, for `left_out` (ForEachRow10).
template <int kBlockWidth, bool kFromLuma, Overlap kOverlap, class Rest, class LeftOut>
void Chroma10Rows(const uint16_t* src, uint16_t* dst, const uint16_t* luma, const PlaneRows& rows,
                  const BlockNoiseRow& first_row, int width, const ChromaScalingIndex& index,
                  const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value, Rest&& rest,
                  LeftOut&& left_out) {
    const StepConstants fade = MakeStepConstants(scaling, scaling_shift, min_value, max_value, first_row);
    const Step10Constants c = MakeStep10Constants(scaling, scaling_shift, min_value, max_value);
    const __m256i mults =
        _mm256_set1_epi32(int32_t(uint32_t(uint16_t(index.luma_mult)) | uint32_t(uint16_t(index.mult)) << 16));
    const __m256i offset = _mm256_set1_epi16(int16_t(index.offset * 4)), zero = _mm256_setzero_si256();
    auto merged = [&](__m256i l, __m256i s) FG_INLINE_LAMBDA {
        const __m256i lo = _mm256_srai_epi32(_mm256_madd_epi16(_mm256_unpacklo_epi16(l, s), mults), 6);
        const __m256i hi = _mm256_srai_epi32(_mm256_madd_epi16(_mm256_unpackhi_epi16(l, s), mults), 6);
        // (10-bit samples keep it within int16: at most (2 * 1023 * 128) >> 6 plus the offset)
        const __m256i m = _mm256_adds_epi16(_mm256_packs_epi32(lo, hi), offset);
        return _mm256_min_epi16(_mm256_max_epi16(m, zero), c.last);
    };
    auto row_steps = [&](int r, const BlockNoiseRow& row, const uint16_t* s, uint16_t* d, const uint16_t* ahead,
                         bool& skipped) FG_INLINE_LAMBDA {
        const uint16_t* l = RowDown(luma, r, rows.luma_stride);
        int vector_end = width;
        ForEachStep10(
            width, ahead, skipped,
            [&](int x, auto& v, auto& idx) FG_INLINE_LAMBDA {
                __m256i any = _mm256_setzero_si256();
                for (int g = 0; g < VectorsOf(v); ++g) {
                    v[g] = Load256(s + x + 16 * g);
                    const __m256i lv = Load256(l + x + 16 * g);
                    any = _mm256_or_si256(any, _mm256_or_si256(v[g], lv));
                    // (luma as the index: within the table wherever the step is blended)
                    idx[g] = kFromLuma ? lv : merged(lv, v[g]);
                }
                return any;
            },
            [&](int x, const auto& v, const auto& idx) FG_INLINE_LAMBDA {
                BlendStep10<kBlockWidth, kOverlap>(fade, c, row, x, v, idx, d);
            },
            [&](int x) {
                vector_end = x;
                rest(r, row, x);
            });
        return vector_end;
    };
    ForEachRow10(src, dst, rows, first_row, row_steps, left_out);
}

}  // namespace avx2

#endif  // HWY_TARGET == HWY_AVX2

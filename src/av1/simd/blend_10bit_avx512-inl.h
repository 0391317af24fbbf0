// 10-bit AV1 noise application (AV1 7.18.3.5) in whole 512-bit vectors, for the AVX3 target of
// av1_kernels_hwy.cpp on CPUs with AVX512-VBMI: twins of blend_luma_row and blend_chroma_row at
// 10 bits, bit-equal to them. Included after blend_u8_avx512-inl.h (whose byte look-up, noise and
// overlap helpers it shares), on the AVX3 pass only.
//
// The scale of a 10-bit sample is scale_lut's own interpolation (7.18.3.5): ScalingLut[x] and
// ScalingLut[x + 1] for x = index >> 2, weighted by the index's low 2 bits. Eight registers
// hold the two 256-entry tables (ScalingLookup::table8 and next8); four two-table byte permutes
// (vpermi2b, 128 entries each) and two masked merges by x's top bit look the two ends of 64
// samples up at once, and one unsigned x signed byte multiply-add of the (start, end) pairs
// by (4 - rem, rem) interpolates them, whatever the picture's content (the generic kernels'
// shuffle chains are fast only where neighbouring samples share table rows). The look-up of
// the 1024-entry full_table() it replaced took eight permutes and seven merges: on Intel cores
// a two-table byte permute is three micro-ops, two of them on the one shuffle port, and the
// interpolation took the per-picture cost to 0.85 of that (Xeon, Emerald Rapids;
// docs/performance-notes.md).
#if HWY_TARGET == HWY_AVX3

namespace avx512 {

// ScalingLut and its successor table ScalingLookup::next8 (ScalingLut[min(x + 1, 255)]): the
// two ends of scale_lut's interpolation, in eight registers.
struct InterpolationLut {
    ByteLut start, end;
};
FG_AVX512_VBMI inline InterpolationLut LoadInterpolationLut(const ScalingLookup& scaling) {
    return {LoadByteLut(scaling.table8().data()), LoadByteLut(scaling.next8())};
}

// The q15 scales of 64 samples in sample order (two vectors of 16-bit lanes) from their
// scaling indices so. start * (4 - rem) + end * rem + 2 >> 2 is the spec's start +
// Round2((end - start) * rem, 2) (4 * start adds whole steps of 4), and its products fit the
// byte multiply-add: start and end are unsigned bytes, the weights 0..4. The pack that makes
// the byte indices interleaves the 128-bit lanes, and unpacking the looked-up pairs undoes it.
FG_AVX512_VBMI inline void Scales10(const InterpolationLut& lut, __m512i index_low, __m512i index_high,
                                    __m128i up_shift, __m512i& scale_low, __m512i& scale_high) {
    // indices beyond 10 bits read the last entry, as ScalingLookup does
    const __m512i last = _mm512_set1_epi16(1023);
    const __m512i i_low = _mm512_min_epu16(index_low, last), i_high = _mm512_min_epu16(index_high, last);
    const __m512i x = _mm512_packus_epi16(_mm512_srli_epi16(i_low, 2), _mm512_srli_epi16(i_high, 2));
    const __m512i start = LookUpBytes(lut.start, x), end = LookUpBytes(lut.end, x);
    const __m512i three = _mm512_set1_epi16(3), four = _mm512_set1_epi16(4);
    const __m512i quarter = _mm512_set1_epi16(1 << 13);  // rounding high multiply: (v + 2) >> 2
    auto interpolated = [&](__m512i pairs, __m512i index) FG_AVX512_VBMI {
        const __m512i rem = _mm512_and_si512(index, three);
        const __m512i weights = _mm512_sub_epi16(_mm512_or_si512(_mm512_slli_epi16(rem, 8), four), rem);
        return _mm512_sll_epi16(_mm512_mulhrs_epi16(_mm512_maddubs_epi16(pairs, weights), quarter), up_shift);
    };
    scale_low = interpolated(_mm512_unpacklo_epi8(start, end), i_low);
    scale_high = interpolated(_mm512_unpackhi_epi8(start, end), i_high);
}

// Whether a sample of the OR of a step's samples lies above 10 bits (bad input): the 16-bit
// arithmetic here holds the spec's integers only below 2^14, so such a step writes nothing and
// sets `skipped`, for the caller to blend it the scalar way (its samples still there, in place
// too). Not a call from the step: the call made the LUT's registers spill around every step.
FG_AVX512_VBMI inline bool AnyAbove10Bits(__m512i any) {
    return _mm512_test_epi16_mask(any, _mm512_set1_epi16(int16_t(0xFC00))) != 0;
}

// 32 samples of the output: src + Round2(scale * noise, shift), the rounding high multiply of
// the q15 scale, clipped to [vmin, vmax].
FG_AVX512_VBMI inline void StoreBlended(uint16_t* dst, __m512i src, __m512i scale, __m512i noise, __m512i vmin,
                                        __m512i vmax) {
    const __m512i v = _mm512_adds_epi16(src, _mm512_mulhrs_epi16(scale, noise));  // as the AVX2 twin
    _mm512_storeu_si512(dst, _mm512_min_epi16(_mm512_max_epi16(v, vmin), vmax));
}

// What every step of a 10-bit form's rows shares, made once for the rows, in registers.
struct Blend10Constants {
    InterpolationLut lut;
    SeamFade fade;
    __m128i up_shift;
    __m512i vmin, vmax;
};
FG_AVX512_VBMI inline Blend10Constants MakeBlend10Constants(const ScalingLookup& scaling, int scaling_shift,
                                                            int min_value, int max_value,
                                                            const BlockNoiseRow& first_row) {
    return {LoadInterpolationLut(scaling), MakeSeamFade(first_row), _mm_cvtsi32_si128(15 - scaling_shift),
            _mm512_set1_epi16(int16_t(min_value)), _mm512_set1_epi16(int16_t(max_value))};
}

// The 64-sample steps of a 10-bit row (ForEach64 over kBlockWidth-wide blocks). load(x, s_low,
// s_high, i_low, i_high) loads a step's samples and their scaling indices, all before the
// step's first store (in place), and returns the OR of every sample it read: a step holding one
// above 10 bits writes nothing and sets `skipped` (AnyAbove10Bits). `rest(x, seams)` as
// ForEach64's. Sample order (samples 0-31, 32-63 of the step in 16-bit lanes): the pack that
// makes the byte indices interleaves the 128-bit lanes, and unpacking the looked-up bytes
// undoes it.
template <int kBlockWidth, Overlap kOverlap, class Load, class Rest>
FG_AVX512_VBMI inline void ForEachStep10(const Blend10Constants& c, const BlockNoiseRow& row, int width,
                                         uint16_t* d, const uint16_t* ahead, bool& skipped, Load&& load,
                                         Rest&& rest) {
    ForEach64<kBlockWidth, kOverlap>(
        row, width, width,
        [&](int x, const int16_t* const* blocks, const uint32_t* seams) FG_AVX512_VBMI {
            PrefetchSourceAhead<64>(ahead ? ahead + x : nullptr);
            __m512i s_low, s_high, i_low, i_high;
            if (AnyAbove10Bits(load(x, s_low, s_high, i_low, i_high))) {
                skipped = true;
                return;
            }
            __m512i noise_low, noise_high;
            OverlappedNoiseOf64<kBlockWidth, kOverlap>(blocks, seams, x == 0, c.fade, noise_low, noise_high);
            __m512i scale_low, scale_high;
            Scales10(c.lut, i_low, i_high, c.up_shift, scale_low, scale_high);
            StoreBlended(d + x, s_low, scale_low, noise_low, c.vmin, c.vmax);
            StoreBlended(d + x + 32, s_high, scale_high, noise_high, c.vmin, c.vmax);
        },
        rest);
}

// Twin of blend_luma_row at 10 bits for rows.count rows (PlaneRows): the samples are their own
// scaling indices. before_row(r, s) first (the co-sited averages of the clean row),
// `rest(r, row, x, seams)` blends samples [x, width) of row r the generic way, `left_out` as
// ForEachRow10.
template <Overlap kOverlap, class BeforeRow, class Rest, class LeftOut>
FG_AVX512_VBMI void Luma10Rows(const uint16_t* src, uint16_t* dst, const PlaneRows& rows,
                               const BlockNoiseRow& first_row, int width, const ScalingLookup& scaling,
                               int scaling_shift, int min_value, int max_value, BeforeRow&& before_row, Rest&& rest,
                               LeftOut&& left_out) {
    const Blend10Constants c = MakeBlend10Constants(scaling, scaling_shift, min_value, max_value, first_row);
    auto row_steps = [&](int r, const BlockNoiseRow& row, const uint16_t* s, uint16_t* d, const uint16_t* ahead,
                         bool& skipped) FG_AVX512_VBMI {
        before_row(r, s);
        int vector_end = width;
        ForEachStep10<32, kOverlap>(
            c, row, width, d, ahead, skipped,
            [&](int x, __m512i& s_low, __m512i& s_high, __m512i& i_low, __m512i& i_high) FG_AVX512_VBMI {
                i_low = s_low = _mm512_loadu_si512(s + x);
                i_high = s_high = _mm512_loadu_si512(s + x + 32);
                return _mm512_or_si512(s_low, s_high);
            },
            [&](int x, const uint32_t* seams) {
                vector_end = x;
                rest(r, row, x, seams);
            });
        return vector_end;
    };
    ForEachRow10(src, dst, rows, first_row, row_steps, left_out);
}

// Twin of blend_chroma_row at 10 bits with unsubsampled luma (the synthesis hands subsampled
// chroma its shared co-sited luma rows so) for rows.count rows, row r's luma at
// luma + r * rows.luma_stride; `rest(r, row, x, seams)` and `left_out` as Luma10Rows. The
// scaling index of chroma_scaling_index: luma * luma_mult + chroma * mult as one multiply-add
// of interleaved (luma, chroma) pairs into 32-bit lanes (it needs 19 bits), >> 6, and the pack
// back to 16 bits restores the sample order the interleave split. A step whose chroma or luma
// holds a sample above 10 bits is left out.
template <int kBlockWidth, bool kFromLuma, Overlap kOverlap, class Rest, class LeftOut>
FG_AVX512_VBMI void Chroma10Rows(const uint16_t* src, uint16_t* dst, const uint16_t* luma, const PlaneRows& rows,
                                 const BlockNoiseRow& first_row, int width, const ChromaScalingIndex& index,
                                 const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value,
                                 Rest&& rest, LeftOut&& left_out) {
    const Blend10Constants c = MakeBlend10Constants(scaling, scaling_shift, min_value, max_value, first_row);
    const __m512i mults =
        _mm512_set1_epi32(int32_t(uint32_t(uint16_t(index.luma_mult)) | uint32_t(uint16_t(index.mult)) << 16));
    const __m512i offset = _mm512_set1_epi16(int16_t(index.offset * 4));
    const __m512i zero = _mm512_setzero_si512(), last = _mm512_set1_epi16(1023);
    auto merged = [&](__m512i l, __m512i s) FG_AVX512_VBMI {
        const __m512i lo = _mm512_srai_epi32(_mm512_madd_epi16(_mm512_unpacklo_epi16(l, s), mults), 6);
        const __m512i hi = _mm512_srai_epi32(_mm512_madd_epi16(_mm512_unpackhi_epi16(l, s), mults), 6);
        const __m512i m = _mm512_adds_epi16(_mm512_packs_epi32(lo, hi), offset);  // as the AVX2 twin
        return _mm512_min_epi16(_mm512_max_epi16(m, zero), last);
    };
    auto row_steps = [&](int r, const BlockNoiseRow& row, const uint16_t* s, uint16_t* d, const uint16_t* ahead,
                         bool& skipped) FG_AVX512_VBMI {
        const uint16_t* l = RowDown(luma, r, rows.luma_stride);
        int vector_end = width;
        ForEachStep10<kBlockWidth, kOverlap>(
            c, row, width, d, ahead, skipped,
            [&](int x, __m512i& s_low, __m512i& s_high, __m512i& i_low, __m512i& i_high) FG_AVX512_VBMI {
                s_low = _mm512_loadu_si512(s + x);
                s_high = _mm512_loadu_si512(s + x + 32);
                i_low = _mm512_loadu_si512(l + x);
                i_high = _mm512_loadu_si512(l + x + 32);
                const __m512i any = _mm512_or_si512(_mm512_ternarylogic_epi64(s_low, s_high, i_low, 0xFE), i_high);
                if constexpr (!kFromLuma) {
                    i_low = merged(i_low, s_low);
                    i_high = merged(i_high, s_high);
                }
                return any;
            },
            [&](int x, const uint32_t* seams) {
                vector_end = x;
                rest(r, row, x, seams);
            });
        return vector_end;
    };
    ForEachRow10(src, dst, rows, first_row, row_steps, left_out);
}

}  // namespace avx512

#endif  // HWY_TARGET == HWY_AVX3

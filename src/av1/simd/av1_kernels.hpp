// Optimized twins of the AV1 noise application stages (Highway, runtime dispatch over the
// targets the CPU supports), each bit-equal to the scalar reference named beside it
// (tests/unit/simd_equivalence_test.cpp checks every target on random input).
// Scaling functions are passed as int32 tables of 1 << bit_depth entries (the values of
// ScalingLookup::operator()) above 8 bits, and as the 256-byte ScalingLookup::table8() at
// 8 bits.
#pragma once
#include <cstdint>

#include "av1/grain_blending.hpp"

namespace filmgrain::av1::simd {

// Twin of blend_luma_row.
void blend_luma_row_u8(const uint8_t* src, uint8_t* dst, const int16_t* noise, int width, const uint8_t* scaling,
                       int scaling_shift, int min_value, int max_value);
void blend_luma_row_u16(const uint16_t* src, uint16_t* dst, const int16_t* noise, int width, const int32_t* scaling,
                        int scaling_shift, int min_value, int max_value);

// Twin of blend_chroma_row.
void blend_chroma_row_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width, const int16_t* noise,
                         int width, int subsampling_x, const ChromaScalingIndex& index, const uint8_t* scaling,
                         int scaling_shift, int bit_depth, int min_value, int max_value);
void blend_chroma_row_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                          const int16_t* noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                          const int32_t* scaling, int scaling_shift, int bit_depth, int min_value, int max_value);

// Twin of the vertical overlap of build_stripe_noise: cur[x] = clamp((old[x] * old_weight +
// cur[x] * new_weight + 16) >> 5, gmin, gmax).
void cross_fade_row(const int16_t* old_row, int16_t* cur, int width, int old_weight, int new_weight, int gmin,
                    int gmax);

}  // namespace filmgrain::av1::simd

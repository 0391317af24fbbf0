// Optimized twins of the AV1 noise application stages (Highway, runtime dispatch over the
// targets the CPU supports), each bit-equal to the scalar reference named beside it
// (tests/unit/simd_equivalence_test.cpp checks every target on random input).
//
// The noise of a picture row is given block by block (BlockNoiseRow), the way 7.18.3.5 lays
// it out, so the blends read it straight from the grain template at each block's random
// offset instead of from a copied noise stripe.
//
// Scaling functions are passed as their ScalingLookup: the spec's 256-byte ScalingLut laid
// out for byte shuffles at every bit depth, and above 8 bits scale_lut over the whole range
// (made once per parameter set). Round2(scale * noise, shift) is one rounding high multiply
// (pmulhrsw) in 16-bit lanes of the scale shifted up to q15 (scale <= 255 and shift >= 8
// keep it below 2^15).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "av1/grain_blending.hpp"

namespace filmgrain::av1::simd {

// One row's noise: column x of the row lies in block b = x / block_width and takes
// blocks[b][x - b * block_width], except for the first two samples of every block but the
// first when the blocks overlap horizontally (overlap_flag): those are faded with columns
// block_width and block_width + 1 of the left block, either given as seams[b] (low 16 bits
// first; seams[0] holds blocks[0][0..1] unchanged) or, when seams is null and fade is set,
// computed on the fly as clamp((left * fade_old[k] + own * fade_new[k] + 16) >> 5) (only up to
// 10 bits, where that sum fits 16-bit lanes).
//
// Block b's row starts at blocks[b] + row_offset: a stripe points `blocks` at its blocks' first
// rows once and moves row_offset down its rows (rather than rewriting every pointer per row).
//
// At 8 bits the grain fits a byte (-128..127): byte_blocks, where set, are the same blocks in
// an int8 copy of the template (byte_blocks[b] + row_offset is block(b) as bytes), for the
// kernels that read noise as bytes (the AVX-512 VBMI and the AVX2 luma rows, which then load
// half the noise bytes and fade the seams in byte pairs). They read 64 bytes from every such
// row's start (its block and the next block's overlap columns): the copy is padded for that.
// Every kernel must give the same output with and without them.
struct BlockNoiseRow {
    const int16_t* const* blocks = nullptr;
    std::ptrdiff_t row_offset = 0;
    const int8_t* const* byte_blocks = nullptr;
    const uint32_t* seams = nullptr;
    int block_width = 32;  // 32 >> subsampling_x
    bool fade = false;
    int16_t fade_old[2] = {0, 0}, fade_new[2] = {32, 32};
    int16_t gmin = -128, gmax = 127;

    const int16_t* block(int b) const { return blocks[b] + row_offset; }
    const int8_t* byte_block(int b) const { return byte_blocks[b] + row_offset; }

    int16_t at(int x) const {
        const int b = x / block_width, k = x - b * block_width;
        if (seams && k < 2) return int16_t(uint16_t(seams[b] >> (16 * k)));
        if (fade && b > 0 && k < 2) {
            const int v = (block(b - 1)[block_width + k] * fade_old[k] + block(b)[k] * fade_new[k] + 16) >> 5;
            return int16_t(v < gmin ? gmin : v > gmax ? gmax : v);
        }
        return block(b)[k];
    }
};

// How many bytes from the start of every byte_blocks row the byte kernels read (a block row and
// the overlap columns 32 and 33 of the same row, as one 32-byte load each); the int8 copy of a
// template ends with that many spare bytes.
inline constexpr int kByteNoiseReadBytes = 64;

// Whether the luma row kernels this CPU dispatches to read BlockNoiseRow::byte_blocks (the
// AVX-512 VBMI and the AVX2 forms): where none does, the synthesis makes no int8 copy.
bool luma_rows_read_byte_noise();

// The int8 copy of 8-bit noise `samples` (each within -128..127) for byte_blocks, with
// kByteNoiseReadBytes spare bytes; `out` reuses its storage.
void copy_noise_as_bytes(const std::vector<int16_t>& samples, std::vector<int8_t>& out);

// Rows [0, count) of a plane for the *_rows kernels: row r reads src + r * src_stride (bytes)
// and the luma co-sited with it at luma + r * luma_stride, writes dst + r * dst_stride, and
// takes the noise row with row_offset + r * noise_step (the next template row).
// The u16 kernels prefetch, for rows r < ahead_count, the source row at ahead + r * src_stride
// (kSourcePrefetchRows further down: the rows whose such row lies in the plane). A hint only:
// the output does not depend on it.
struct PlaneRows {
    int count = 1;
    std::ptrdiff_t src_stride = 0, dst_stride = 0, luma_stride = 0, noise_step = 0;
    const uint16_t* ahead = nullptr;
    int ahead_count = 0;
};

// Where blend_luma_rows_u16 writes co_sited_luma_row_u16 of the clean rows (horizontally
// subsampled chroma above 8 bits, (width + 1) / 2 samples a row): row r is row
// i = first_row + r of the stripe, and every i that is a multiple of 1 << rows_shift (the luma
// rows co-sited with chroma rows) writes out + (i >> rows_shift) * stride (samples). None
// where out is null.
struct CoSitedRows {
    uint16_t* out = nullptr;
    std::ptrdiff_t stride = 0;
    int rows_shift = 0, first_row = 0;

    uint16_t* row(int r) const {
        const int i = first_row + r;
        return out && (i & ((1 << rows_shift) - 1)) == 0 ? out + std::ptrdiff_t(i >> rows_shift) * stride : nullptr;
    }
};

// How far below its row the synthesis points the u16 blends' `ahead`: luma rows, chroma rows
// >> subsampling_y (PrefetchSourceAhead in av1_kernels_hwy.cpp gives the measurements).
inline constexpr int kSourcePrefetchRows = 16;

// Twins of blend_luma_row.
void blend_luma_row_u8(const uint8_t* src, uint8_t* dst, const BlockNoiseRow& noise, int width,
                       const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value);
// With `co_sited` (horizontally subsampled chroma above 8 bits), blend_luma_row_u16 also writes
// co_sited_luma_row_u16 of the clean row, (width + 1) / 2 samples, into it: the luma kernel
// has the samples in registers when it loads them to blend (where dst is src, before it
// overwrites them).
// `ahead` (the u16 forms, may be null): a source row further down the plane, at least `width`
// samples, which the 10-bit AVX2 and AVX-512 kernels prefetch as they go
// (kSourcePrefetchRows). A hint only: the output does not depend on it.
void blend_luma_row_u16(const uint16_t* src, uint16_t* dst, const BlockNoiseRow& noise, int width,
                        const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                        uint16_t* co_sited = nullptr, const uint16_t* ahead = nullptr);

// blend_luma_row_u8 of each of rows.count rows, one call for all (the row loop inside the
// target's kernel, its constants made once).
void blend_luma_rows_u8(const uint8_t* src, uint8_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                        int width, const ScalingLookup& scaling, int scaling_shift, int min_value, int max_value);
// blend_luma_row_u16 of each of rows.count rows, with co_sited's rows made as it says and
// rows.ahead prefetched.
void blend_luma_rows_u16(const uint16_t* src, uint16_t* dst, const PlaneRows& rows, const BlockNoiseRow& noise,
                         int width, const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value,
                         int max_value, const CoSitedRows& co_sited = {});

// Twins of blend_chroma_row.
void blend_chroma_row_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                         const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                         const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value);
void blend_chroma_row_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                          const BlockNoiseRow& noise, int width, int subsampling_x, const ChromaScalingIndex& index,
                          const ScalingLookup& scaling, int scaling_shift, int bit_depth, int min_value, int max_value,
                          const uint16_t* ahead = nullptr);

// blend_chroma_row_u16 of each of rows.count rows, rows.ahead prefetched.
void blend_chroma_rows_u16(const uint16_t* src, uint16_t* dst, const uint16_t* luma, int luma_width,
                           const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                           const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                           int bit_depth, int min_value, int max_value);

// blend_chroma_row_u8 of each of rows.count rows, one call for all.
void blend_chroma_rows_u8(const uint8_t* src, uint8_t* dst, const uint8_t* luma, int luma_width,
                          const PlaneRows& rows, const BlockNoiseRow& noise, int width, int subsampling_x,
                          const ChromaScalingIndex& index, const ScalingLookup& scaling, int scaling_shift,
                          int bit_depth, int min_value, int max_value);

// Twin of co_sited_luma_row above 8 bits (where the synthesis shares it between the chroma
// planes).
void co_sited_luma_row_u16(const uint16_t* luma, int luma_width, int width, uint16_t* out);

// Twin of the vertical overlap of build_stripe_noise: cur[x] = clamp((old[x] * old_weight +
// cur[x] * new_weight + 16) >> 5, gmin, gmax).
void cross_fade_row(const int16_t* old_row, int16_t* cur, int width, int old_weight, int new_weight, int gmin,
                    int gmax);

// out[x] = noise.at(x) for x < width.
void assemble_noise_row(const BlockNoiseRow& noise, int width, int16_t* out);

// assemble_noise_row of both rows, then cross_fade_row (weights and range from new_noise)
// into out, for bit depths up to 10 with the horizontal overlap faded in the kernel (fade
// set, no seams) or absent.
void assemble_cross_faded_row(const BlockNoiseRow& old_noise, const BlockNoiseRow& new_noise, int width,
                              int old_weight, int new_weight, int16_t* out);

}  // namespace filmgrain::av1::simd

// Optimized twins of the FGC per-stripe stages (Highway, runtime dispatch over the targets
// the CPU supports). Each is bit-equal to the scalar stages named beside it; the
// equivalence tests (tests/unit/simd_equivalence_test.cpp, fgc_simd_equivalence_test.cpp)
// check that on random input for every target. The optimized stripe holds grain as int16,
// which is exact: a grain value is at most (255 << (bd - 8)) * 127 >> (log2_scale_factor +
// 6) <= 32385 in magnitude (log2_scale_factor >= 2 whenever grain is synthesized), or as
// int8 when every value of a component's scaled tables fits (always at 8 bits: <= 126).
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/cache_line.hpp"

namespace filmgrain::fgc::simd {

// The same row of the next stripe in the picture read (`src`) and in the one written
// (`dst`), either null: the blend kernels prefetch the first for reading and the second for
// writing as they go. Neither changes an output. Why the second: in a decoder, the output
// picture written one frame ago has left the caches by the next frame, and every store
// waits for its line to come back for ownership; in `filmgrain decode` of a 1080p 8-bit
// HEVC stream the 8-bit kernels (8x8 deblock and blend, block tables) took 0.43-0.47 ms per
// frame with the source prefetch alone and 0.29 with both (perf samples, 4 runs each, on the
// AVX-512 machine). On a Zen 3 (AVX2), timed frame by frame alternating with each variant,
// only the source's prefetch paid (no prefetch 1.07-1.27 ms, source alone as much as both,
// 0.85-0.97); the output's is kept since it costs nothing there (docs/performance-notes.md).
template <typename Pixel>
struct NextStripeRow {
    const Pixel* src = nullptr;
    Pixel* dst = nullptr;
    // the row `rows` below, in pictures of these strides (null stays null)
    NextStripeRow below(std::ptrdiff_t rows, std::ptrdiff_t src_stride, std::ptrdiff_t dst_stride) const {
        return {src ? src + rows * src_stride : nullptr, dst ? dst + rows * dst_stride : nullptr};
    }
};

// One block of the stripe: `rows` template rows starting at `tmpl` (row pitch 64), scaled
// by `scale` (sign included) and shifted right, written to `cols` columns at `dst`.
// Twin of the inner copy loop of the reference stripe in fgc_picture_synthesis.cpp.
struct BlockCopy {
    const int8_t* tmpl;
    int16_t* dst;
    int32_t scale;
    int cols;
};
void scale_template_blocks(const BlockCopy* blocks, int count, int rows, int shift, std::ptrdiff_t dst_stride);

// Twin of deblock_stripe_vertical_edges followed by blend_row_additive, for one row:
// `grain` is the undeblocked row and is only read (it needs one readable value past
// `width`, as the reference stripe's padding provides). For u8 the grain must satisfy
// |g| <= 8191 (8-bit grain is at most 126); for u16 |g| <= 32385 >> (16 - bit_depth), the
// bound above. `ahead` (either part may be null) holds rows of at least `width` samples the kernel
// prefetches as it goes: the synthesis passes the same row of the next stripe. It changes
// no output.
void deblock_blend_row_u8(const uint8_t* src, uint8_t* dst, const int16_t* grain, int width, int block_size,
                          NextStripeRow<uint8_t> ahead = {});
void deblock_blend_row_u16(const uint16_t* src, uint16_t* dst, const int16_t* grain, int width, int block_size,
                           int bit_depth, NextStripeRow<uint16_t> ahead = {});

// The same from int8 grain, as the narrow scaled tables hold it (|g| <= 128). The u8 kernel
// also reads grain[-1] (any value: column 0 is never filtered); both read grain[width].
void deblock_blend_row_u8_i8(const uint8_t* src, uint8_t* dst, const int8_t* grain, int width, int block_size,
                             NextStripeRow<uint8_t> ahead = {});
void deblock_blend_row_u16_i8(const uint16_t* src, uint16_t* dst, const int8_t* grain, int width, int block_size,
                              int bit_depth, NextStripeRow<uint16_t> ahead = {});

// gather_block_bands_i8, the zeros from `grain_end` on and deblock_blend_row_u8_i8 for
// `rows` rows, without the rows of grain in memory: grain column x of row r is
// blocks[x / block][offset + r * pitch + x % block] for x < grain_end and 0 from there.
// Reads the blocks that hold columns below min(grain_end, width + 1) (those the reference's
// deblocking can read). src, dst and `ahead` (as in deblock_blend_row_u8_i8; may be null)
// step by their strides from row to row. `row` is scratch of deblock_blend_block_rows_scratch
// bytes (any alignment), in which targets without a whole-row form gather the rows: each
// row starts on a 64-byte boundary of it and spans max(block * ceil(min(grain_end, width +
// 1) / block), width + 2) bytes rounded up to 64, so that the gather's stores never split a
// cache line (a band starting one byte in split every other 32-byte store: on a Zen 3 the
// gather was 30 % of the 1080p 8-bit frame).
constexpr std::size_t kBlockRowsBandAlign = kCacheLineBytes;
constexpr std::size_t deblock_blend_block_rows_band_stride(int width, int grain_end, int block) {
    const int end = grain_end < width + 1 ? grain_end : width + 1;
    const int gathered = (end + block - 1) / block * block;
    const std::size_t used = std::size_t(gathered > width + 2 ? gathered : width + 2);
    return (used + kBlockRowsBandAlign - 1) / kBlockRowsBandAlign * kBlockRowsBandAlign;
}
constexpr std::size_t deblock_blend_block_rows_scratch(int rows, int width, int grain_end, int block) {
    // the slack puts row 0 on a boundary with at least one readable byte before it
    return kBlockRowsBandAlign + std::size_t(rows) * deblock_blend_block_rows_band_stride(width, grain_end, block);
}
void deblock_blend_block_rows_u8_i8(const uint8_t* src, std::ptrdiff_t src_stride, uint8_t* dst,
                                    std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                    std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int8_t* row,
                                    NextStripeRow<uint8_t> ahead = {});

// The same for 16-bit samples with deblock_blend_row_u16_i8's arithmetic; the strides are in
// samples, and `row` is the same scratch (of int8 grain).
void deblock_blend_block_rows_u16_i8(const uint16_t* src, std::ptrdiff_t src_stride, uint16_t* dst,
                                     std::ptrdiff_t dst_stride, const int8_t* const* blocks, std::ptrdiff_t offset,
                                     std::ptrdiff_t pitch, int rows, int width, int grain_end, int block, int bit_depth,
                                     int8_t* row, NextStripeRow<uint16_t> ahead = {});

// Rows of one block row of the stripe: for each of `count` blocks, `rows` rows of `block`
// values (8, 16 or 32) that lie `pitch` apart from blocks[j] + offset, copied to
// out + j * block, rows `out_stride` apart. Twin of the element-wise copy.
void gather_block_bands_i8(const int8_t* const* blocks, std::ptrdiff_t offset, int count, int block, int rows,
                           std::ptrdiff_t pitch, int8_t* out, std::ptrdiff_t out_stride);

// Sums of `rows` x `block` sample blocks for the `width / block` whole blocks that start
// at x = 0, block, 2*block, ... (block 8, 16 or 32; rows 1..32): the integer sums the local
// adaptation (block_average_inside / block_average_replicated) divides or shifts.
void block_sums_u8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums);
// The int8 grain of the `width / block` whole blocks from x = 0 (block_sums_u8's blocks):
// blocks[j] = base + offsets[min(sum_j >> shift, 255)] + places[j], sum_j the block's
// sample sum. Twin of block_sums_u8 followed by the optimized stripe's look-up of each
// block's interval table (offsets: per average, the interval's table; places: per block,
// its position and sign in a table). Every offsets[a] + places[j] must fit int32.
void block_tables_u8(const uint8_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                     const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** blocks);
void block_sums_u16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, uint32_t* sums);
// block_tables_u8 for 16-bit samples (block_sums_u16's sums; `stride` in bytes).
void block_tables_u16(const uint16_t* src, std::ptrdiff_t stride, int rows, int width, int block, int shift,
                      const int32_t* offsets, const int32_t* places, const int8_t* base, const int8_t** blocks);

}  // namespace filmgrain::fgc::simd

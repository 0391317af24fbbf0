// The optimized stripe of FgcPictureSynthesis, the twin of reference_stripe.cpp for model 0,
// additive blending and square blocks (see fgc_picture_synthesis.hpp).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/cache_line.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/local_adaptation.hpp"

namespace filmgrain::fgc {

// Optimized twin of reference_stripe, for one block size. The block sums (a vector kernel)
// give each block its interval; a block's grain is then a pointer into that interval's
// scaled template (ScaledTemplates: the reference's per-sample products, made once per
// parameter set), or into stripe scratch scaled block by block when the component has too
// many intervals for tables. Eight rows at a time, the fused deblocking + blending kernel
// adds the blocks' rows to the picture: the grain of a whole stripe is never written out.
// With int8 tables (8-bit grain always fits) the kernel loads each row's grain from the
// blocks' pointers itself (on targets without such a form it gathers them into scratch);
// int16 grain is copied into a band of grain rows first. With int8 tables the whole blocks
// also get their tables from a kernel that sums them. Blocks that touch the
// picture's right or bottom edge take their averages from the reference functions.
// Blocks without grain point here: zeros for any block row at either pitch.
template <typename Table>
alignas(kCacheLineBytes) constexpr Table kZeroGrain[kTemplateSize * 32] = {};

template <typename Pixel, int kBlock, typename Table>
void FgcPictureSynthesis::optimized_stripe(const ResolvedFgc& params, int c, const PlaneView& src,
                                         const PlaneView& dst, int bit_depth, int by, bool prefetch_next,
                                         Scratch& scratch) const {
    constexpr int kRandBlock = kBlock == 32 ? 32 : 16;
    constexpr int kSub = kRandBlock / kBlock;  // adaptation blocks per randomization block, each direction
    constexpr int kLog2Area = kBlock == 8 ? 6 : kBlock == 16 ? 8 : 10;
    const ResolvedComponent& comp = params.comp[c];
    const int w = src.width, h = src.height;
    const int blocks_x = (w + kRandBlock - 1) / kRandBlock;
    const int columns = blocks_x * kSub;  // block columns of the stripe, including those past the edge
    const int grain_width = blocks_x * kRandBlock;
    const int whole_blocks = w / kBlock;
    const bool rdd5 = flavour_ != FgcFlavour::kVtm;
    const bool tables = have_scaled_[c];
    const uint32_t* states = states_[c].data() + std::size_t(by) * std::size_t(blocks_x);
    const int y_top = by * kRandBlock;

    // Each block column's position in the template and its sign (those of its randomization
    // block), as an offset into an interval's pair of scaled tables (the negative table
    // follows the positive one).
    int32_t* places = scratch.places.data();
    for (int b = 0; b < blocks_x; b++) {
        const BlockOffset off = block_offset_from_state(states[b], kBlock);
        const int32_t origin = off.y * kTemplateSize + off.x + int32_t(states[b] & 1u) * kTemplateSize * kTemplateSize;
        for (int sub = 0; sub < kSub; sub++) places[b * kSub + sub] = origin + sub * kBlock;
    }
    const Table* const kNoGrain = kZeroGrain<Table>;
    const Table* table0 = tables ? scaled_[c].template table<Table>(0, 0) : nullptr;
    constexpr std::ptrdiff_t kIntervalPitch = 2 * kTemplateSize * kTemplateSize;
    const Table** blocks;
    if constexpr (sizeof(Table) == 1)
        blocks = scratch.narrow_blocks.data();
    else
        blocks = scratch.blocks.data();
    int copies = 0;
    for (int yi = 0; yi < kSub; yi++) {
        const int y0 = y_top + yi * kBlock;
        const int rows_inside = std::min(kBlock, h - y0);
        const Table** block_row = blocks + yi * columns;
        if (rows_inside <= 0) {  // below the picture: these rows are never blended
            std::fill(block_row, block_row + columns, kNoGrain);
            continue;
        }
        uint32_t* sums = scratch.sums.data() + yi * columns;
        // int8 tables: whole blocks get their tables from block_tables_u8 / _u16, which sum
        // them themselves (the other blocks do not read sums when the rows are whole)
        constexpr bool kInt8Tables = sizeof(Table) == 1;
        const bool table_kernel = kInt8Tables && tables && rows_inside == kBlock;
        auto sum_blocks = [&](int y, int n, uint32_t* out) {
            if constexpr (sizeof(Pixel) == 1)
                simd::block_sums_u8(src.row<const Pixel>(y), src.stride, n, w, kBlock, out);
            else
                simd::block_sums_u16(src.row<const Pixel>(y), src.stride, n, w, kBlock, out);
        };
        if (!table_kernel) sum_blocks(y0, rows_inside, sums);
        // vtm's blocks that cross the bottom edge average the edge-replicated picture
        // (block_average_replicated): the rows inside, and the last row once for each row below
        const uint32_t* last_row = nullptr;
        if (!rdd5 && rows_inside < kBlock) {
            sum_blocks(h - 1, 1, scratch.last_row_sums.data());
            last_row = scratch.last_row_sums.data();
        }
        const int row_offset = yi * kBlock * kTemplateSize;
        int j = 0;
        if (tables && rows_inside == kBlock) {
            // Whole blocks, the bulk of the picture: both flavours shift the sum by
            // log2(area) + bd - 8 (rdd5 divides by the area, exactly a shift here).
            // The average is at most 255 at any bit depth (for samples within it; larger
            // ones, bad input, are held to the last entry); blocks in no interval read the
            // zero table (table_offsets_).
            const int avg_shift = kLog2Area + bit_depth - 8;
            const int32_t* offsets = table_offsets_[c].data();
            const Table* base = table0 + row_offset;
            if constexpr (kInt8Tables) {
                if constexpr (sizeof(Pixel) == 1)
                    simd::block_tables_u8(src.row<const Pixel>(y0), src.stride, kBlock, w, kBlock, avg_shift, offsets,
                                          places, base, block_row);
                else
                    simd::block_tables_u16(src.row<const Pixel>(y0), src.stride, kBlock, w, kBlock, avg_shift, offsets,
                                           places, base, block_row);
                j = whole_blocks;
            } else {
                for (; j < whole_blocks; j++)
                    block_row[j] = base + offsets[std::min<uint32_t>(sums[j] >> avg_shift, 255)] + places[j];
            }
        }
        for (; j < columns; j++) {
            const int x0 = j * kBlock;
            int avg;
            if (rdd5) {
                if (x0 >= w) {  // HM-2020 writes grain only inside the picture
                    block_row[j] = kNoGrain;
                    continue;
                }
                if (j < whole_blocks) {
                    // a whole block divides by 2^kLog2Area: the same as a shift for unsigned sums
                    const uint32_t mean =
                        rows_inside == kBlock ? sums[j] >> kLog2Area : sums[j] / uint32_t(kBlock * rows_inside);
                    avg = int(std::min<uint32_t>(mean >> (bit_depth - 8), 255));
                } else {
                    avg = block_average_inside<Pixel>(src, x0, y0, kBlock, bit_depth);
                }
            } else if (j < whole_blocks) {
                const uint32_t sum = last_row ? sums[j] + uint32_t(kBlock - rows_inside) * last_row[j] : sums[j];
                avg = int(std::min<uint32_t>(sum >> (kLog2Area + bit_depth - 8), 255));
            } else {
                avg = block_average_replicated<Pixel>(src, x0, y0, kBlock, bit_depth);
            }
            const int iv = comp.interval_of_intensity[std::size_t(avg)];
            if (iv < 0) {  // no interval: this block gets no grain
                block_row[j] = kNoGrain;
                continue;
            }
            if (tables) {
                block_row[j] = table0 + iv * kIntervalPitch + places[j] + row_offset;
            } else if constexpr (sizeof(Table) == 2) {  // narrow tables exist only with tables
                const BlockOffset off = block_offset_from_state(states[j / kSub], kBlock);
                const int offset = (off.y + yi * kBlock) * kTemplateSize + off.x + (j % kSub) * kBlock;
                const ResolvedInterval& ri = comp.intervals[std::size_t(iv)];
                int16_t* out = scratch.scaled.data() + std::size_t(copies) * kBlock * kBlock;
                scratch.copies[std::size_t(copies++)] = {cache_.get(ri.cutoff_h, ri.cutoff_v)[0].data() + offset, out,
                                                         off.sign * ri.scale, kBlock};
                block_row[j] = out;
            }
        }
    }
    if (!tables)
        simd::scale_template_blocks(scratch.copies.data(), copies, kBlock, params.log2_scale_factor + 6, kBlock);
    const std::ptrdiff_t pitch = tables ? kTemplateSize : kBlock;

    // rdd5 has no grain at or past the right edge; both have two zero columns of padding,
    // which the deblocking of the last edge reads
    const int zero_from = rdd5 ? w : grain_width;
    // The grain of up to kBandRows rows of one block row at a time (for int8 grain, the
    // kernels' scratch), each row after one readable element, which the u8 kernel loads
    // (column 0 is never filtered): a block's pointer is read once for all those rows, and
    // the band stays small enough to be read back from the first-level cache.
    const std::ptrdiff_t band_stride = grain_width + 3;
    Table* band;
    if constexpr (sizeof(Table) == 1)
        band = scratch.narrow_band.data() + 1;
    else
        band = scratch.band.data() + 1;
    const int rows = std::min(kRandBlock, h - y_top);
    for (int l0 = 0; l0 < rows; l0 += kBandRows) {
        const Table* const* block_row = blocks + (l0 / kBlock) * columns;
        const std::ptrdiff_t r0 = std::ptrdiff_t(l0 % kBlock) * pitch;
        const int band_rows = std::min(kBandRows, rows - l0);
        if constexpr (sizeof(Table) == 1) {
            // int8 grain is deblocked and blended straight from the blocks' table rows
            const int y = y_top + l0;
            using Ahead = simd::NextStripeRow<Pixel>;
            const Ahead ahead = prefetch_next && y + band_rows - 1 + kRandBlock < h
                                    ? Ahead{src.row<const Pixel>(y + kRandBlock), dst.row<Pixel>(y + kRandBlock)}
                                    : Ahead{};
            if constexpr (sizeof(Pixel) == 1)
                simd::deblock_blend_block_rows_u8_i8(src.row<const Pixel>(y), src.stride, dst.row<Pixel>(y),
                                                     dst.stride, block_row, r0, pitch, band_rows, w, zero_from, kBlock,
                                                     band - 1, ahead);
            else  // strides in samples
                simd::deblock_blend_block_rows_u16_i8(
                    src.row<const Pixel>(y), src.stride / std::ptrdiff_t(sizeof(Pixel)), dst.row<Pixel>(y),
                    dst.stride / std::ptrdiff_t(sizeof(Pixel)), block_row, r0, pitch, band_rows, w, zero_from, kBlock,
                    bit_depth, band - 1, ahead);
        } else {
            // int16 grain (wide tables, or blocks scaled into scratch) goes through a band
            auto gather = [&](int n) {
                for (int j = 0; j < columns; j++) {
                    const Table* b = block_row[j] + r0;
                    Table* out = band + j * kBlock;
                    for (int l = 0; l < n; l++)
                        std::memcpy(out + l * band_stride, b + l * pitch, sizeof(Table) * kBlock);
                }
            };
            if (band_rows == kBandRows)
                gather(kBandRows);  // a constant count: the row loop unrolls
            else
                gather(band_rows);
            for (int l = 0; l < band_rows; l++) {
                Table* g = band + l * band_stride;
                std::fill(g + zero_from, g + grain_width + 2, Table(0));
                const int y = y_top + l0 + l;
                // the same row of the next stripe, whose block sums come next (prefetched as this
                // row is blended)
                using Ahead = simd::NextStripeRow<Pixel>;
                const Ahead ahead = prefetch_next && y + kRandBlock < h
                                        ? Ahead{src.row<const Pixel>(y + kRandBlock), dst.row<Pixel>(y + kRandBlock)}
                                        : Ahead{};
                if constexpr (sizeof(Pixel) == 1)
                    simd::deblock_blend_row_u8(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, ahead);
                else
                    simd::deblock_blend_row_u16(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, bit_depth,
                                                ahead);
            }
        }
    }
}

template <typename Pixel>
void FgcPictureSynthesis::optimized_stripe_of(const ResolvedFgc& params, int c, const PlaneView& src,
                                            const PlaneView& dst, int bit_depth, int by, bool prefetch_next,
                                            Scratch& scratch) const {
    const bool narrow = have_scaled_[c] && scaled_[c].narrow();
    auto run = [&](auto block) {
        constexpr int kBlock = decltype(block)::value;
        if (narrow)
            optimized_stripe<Pixel, kBlock, int8_t>(params, c, src, dst, bit_depth, by, prefetch_next, scratch);
        else
            optimized_stripe<Pixel, kBlock, int16_t>(params, c, src, dst, bit_depth, by, prefetch_next, scratch);
    };
    if (block_size_ == 8)
        run(std::integral_constant<int, 8>{});
    else if (block_size_ == 16)
        run(std::integral_constant<int, 16>{});
    else
        run(std::integral_constant<int, 32>{});
}

template void FgcPictureSynthesis::optimized_stripe_of<uint8_t>(const ResolvedFgc&, int, const PlaneView&,
                                                              const PlaneView&, int, int, bool, Scratch&) const;
template void FgcPictureSynthesis::optimized_stripe_of<uint16_t>(const ResolvedFgc&, int, const PlaneView&,
                                                               const PlaneView&, int, int, bool, Scratch&) const;

}  // namespace filmgrain::fgc

#include "fgc/fgc_synthesis.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>

#include "fgc/blending.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/local_adaptation.hpp"
#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::fgc {

int default_block_size(FgcFlavour flavour, int luma_width, int luma_height) {
    if (flavour != FgcFlavour::kVtm) return 8;
    const long long area = (long long)luma_width * luma_height;
    if (area <= 1920LL * 1080) return 8;
    if (area <= 3840LL * 2160) return 16;
    return 32;
}

FgcFrameSynthesis::FgcFrameSynthesis(FgcFlavour flavour, int block_size, int threads, Kernels kernels)
    : flavour_(flavour),
      block_size_(block_size),
      // ffmpeg: the scalar stages only. Its deblocking depends on which blocks got grain,
      // which the fused deblocking + blending kernels do not know.
      kernels_(flavour == FgcFlavour::kFfmpeg ? Kernels::kReference : kernels),
      cache_(flavour == FgcFlavour::kVtm ? TemplateTransform::kVvcDct2 : TemplateTransform::kRdd5Matrix, block_size) {
    if (block_size != 8 && block_size != 16 && block_size != 32)
        throw Error(ErrorCode::kInvalidArgument, "block size " + std::to_string(block_size) + " is not 8, 16 or 32");
    pool_ = std::make_unique<ThreadPool>(threads);
    scratch_.resize(std::size_t(pool_->size()));
}

FgcFrameSynthesis::~FgcFrameSynthesis() = default;

int FgcFrameSynthesis::threads() const { return pool_->size(); }

std::size_t FgcFrameSynthesis::scratch_bytes() const {
    std::size_t n = 0;
    for (const auto& st : states_) n += st.capacity() * sizeof(uint32_t);
    for (const auto& s : scratch_)
        n += s.stripe.capacity() * sizeof(int32_t) + s.has_grain.capacity() + s.sums.capacity() * sizeof(uint32_t) +
             s.blocks.capacity() * sizeof(const int16_t*) + s.narrow_blocks.capacity() * sizeof(const int8_t*) + s.places.capacity() * sizeof(int32_t) +
             s.band.capacity() * sizeof(int16_t) + s.narrow_band.capacity() +
             s.scaled.capacity() * sizeof(int16_t) + s.copies.capacity() * sizeof(simd::BlockCopy);
    return n;
}

std::size_t FgcFrameSynthesis::scaled_template_bytes() const {
    std::size_t n = 0;
    for (const auto& t : scaled_) n += t.bytes();
    return n;
}

void FgcFrameSynthesis::prepare(const ResolvedFgc& params) {
    for (auto [h, v] : params.cutoff_pairs) cache_.ensure(h, v);
}

void copy_plane(const PlaneView& src, const PlaneView& dst, int bytes_per_sample) {
    if (src.data == dst.data && src.stride == dst.stride) return;
    const std::size_t row_bytes = std::size_t(src.width) * bytes_per_sample;
    for (int y = 0; y < src.height; y++) std::memmove(dst.data + dst.stride * y, src.data + src.stride * y, row_bytes);
}


// Scalar reference: one randomization-block row (stripe) built block by block with the
// reference stages.
template <typename Pixel>
void FgcFrameSynthesis::reference_stripe(const ResolvedFgc& params, int c, const PlaneView& src, const PlaneView& dst,
                                         int bit_depth, int by, Scratch& scratch) const {
    const ResolvedComponent& comp = params.comp[c];
    const int bs = block_size_;
    const int rb = bs == 32 ? 32 : 16;  // randomization block: one LFSR step each
    const int w = src.width, h = src.height;
    const int blocks_x = (w + rb - 1) / rb;
    const bool rdd5 = flavour_ != FgcFlavour::kVtm;
    const int shift = params.log2_scale_factor + 6;
    const uint32_t* states = states_[c].data();

    // +2 columns: the deblocking filter reads one sample past the last edge.
    const int stride = blocks_x * rb + 2;
    std::vector<int32_t>& stripe = scratch.stripe;
    if (stripe.size() < std::size_t(stride) * rb) stripe.resize(std::size_t(stride) * rb);
    std::fill(stripe.begin(), stripe.begin() + std::ptrdiff_t(stride) * rb, 0);
    // ffmpeg: which 8x8 blocks of the stripe got grain, per block row (deblocking depends on it)
    const bool ffmpeg = flavour_ == FgcFlavour::kFfmpeg;
    const int block_columns = blocks_x * (rb / bs);
    std::vector<uint8_t>& has_grain = scratch.has_grain;
    if (ffmpeg) std::fill(has_grain.begin(), has_grain.begin() + std::ptrdiff_t(block_columns) * 2, uint8_t(0));
    for (int bx = 0; bx < blocks_x; bx++) {
        const BlockOffset off = block_offset_from_state(states[std::size_t(by) * blocks_x + bx], bs);
        const int sub_count = bs == 8 ? 4 : 1;
        for (int sub = 0; sub < sub_count; sub++) {
            const int xo = bs == 8 ? (sub & 1) * 8 : 0, yo = bs == 8 ? (sub >> 1) * 8 : 0;
            const int x0 = bx * rb + xo, y0 = by * rb + yo;
            int avg;
            int cols = bs;
            if (rdd5) {
                if (x0 >= w || y0 >= h) continue;
                avg = ffmpeg ? block_average_zero_outside<Pixel>(src, x0, y0, bs, bit_depth)
                             : block_average_inside<Pixel>(src, x0, y0, bs, bit_depth);
                cols = std::min(bs, w - x0);  // HM-2020 writes grain only inside the picture
            } else {
                avg = block_average_replicated<Pixel>(src, x0, y0, bs, bit_depth);
            }
            const int iv = comp.interval_of_intensity[avg];
            if (iv < 0) continue;  // no interval: this block gets no grain
            if (ffmpeg) has_grain[std::size_t(yo / bs) * block_columns + x0 / bs] = 1;
            const ResolvedInterval& ri = comp.intervals[iv];
            const GrainTemplate& t = cache_.get(ri.cutoff_h, ri.cutoff_v);
            const int32_t scale = off.sign * ri.scale;
            for (int l = 0; l < bs; l++) {
                const int8_t* trow = t[off.y + yo + l].data() + off.x + xo;
                int32_t* g = stripe.data() + std::size_t(yo + l) * stride + x0;
                for (int k = 0; k < cols; k++) g[k] = (scale * trow[k]) >> shift;
            }
        }
    }
    const int rows = std::min(rb, h - by * rb);
    for (int yo = 0; yo < rows; yo += bs)
        deblock_stripe_vertical_edges(stripe.data() + std::size_t(yo) * stride, stride, std::min(bs, rows - yo), w, bs,
                                      ffmpeg ? has_grain.data() + std::size_t(yo / bs) * block_columns : nullptr);
    for (int l = 0; l < rows; l++) {
        const int y = by * rb + l;
        blend_row_additive<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), stripe.data() + std::size_t(l) * stride,
                                  w, bit_depth);
    }
}

// Optimized twin of reference_stripe, for one block size. The block sums (a vector kernel)
// give each block its interval; a block's grain is then a pointer into that interval's
// scaled template (ScaledTemplates: the reference's per-sample products, made once per
// parameter set), or into stripe scratch scaled block by block when the component has too
// many intervals for tables. Eight rows at a time, the blocks' rows are copied into a band
// of grain rows (int8 when the tables are: 8-bit grain always fits), which the fused
// deblocking + blending kernel adds to the picture row by row: the grain of a whole stripe
// is never written out. Blocks that touch the picture's right or bottom edge take their
// averages from the reference functions.
// Blocks without grain point here: zeros for any block row at either pitch.
template <typename Table>
alignas(64) constexpr Table kZeroGrain[kTemplateSize * 32] = {};

template <typename Pixel, int kBlock, typename Table>
void FgcFrameSynthesis::optimized_stripe(const ResolvedFgc& params, int c, const PlaneView& src,
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
        if (rdd5 || rows_inside == kBlock) {
            if constexpr (sizeof(Pixel) == 1)
                simd::block_sums_u8(src.row<const Pixel>(y0), src.stride, rows_inside, w, kBlock, sums);
            else
                simd::block_sums_u16(src.row<const Pixel>(y0), src.stride, rows_inside, w, kBlock, sums);
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
            for (; j < whole_blocks; j++)
                block_row[j] = base + offsets[std::min<uint32_t>(sums[j] >> avg_shift, 255)] + places[j];
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
            } else if (j < whole_blocks && rows_inside == kBlock) {
                avg = int(std::min<uint32_t>(sums[j] >> (kLog2Area + bit_depth - 8), 255));
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
    // The grain of up to kBandRows rows of one block row at a time, each row after one
    // readable element, which the u8 kernel loads (column 0 is never filtered): a block's
    // pointer is read once for all those rows, and the band stays small enough to be read
    // back from the first-level cache.
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
        auto gather = [&](int n) {
            for (int j = 0; j < columns; j++) {
                const Table* b = block_row[j] + r0;
                Table* out = band + j * kBlock;
                for (int l = 0; l < n; l++)
                    std::memcpy(out + l * band_stride, b + l * pitch, sizeof(Table) * kBlock);
            }
        };
        if constexpr (sizeof(Table) == 1)
            simd::gather_block_bands_i8(block_row, r0, columns, kBlock, band_rows, pitch, band, band_stride);
        else if (band_rows == kBandRows)
            gather(kBandRows);  // a constant count: the row loop unrolls
        else
            gather(band_rows);
        for (int l = 0; l < band_rows; l++) {
            Table* g = band + l * band_stride;
            std::fill(g + zero_from, g + grain_width + 2, Table(0));
            const int y = y_top + l0 + l;
            // the same row of the next stripe, whose block sums come next (prefetched as this
            // row is blended)
            const Pixel* ahead = prefetch_next && y + kRandBlock < h ? src.row<const Pixel>(y + kRandBlock) : nullptr;
            if constexpr (sizeof(Pixel) == 1 && sizeof(Table) == 1)
                simd::deblock_blend_row_u8_i8(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, ahead);
            else if constexpr (sizeof(Pixel) == 1)
                simd::deblock_blend_row_u8(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, ahead);
            else if constexpr (sizeof(Table) == 1)
                simd::deblock_blend_row_u16_i8(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, bit_depth,
                                               ahead);
            else
                simd::deblock_blend_row_u16(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, kBlock, bit_depth, ahead);
        }
    }
}

template <typename Pixel>
void FgcFrameSynthesis::optimized_stripe_of(const ResolvedFgc& params, int c, const PlaneView& src,
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

void FgcFrameSynthesis::apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst,
                              int32_t pic_offset) {
    prepare(params);
    const int bps = src.bytes_per_sample();
    const int rb = block_size_ == 32 ? 32 : 16;
    // Sequential part: the LFSR walk of each component (cheap). Then every stripe of every
    // component is an independent task.
    int first_task[4] = {0, 0, 0, 0};
    for (int c = 0; c < 3; c++) {
        int stripes = 0;
        if (c < src.plane_count()) {
            const PlaneView& p = src.planes[c];
            if (params.cancelled || !params.comp[c].present) {
                copy_plane(p, dst.planes[c], bps);
            } else {
                const int blocks_x = (p.width + rb - 1) / rb;
                stripes = (p.height + rb - 1) / rb;
                fill_block_states(component_seed(pic_offset, c), blocks_x, stripes, states_[c]);
            }
        }
        first_task[c + 1] = first_task[c] + stripes;
    }
    // Every worker's buffers are sized here, on the calling thread, for the widest plane:
    // a worker that got no stripe in the first frames cannot allocate later.
    const int blocks_x = (src.width + rb - 1) / rb;
    bool all_tables = true, any_narrow = false, any_wide = false;
    if (kernels_ == Kernels::kOptimized)
        for (int c = 0; c < src.plane_count() && c < 3; c++)
            if (!params.cancelled && params.comp[c].present) {
                have_scaled_[c] = scaled_[c].update(params.comp[c], cache_, params.log2_scale_factor + 6);
                if (have_scaled_[c])
                    for (int a = 0; a < 256; a++) {
                        const int iv = params.comp[c].interval_of_intensity[std::size_t(a)];
                        table_offsets_[c][std::size_t(a)] =
                            (iv < 0 ? scaled_[c].zero_interval() : iv) * 2 * kTemplateSize * kTemplateSize;
                    }
                all_tables &= have_scaled_[c];
                const bool narrow = have_scaled_[c] && scaled_[c].narrow();
                any_narrow |= narrow;
                any_wide |= !narrow;
            }
    auto grow = [](auto& v, std::size_t n) {
        if (v.size() < n) v.resize(n);
    };
    for (auto& s : scratch_) {
        if (kernels_ == Kernels::kReference) {
            grow(s.stripe, std::size_t(blocks_x * rb + 2) * rb);
            if (flavour_ == FgcFlavour::kFfmpeg) grow(s.has_grain, std::size_t(blocks_x) * 4);
        } else {
            grow(s.sums, std::size_t(blocks_x) * 4);
            grow(s.blocks, std::size_t(blocks_x) * 4);
            grow(s.narrow_blocks, std::size_t(blocks_x) * 4);
            grow(s.places, std::size_t(blocks_x) * 2);
            // kBandRows rows of the stripe's width, 3 columns of padding
            const std::size_t band = std::size_t(blocks_x * rb + 3) * std::size_t(kBandRows);
            if (any_narrow) grow(s.narrow_band, band);
            if (any_wide) grow(s.band, band);
            if (!all_tables) {
                grow(s.scaled, std::size_t(blocks_x) * rb * rb);
                grow(s.copies, std::size_t(blocks_x) * 4);
            }
        }
    }
    // The stripes go to the threads in runs of consecutive ones, because each stripe's blend
    // prefetches the rows of the stripe below (deblock_blend_row_*), which helps only if the
    // same thread takes it: handed out one by one, two threads would alternate and fetch each
    // other's rows. Eight runs per thread keep the threads' shares within a small fraction of
    // a frame of each other when one of them is held up.
    const int stripes = first_task[3];
    const int runs = std::min(stripes, pool_->size() == 1 ? 1 : pool_->size() * 8);
    pool_->parallel_for(runs, [&](int run, int worker) {
        const int t0 = int(int64_t(stripes) * run / runs), t1 = int(int64_t(stripes) * (run + 1) / runs);
        Scratch& scratch = scratch_[std::size_t(worker)];
        for (int task = t0; task < t1; task++) {
            int c = 0;
            while (task >= first_task[c + 1]) c++;
            const int by = task - first_task[c];
            const bool prefetch_next = task + 1 < t1 && task + 1 < first_task[c + 1];
            const PlaneView &s = src.planes[c], &d = dst.planes[c];
            if (kernels_ == Kernels::kReference) {
                if (bps == 1)
                    reference_stripe<uint8_t>(params, c, s, d, src.bit_depth, by, scratch);
                else
                    reference_stripe<uint16_t>(params, c, s, d, src.bit_depth, by, scratch);
            } else if (bps == 1) {
                optimized_stripe_of<uint8_t>(params, c, s, d, src.bit_depth, by, prefetch_next, scratch);
            } else {
                optimized_stripe_of<uint16_t>(params, c, s, d, src.bit_depth, by, prefetch_next, scratch);
            }
        }
    });
}

}  // namespace filmgrain::fgc

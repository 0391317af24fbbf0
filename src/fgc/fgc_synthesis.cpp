#include "fgc/fgc_synthesis.hpp"

#include <algorithm>
#include <cstring>

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
      kernels_(kernels),
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
        n += s.stripe.capacity() * sizeof(int32_t) + s.stripe16.capacity() * sizeof(int16_t) +
             s.sums.capacity() * sizeof(uint32_t) + s.copies.capacity() * sizeof(simd::BlockCopy);
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
                avg = block_average_inside<Pixel>(src, x0, y0, bs, bit_depth);
                cols = std::min(bs, w - x0);  // HM-2020 writes grain only inside the picture
            } else {
                avg = block_average_replicated<Pixel>(src, x0, y0, bs, bit_depth);
            }
            const int iv = comp.interval_of_intensity[avg];
            if (iv < 0) continue;  // no interval: this block gets no grain
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
    deblock_stripe_vertical_edges(stripe.data(), stride, rows, w, bs);
    for (int l = 0; l < rows; l++) {
        const int y = by * rb + l;
        blend_row_additive<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), stripe.data() + std::size_t(l) * stride,
                                  w, bit_depth);
    }
}

// Optimized twin of reference_stripe: block sums, template copies and the fused
// deblocking + blending run as vector kernels on an int16 stripe; blocks that touch the
// picture's right or bottom edge take their averages from the reference functions.
template <typename Pixel>
void FgcFrameSynthesis::optimized_stripe(const ResolvedFgc& params, int c, const PlaneView& src,
                                         const PlaneView& dst, int bit_depth, int by, Scratch& scratch) const {
    const ResolvedComponent& comp = params.comp[c];
    const int bs = block_size_;
    const int rb = bs == 32 ? 32 : 16;
    const int w = src.width, h = src.height;
    const int blocks_x = (w + rb - 1) / rb;
    const bool rdd5 = flavour_ != FgcFlavour::kVtm;
    const int shift = params.log2_scale_factor + 6;
    const uint32_t* states = states_[c].data();
    const int stride = blocks_x * rb + 2;
    const int sub_rows = bs == 8 ? 2 : 1, sub_cols = bs == 8 ? 2 : 1;
    const int whole_blocks = w / bs;
    const int log2_area = bs == 8 ? 6 : bs == 16 ? 8 : 10;

    if (scratch.stripe16.size() < std::size_t(stride) * rb) scratch.stripe16.resize(std::size_t(stride) * rb);
    if (scratch.sums.size() < std::size_t(blocks_x) * 2 * sub_rows)
        scratch.sums.resize(std::size_t(blocks_x) * 2 * sub_rows);
    if (scratch.copies.size() < std::size_t(blocks_x) * 4) scratch.copies.resize(std::size_t(blocks_x) * 4);
    int16_t* stripe = scratch.stripe16.data();
    std::fill(stripe, stripe + std::ptrdiff_t(stride) * rb, int16_t(0));

    // Block sums of each row of adaptation blocks in this stripe (whole blocks only).
    const int blocks_per_row = blocks_x * sub_cols;
    uint32_t* sums = scratch.sums.data();
    for (int yi = 0; yi < sub_rows; yi++) {
        const int y0 = by * rb + yi * bs;
        const int rows_inside = std::min(bs, h - y0);
        if (rows_inside <= 0 || (!rdd5 && rows_inside < bs)) continue;
        const Pixel* row0 = src.row<const Pixel>(y0);
        if constexpr (sizeof(Pixel) == 1)
            simd::block_sums_u8(row0, src.stride, rows_inside, w, bs, sums + yi * blocks_per_row);
        else
            simd::block_sums_u16(row0, src.stride, rows_inside, w, bs, sums + yi * blocks_per_row);
    }

    int copies = 0;
    for (int bx = 0; bx < blocks_x; bx++) {
        const BlockOffset off = block_offset_from_state(states[std::size_t(by) * blocks_x + bx], bs);
        const int sub_count = bs == 8 ? 4 : 1;
        for (int sub = 0; sub < sub_count; sub++) {
            const int xo = bs == 8 ? (sub & 1) * 8 : 0, yo = bs == 8 ? (sub >> 1) * 8 : 0;
            const int x0 = bx * rb + xo, y0 = by * rb + yo;
            const int rows_inside = std::min(bs, h - y0);
            const bool whole_columns = x0 / bs < whole_blocks;
            int avg;
            int cols = bs;
            if (rdd5) {
                if (x0 >= w || y0 >= h) continue;
                if (whole_columns) {
                    const uint32_t sum = sums[(yo / bs) * blocks_per_row + x0 / bs];
                    // a whole block divides by 2^log2_area: the same as a shift for unsigned sums
                    const uint32_t mean = rows_inside == bs ? sum >> log2_area : sum / uint32_t(bs * rows_inside);
                    avg = int(std::min<uint32_t>(mean >> (bit_depth - 8), 255));
                } else {
                    avg = block_average_inside<Pixel>(src, x0, y0, bs, bit_depth);
                }
                cols = std::min(bs, w - x0);
            } else if (whole_columns && rows_inside == bs) {
                const uint64_t sum = sums[(yo / bs) * blocks_per_row + x0 / bs];
                avg = int(std::min<uint64_t>(sum >> (log2_area + bit_depth - 8), 255));
            } else {
                avg = block_average_replicated<Pixel>(src, x0, y0, bs, bit_depth);
            }
            const int iv = comp.interval_of_intensity[avg];
            if (iv < 0) continue;
            const ResolvedInterval& ri = comp.intervals[iv];
            const GrainTemplate& t = cache_.get(ri.cutoff_h, ri.cutoff_v);
            scratch.copies[std::size_t(copies++)] = {t[off.y + yo].data() + off.x + xo,
                                                     stripe + std::size_t(yo) * stride + x0, off.sign * ri.scale, cols};
        }
    }
    simd::scale_template_blocks(scratch.copies.data(), copies, bs, shift, stride);

    const int rows = std::min(rb, h - by * rb);
    for (int l = 0; l < rows; l++) {
        const int y = by * rb + l;
        const int16_t* g = stripe + std::size_t(l) * stride;
        if constexpr (sizeof(Pixel) == 1)
            simd::deblock_blend_row_u8(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bs);
        else
            simd::deblock_blend_row_u16(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bs, bit_depth);
    }
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
    const std::size_t stripe_size = std::size_t(blocks_x * rb + 2) * rb;
    for (auto& s : scratch_) {
        if (kernels_ == Kernels::kReference) {
            if (s.stripe.size() < stripe_size) s.stripe.resize(stripe_size);
        } else {
            if (s.stripe16.size() < stripe_size) s.stripe16.resize(stripe_size);
            if (s.sums.size() < std::size_t(blocks_x) * 4) s.sums.resize(std::size_t(blocks_x) * 4);
            if (s.copies.size() < std::size_t(blocks_x) * 4) s.copies.resize(std::size_t(blocks_x) * 4);
        }
    }
    pool_->parallel_for(first_task[3], [&](int task, int worker) {
        int c = 0;
        while (task >= first_task[c + 1]) c++;
        const int by = task - first_task[c];
        Scratch& scratch = scratch_[std::size_t(worker)];
        const PlaneView &s = src.planes[c], &d = dst.planes[c];
        if (kernels_ == Kernels::kReference) {
            if (bps == 1)
                reference_stripe<uint8_t>(params, c, s, d, src.bit_depth, by, scratch);
            else
                reference_stripe<uint16_t>(params, c, s, d, src.bit_depth, by, scratch);
        } else {
            if (bps == 1)
                optimized_stripe<uint8_t>(params, c, s, d, src.bit_depth, by, scratch);
            else
                optimized_stripe<uint16_t>(params, c, s, d, src.bit_depth, by, scratch);
        }
    });
}

}  // namespace filmgrain::fgc

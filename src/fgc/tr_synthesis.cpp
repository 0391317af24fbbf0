#include "fgc/tr_synthesis.hpp"

#include <algorithm>

#include "fgc/ar_template_generation.hpp"
#include "fgc/blending.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/fgc_synthesis.hpp"
#include "fgc/local_adaptation.hpp"
#include "fgc/multiplicative_blending.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::fgc {

TrFrameSynthesis::TrFrameSynthesis(FgcFlavour base, int block_size, int single_line_blocks)
    : base_(base),
      block_size_(block_size),
      single_line_(single_line_blocks),
      cache_(base == FgcFlavour::kVtm ? TemplateTransform::kVvcDct2 : TemplateTransform::kRdd5Matrix, block_size) {
    if (base != FgcFlavour::kTr && base != FgcFlavour::kVtm)
        throw Error(ErrorCode::kInvalidArgument, "TrFrameSynthesis runs the tr and vtm flavours only");
    if (block_size != 8 && block_size != 16 && block_size != 32)
        throw Error(ErrorCode::kInvalidArgument, "block size " + std::to_string(block_size) + " is not 8, 16 or 32");
    if (single_line_blocks != 0 && single_line_blocks != block_size)
        throw Error(ErrorCode::kInvalidArgument, "single-line blocks of " + std::to_string(single_line_blocks) +
                                                     "x1 need block size " + std::to_string(single_line_blocks));
}

void TrFrameSynthesis::prepare(const ResolvedFgc& params) {
    for (int c = 0; c < 3; c++) {
        auto& list = interval_template_[c];
        list.clear();
        for (const ResolvedInterval& ri : params.comp[c].intervals) {
            if (single_line_ && !list.empty()) break;  // one template per component and picture
            if (params.model_id == 0) {
                list.push_back(&cache_.ensure(ri.cutoff_h, ri.cutoff_v));
                continue;
            }
            // Intervals of one component share the noise field (Seed_LUT[c]), so that their
            // templates differ only by the filter and the texture changes smoothly with
            // intensity; components get different fields.
            const std::array<int, 6> key{c, params.log2_scale_factor, ri.ar[1], ri.ar[3], ri.ar[4], ri.ar[5]};
            auto& slot = ar_cache_[key];
            if (!slot)
                slot = std::make_unique<GrainTemplate>(make_ar_template_rdd5_noise(ri.ar, params.log2_scale_factor, c));
            list.push_back(slot.get());
        }
    }
}

namespace {

bool has_colour_correlation(const ResolvedFgc& params, int c) {
    if (params.model_id != 1 || c == 0 || !params.comp[c].present || !params.comp[c - 1].present) return false;
    return std::any_of(params.comp[c].intervals.begin(), params.comp[c].intervals.end(),
                       [](const ResolvedInterval& ri) { return ri.ar[2] != 0; });
}

}  // namespace

// The colour term p1 * G[c-1][x][y] of the auto-regressive model, with the previous
// component's finished grain at the co-located position (the mean of the 2x2 or 2x1 luma
// samples under a subsampled chroma sample, rounded). It is added to the grain after the
// component's own filtering, rather than fed through its recursion: the templates are made
// before any picture, and the recursion would need the previous component's grain of the
// whole picture at every sample.
void TrFrameSynthesis::add_colour_correlation(const ResolvedFgc& params, int c, const FrameView& frame, int y0,
                                              int rows, int stride) {
    const PlaneView& cur = frame.planes[c];
    const int pw = frame.planes[c - 1].width, ph = frame.planes[c - 1].height;
    const int sx = c == 1 ? chroma_shift_x(frame.format) : 0, sy = c == 1 ? chroma_shift_y(frame.format) : 0;
    const int n_shift = sx + sy;
    const int L = params.log2_scale_factor;
    const int32_t* prev = plane_grain_[c - 1].data();
    for (int l = 0; l < rows; l++) {
        const int y = y0 + l;
        int32_t* g = stripe_.data() + std::size_t(l) * stride;
        const int16_t* rho = rho_.data() + std::size_t(l) * stride;
        for (int x = 0; x < cur.width; x++) {
            if (!rho[x]) continue;
            int32_t sum = 0;
            for (int j = 0; j < (1 << sy); j++)
                for (int i = 0; i < (1 << sx); i++)
                    sum += prev[std::size_t(std::min((y << sy) + j, ph - 1)) * pw + std::min((x << sx) + i, pw - 1)];
            const int32_t co = n_shift ? (sum + (1 << (n_shift - 1))) >> n_shift : sum;
            g[x] += (rho[x] * co + (1 << (L - 1))) >> L;
        }
    }
}

template <typename Pixel>
void TrFrameSynthesis::apply_component(const ResolvedFgc& params, int c, const FrameView& src_frame,
                                       const FrameView& dst_frame, uint32_t seed, bool keep_grain) {
    const PlaneView& src = src_frame.planes[c];
    const PlaneView& dst = dst_frame.planes[c];
    const int bit_depth = src_frame.bit_depth;
    const ResolvedComponent& comp = params.comp[c];
    const std::vector<const GrainTemplate*>& templates = interval_template_[c];
    const int bs = block_size_;
    const int rb = bs == 32 ? 32 : 16;  // randomization block: one LFSR step each
    const int w = src.width, h = src.height;
    const int blocks_x = (w + rb - 1) / rb, blocks_y = (h + rb - 1) / rb;
    const bool inside = base_ != FgcFlavour::kVtm;  // rdd5: only the samples inside the picture
    const bool line = single_line_ != 0;
    const bool correlate = has_colour_correlation(params, c);
    const int shift = params.log2_scale_factor + 6 - params.model_id;
    fill_block_states(seed, blocks_x, blocks_y, states_);

    const int stride = blocks_x * rb + 2;  // +2: the deblocking filter reads past the last edge
    stripe_.resize(std::size_t(stride) * rb);
    if (correlate) rho_.resize(stripe_.size());
    if (keep_grain) plane_grain_[c].resize(std::size_t(w) * h);

    for (int by = 0; by < blocks_y; by++) {
        std::fill(stripe_.begin(), stripe_.end(), 0);
        if (correlate) std::fill(rho_.begin(), rho_.end(), int16_t(0));
        for (int bx = 0; bx < blocks_x; bx++) {
            const BlockOffset off = block_offset_from_state(states_[std::size_t(by) * blocks_x + bx], bs);
            const int sub_count = bs == 8 ? 4 : 1;
            for (int sub = 0; sub < sub_count; sub++) {
                const int xo = bs == 8 ? (sub & 1) * 8 : 0, yo = bs == 8 ? (sub >> 1) * 8 : 0;
                const int x0 = bx * rb + xo, y0 = by * rb + yo;
                if (inside && (x0 >= w || y0 >= h)) continue;
                const int cols = inside ? std::min(bs, w - x0) : bs;
                int block_interval = -1;
                if (!line) {
                    const int avg = inside ? block_average_inside<Pixel>(src, x0, y0, bs, bit_depth)
                                           : block_average_replicated<Pixel>(src, x0, y0, bs, bit_depth);
                    block_interval = comp.interval_of_intensity[avg];
                    if (block_interval < 0) continue;  // no interval: this block gets no grain
                }
                for (int l = 0; l < bs; l++) {
                    int iv = block_interval;
                    if (line) {
                        if (inside && y0 + l >= h) break;
                        const int avg = inside ? segment_average_inside<Pixel>(src, x0, y0 + l, bs, bit_depth)
                                               : segment_average_replicated<Pixel>(src, x0, y0 + l, bs, bit_depth);
                        iv = comp.interval_of_intensity[avg];
                        if (iv < 0) continue;
                    }
                    const ResolvedInterval& ri = comp.intervals[iv];
                    // Single-line blocks: one template for the picture, the first interval's.
                    const GrainTemplate& t = *templates[line ? 0 : iv];
                    const int32_t scale = off.sign * ri.scale;
                    const int8_t* trow = t[off.y + yo + l].data() + off.x + xo;
                    const std::size_t at = std::size_t(yo + l) * stride + x0;
                    int32_t* g = stripe_.data() + at;
                    for (int k = 0; k < cols; k++) g[k] = (scale * trow[k]) >> shift;
                    if (correlate) std::fill(rho_.begin() + at, rho_.begin() + at + cols, int16_t(ri.ar[2]));
                }
            }
        }
        const int rows = std::min(rb, h - by * rb);
        deblock_stripe_vertical_edges(stripe_.data(), stride, rows, w, bs);
        if (correlate) add_colour_correlation(params, c, src_frame, by * rb, rows, stride);
        for (int l = 0; l < rows; l++) {
            const int y = by * rb + l;
            const int32_t* g = stripe_.data() + std::size_t(l) * stride;
            if (keep_grain) std::copy(g, g + w, plane_grain_[c].begin() + std::ptrdiff_t(y) * w);
            if (params.blending_mode_id == 1)
                blend_row_multiplicative<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bit_depth);
            else
                blend_row_additive<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bit_depth);
        }
    }
}

void TrFrameSynthesis::apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst,
                             int32_t pic_offset) {
    prepare(params);
    const int bps = src.bytes_per_sample();
    for (int c = 0; c < src.plane_count(); c++) {
        if (params.cancelled || !params.comp[c].present) {
            copy_plane(src.planes[c], dst.planes[c], bps);
            continue;
        }
        // The next component's colour term reads this one's grain.
        const bool keep = c + 1 < src.plane_count() && has_colour_correlation(params, c + 1);
        const uint32_t seed = component_seed(pic_offset, c);
        if (bps == 1)
            apply_component<uint8_t>(params, c, src, dst, seed, keep);
        else
            apply_component<uint16_t>(params, c, src, dst, seed, keep);
    }
}

}  // namespace filmgrain::fgc

// The scalar reference stripe of FgcPictureSynthesis: every flavour and option but vfgs, one
// stage after the other as TR 23002-9 clause 7 reads (see fgc_picture_synthesis.hpp).
#include <algorithm>
#include <cstdint>

#include "fgc/blending.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/colour_correlation.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/grain_scaling.hpp"
#include "fgc/local_adaptation.hpp"
#include "fgc/multiplicative_blending.hpp"

namespace filmgrain::fgc {

template <typename Pixel>
void FgcPictureSynthesis::reference_stripe(const ResolvedFgc& params, int c, const FrameView& src_frame,
                                         const FrameView& dst_frame, int by, Scratch& scratch) {
    const PlaneView& src = src_frame.planes[c];
    const PlaneView& dst = dst_frame.planes[c];
    const int bit_depth = src_frame.bit_depth;
    const ResolvedComponent& comp = params.comp[c];
    const std::vector<const GrainTemplate*>& templates = interval_template_[std::size_t(c)];
    const int bs = block_size_;
    const int rb = bs == 32 ? 32 : 16;  // randomization block: one LFSR step each
    const int w = src.width, h = src.height;
    const int blocks_x = (w + rb - 1) / rb;
    // rdd5, ffmpeg, tr: only the samples inside the picture are averaged and get grain
    // (HM-2020); vtm: edge-replicated averages over whole blocks (HM/VTM).
    const bool inside = (flavour_ != FgcFlavour::kVtm) != deviations_.partial_blocks_toggled;
    const bool ffmpeg = flavour_ == FgcFlavour::kFfmpeg;
    // FFmpeg's rule: only edges whose right block got grain are deblocked (deblocking.hpp)
    const bool deblock_after_grain = ffmpeg != deviations_.blank_block_deblocking_toggled;
    const bool interval_from_luma = deviations_.chroma_interval_from_luma && c > 0;
    const int luma_sx = c ? chroma_shift_x(src_frame.format) : 0, luma_sy = c ? chroma_shift_y(src_frame.format) : 0;
    const bool line = single_line_ != 0;
    const bool correlate = correlate_[std::size_t(c)];
    // Auto-regressive templates carry one bit more than frequency-filtered ones (as in VFGS).
    const int shift = params.log2_scale_factor + 6 - params.model_id;
    const uint32_t* states = states_[c].data() + std::size_t(by) * std::size_t(blocks_x);

    // +2 columns: the deblocking filter reads one sample past the last edge.
    const int stride = blocks_x * rb + 2;
    const std::ptrdiff_t samples = std::ptrdiff_t(stride) * rb;
    int32_t* stripe = scratch.stripe.data();
    std::fill(stripe, stripe + samples, 0);
    // ffmpeg: which blocks of the stripe got grain, per block row (its deblocking depends on it)
    const int block_columns = blocks_x * (rb / bs);
    uint8_t* has_grain = scratch.has_grain.data();
    if (deblock_after_grain) std::fill(has_grain, has_grain + std::ptrdiff_t(block_columns) * (rb / bs), uint8_t(0));
    int16_t* rho = scratch.rho.data();
    if (correlate) std::fill(rho, rho + samples, int16_t(0));

    for (int bx = 0; bx < blocks_x; bx++) {
        const BlockOffset off = block_offset_from_state(states[bx], bs);
        const int sub_count = bs == 8 ? 4 : 1;
        for (int sub = 0; sub < sub_count; sub++) {
            const int xo = bs == 8 ? (sub & 1) * 8 : 0, yo = bs == 8 ? (sub >> 1) * 8 : 0;
            const int x0 = bx * rb + xo, y0 = by * rb + yo;
            if (inside && (x0 >= w || y0 >= h)) continue;
            const int cols = inside ? std::min(bs, w - x0) : bs;
            // Rows l0..l1 of the block from interval iv's template (single-line blocks: the
            // first interval's, one template for the picture; only the scale follows iv).
            auto emit_rows = [&](int l0, int l1, int iv) {
                const ResolvedInterval& ri = comp.intervals[std::size_t(iv)];
                const GrainTemplate& t = *templates[line ? 0 : std::size_t(iv)];
                const int32_t scale = off.sign * ri.scale;
                for (int l = l0; l < l1; l++) {
                    const std::ptrdiff_t at = std::ptrdiff_t(yo + l) * stride + x0;
                    scale_template_row(t[std::size_t(off.y + yo + l)].data() + off.x + xo, scale, shift, stripe + at,
                                       cols);
                    if (correlate) std::fill(rho + at, rho + at + cols, int16_t(ri.ar[2]));
                }
            };
            if (line) {
                for (int l = 0; l < bs && !(inside && y0 + l >= h); l++) {
                    const int avg = inside ? segment_average_inside<Pixel>(src, x0, y0 + l, bs, bit_depth)
                                           : segment_average_replicated<Pixel>(src, x0, y0 + l, bs, bit_depth);
                    const int iv = comp.interval_of_intensity[std::size_t(avg)];
                    if (iv >= 0) emit_rows(l, l + 1, iv);
                }
                continue;
            }
            // the averaged plane and block: the component's own, or (verify's deviation) the
            // co-sited luma block, clamped into the luma plane
            const PlaneView& avg_plane = interval_from_luma ? src_frame.planes[0] : src;
            const int ax = interval_from_luma ? std::min(x0 << luma_sx, avg_plane.width - 1) : x0;
            const int ay = interval_from_luma ? std::min(y0 << luma_sy, avg_plane.height - 1) : y0;
            const int avg = ffmpeg && inside ? block_average_zero_outside<Pixel>(avg_plane, ax, ay, bs, bit_depth)
                            : inside         ? block_average_inside<Pixel>(avg_plane, ax, ay, bs, bit_depth)
                                             : block_average_replicated<Pixel>(avg_plane, ax, ay, bs, bit_depth);
            const int iv = comp.interval_of_intensity[std::size_t(avg)];
            if (iv < 0) continue;  // no interval: this block gets no grain
            if (deblock_after_grain) has_grain[std::size_t(yo / bs) * block_columns + std::size_t(x0 / bs)] = 1;
            emit_rows(0, bs, iv);
        }
    }
    const int rows = std::min(rb, h - by * rb);
    for (int yo = 0; yo < rows && !deviations_.no_deblocking; yo += bs)
        deblock_stripe_vertical_edges(stripe + std::ptrdiff_t(yo) * stride, stride, std::min(bs, rows - yo), w, bs,
                                      deblock_after_grain ? has_grain + std::size_t(yo / bs) * block_columns
                                                          : nullptr);
    if (correlate) {
        const bool first_chroma = c == 1;  // Cb over luma; Cr over Cb, at the same resolution
        const PreviousGrain previous{plane_grain_[std::size_t(c - 1)].data(), src_frame.planes[c - 1].width,
                                     src_frame.planes[c - 1].height,
                                     first_chroma ? chroma_shift_x(src_frame.format) : 0,
                                     first_chroma ? chroma_shift_y(src_frame.format) : 0};
        add_colour_correlation(previous, params.log2_scale_factor, by * rb, rows, w, stripe, rho, stride);
    }
    for (int l = 0; l < rows; l++) {
        const int y = by * rb + l;
        const int32_t* g = stripe + std::ptrdiff_t(l) * stride;
        if (keep_grain_[std::size_t(c)])
            std::copy(g, g + w, plane_grain_[std::size_t(c)].begin() + std::ptrdiff_t(y) * w);
        if (params.blending_mode_id == 1)
            blend_row_multiplicative<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bit_depth);
        else
            blend_row_additive<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), g, w, bit_depth);
    }
}

template void FgcPictureSynthesis::reference_stripe<uint8_t>(const ResolvedFgc&, int, const FrameView&,
                                                           const FrameView&, int, Scratch&);
template void FgcPictureSynthesis::reference_stripe<uint16_t>(const ResolvedFgc&, int, const FrameView&,
                                                            const FrameView&, int, Scratch&);

}  // namespace filmgrain::fgc

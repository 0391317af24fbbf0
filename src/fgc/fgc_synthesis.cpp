#include "fgc/fgc_synthesis.hpp"

#include <algorithm>
#include <cstring>

#include "fgc/blending.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/local_adaptation.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::fgc {

int default_block_size(FgcFlavour flavour, int luma_width, int luma_height) {
    if (flavour != FgcFlavour::kVtm) return 8;
    const long long area = (long long)luma_width * luma_height;
    if (area <= 1920LL * 1080) return 8;
    if (area <= 3840LL * 2160) return 16;
    return 32;
}

FgcFrameSynthesis::FgcFrameSynthesis(FgcFlavour flavour, int block_size)
    : flavour_(flavour),
      block_size_(block_size),
      cache_(flavour == FgcFlavour::kVtm ? TemplateTransform::kVvcDct2 : TemplateTransform::kRdd5Matrix, block_size) {
    if (block_size != 8 && block_size != 16 && block_size != 32)
        throw Error(ErrorCode::kInvalidArgument, "block size " + std::to_string(block_size) + " is not 8, 16 or 32");
}

void FgcFrameSynthesis::prepare(const ResolvedFgc& params) {
    for (auto [h, v] : params.cutoff_pairs) cache_.ensure(h, v);
}

void copy_plane(const PlaneView& src, const PlaneView& dst, int bytes_per_sample) {
    if (src.data == dst.data && src.stride == dst.stride) return;
    const std::size_t row_bytes = std::size_t(src.width) * bytes_per_sample;
    for (int y = 0; y < src.height; y++) std::memmove(dst.data + dst.stride * y, src.data + src.stride * y, row_bytes);
}

template <typename Pixel>
void FgcFrameSynthesis::apply_component(const ResolvedFgc& params, int c, const PlaneView& src, const PlaneView& dst,
                                        int bit_depth, uint32_t seed) {
    const ResolvedComponent& comp = params.comp[c];
    const int bs = block_size_;
    const int rb = bs == 32 ? 32 : 16;  // randomization block: one LFSR step each
    const int w = src.width, h = src.height;
    const int blocks_x = (w + rb - 1) / rb, blocks_y = (h + rb - 1) / rb;
    const bool rdd5 = flavour_ != FgcFlavour::kVtm;
    const int shift = params.log2_scale_factor + 6;
    fill_block_states(seed, blocks_x, blocks_y, states_);

    // +2 columns: the deblocking filter reads one sample past the last edge.
    const int stride = blocks_x * rb + 2;
    stripe_.resize(std::size_t(stride) * rb);

    for (int by = 0; by < blocks_y; by++) {
        std::fill(stripe_.begin(), stripe_.end(), 0);
        for (int bx = 0; bx < blocks_x; bx++) {
            const BlockOffset off = block_offset_from_state(states_[std::size_t(by) * blocks_x + bx], bs);
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
                    int32_t* g = stripe_.data() + std::size_t(yo + l) * stride + x0;
                    for (int k = 0; k < cols; k++) g[k] = (scale * trow[k]) >> shift;
                }
            }
        }
        const int rows = std::min(rb, h - by * rb);
        deblock_stripe_vertical_edges(stripe_.data(), stride, rows, w, bs);
        for (int l = 0; l < rows; l++) {
            const int y = by * rb + l;
            blend_row_additive<Pixel>(src.row<const Pixel>(y), dst.row<Pixel>(y), stripe_.data() + std::size_t(l) * stride,
                                      w, bit_depth);
        }
    }
}

void FgcFrameSynthesis::apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst,
                              int32_t pic_offset) {
    prepare(params);
    const int bps = src.bytes_per_sample();
    for (int c = 0; c < src.plane_count(); c++) {
        if (params.cancelled || !params.comp[c].present) {
            copy_plane(src.planes[c], dst.planes[c], bps);
            continue;
        }
        const uint32_t seed = component_seed(pic_offset, c);
        if (bps == 1)
            apply_component<uint8_t>(params, c, src.planes[c], dst.planes[c], src.bit_depth, seed);
        else
            apply_component<uint16_t>(params, c, src.planes[c], dst.planes[c], src.bit_depth, seed);
    }
}

}  // namespace filmgrain::fgc

// Scalar reference of the VFGS row kernels (vfgs_row_kernels.hpp): the reference's
// per-sample order of operations, from the helpers of vfgs_picture_synthesis.hpp.
#include <algorithm>

#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "fgc/vfgs/vfgs_row_kernels.hpp"

namespace filmgrain::vfgs::scalar {

namespace {

template <typename In>
void grain_row(const GrainRowJob& job, const In* in, int16_t* grain, int16_t* scale) {
    const ComponentLuts& lut = *job.luts;
    const int bw = job.block_width, c1 = job.overlap_c1, c2 = job.overlap_c2;
    for (int b = 0; b < job.block_count; ++b) {
        const GrainBlock& blk = job.blocks[b];
        for (int i = 0; i < bw; ++i) {
            const int x = b * bw + i;
            const int inten = std::min(static_cast<int>(in[x]) >> job.intensity_shift, 255);
            const auto sample = [&](int t) { return job.pool[t * kTemplateBytes + blk.offset + i]; };
            const auto sample_up = [&](int t) { return job.pool_up[t * kTemplateBytes + blk.offset_up + i]; };
            const int t = lut.tmpl[static_cast<size_t>(inten)];
            int p = sample(t) * blk.sign;
            if (c1) p = overlap_blend(p, sample_up(t) * blk.sign_up, c1, c2);
            if (job.pattern_interpolation && lut.frac[static_cast<size_t>(inten)]) {
                // TR 23002-9 7.5.4: blend with the next template (weights in 1/16).
                const int f = lut.frac[static_cast<size_t>(inten)];
                const int tn = lut.tmpl_next[static_cast<size_t>(inten)];
                int pn = sample(tn) * blk.sign;
                if (c1) pn = overlap_blend(pn, sample_up(tn) * blk.sign_up, c1, c2);
                p = (p * (16 - f) + pn * f + 8) >> 4;
            }
            grain[x] = static_cast<int16_t>(p);
            scale[x] = lut.scale[static_cast<size_t>(inten)];
        }
    }
    // Each edge reads two samples either side and changes the two next to it; edges are at
    // least 8 samples apart, so filtering them one after the other reads unfiltered values.
    for (int b = 1; b < job.block_count; ++b) {
        int16_t* e = grain + b * bw;
        int g[4] = {e[-2], e[-1], e[0], e[1]};
        deblock_edge(g, 2);
        e[-1] = static_cast<int16_t>(g[1]);
        e[0] = static_cast<int16_t>(g[2]);
    }
}

template <typename In, typename Out>
void blend_row(const BlendRowJob& job, const In* in, const int16_t* grain, const int16_t* scale, Out* out,
               bool round_to_8bit) {
    for (int x = 0; x < job.width; ++x) {
        const int g = scale_grain(scale[x], grain[x], job.shift);
        const int v = blend_sample(in[x], g, job.bit_depth);
        out[x] = static_cast<Out>(round_to_8bit ? to_8bit(v) : v);
    }
}

}  // namespace

void grain_row_u8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale) {
    grain_row(job, in, grain, scale);
}
void grain_row_u16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale) {
    grain_row(job, in, grain, scale);
}
void blend_row_u8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out) {
    blend_row(job, in, grain, scale, out, false);
}
void blend_row_u16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                   uint16_t* out) {
    blend_row(job, in, grain, scale, out, false);
}
void blend_row_u16_to_u8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                         uint8_t* out) {
    blend_row(job, in, grain, scale, out, true);
}

}  // namespace filmgrain::vfgs::scalar

// Per-sample grain synthesis and blending of the VFGS flavour: see vfgs_picture_synthesis.hpp.
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"

#include <algorithm>

#include "fgc/vfgs/vfgs_random.hpp"

namespace filmgrain::vfgs {

std::array<int, 2> overlap_weights(int j, int suby, bool first_stripe) {
    if (first_stripe) return {0, 0};
    if (j == 0) return suby > 1 ? std::array<int, 2>{20, 20} : std::array<int, 2>{12, 24};
    if (j == 1) return {24, 12};  // never reached by 4:2:0 chroma (odd luma rows carry no chroma row)
    return {0, 0};
}

void deblock_edge(int* g, int e) {
    const int l1 = g[e - 2], l0 = g[e - 1], r0 = g[e], r1 = g[e + 1];
    g[e - 1] = (l1 + 3 * l0 + r0 + 2) >> 2;
    g[e] = (l0 + 3 * r0 + r1 + 2) >> 2;
}

namespace {

struct RowWork {
    std::vector<int> in;     // source samples of the row, padded to whole blocks
    std::vector<int> grain;  // unscaled grain
    std::vector<int> scale;
};

int read_sample(const PlaneView& p, int bit_depth, int y, int x) {
    return bit_depth > 8 ? p.row<const uint16_t>(y)[x] : p.row<const uint8_t>(y)[x];
}

void write_sample(const PlaneView& p, int bit_depth, int y, int x, int v) {
    if (bit_depth > 8) p.row<uint16_t>(y)[x] = static_cast<uint16_t>(v);
    else p.row<uint8_t>(y)[x] = static_cast<uint8_t>(v);
}

// One row of plane `c`. `j` is the luma row inside the block stripe; `cur`
// and `up` hold the LFSR state of every block of this stripe and of the one above.
void process_row(const FrameView& src, const FrameView& dst, const SynthesisSetup& st, int c, int py, int j,
                 bool first_stripe, const std::vector<uint32_t>& cur, const std::vector<uint32_t>& up, RowWork& w) {
    const int subx = c ? (1 << chroma_shift_x(src.format)) : 1;
    const int suby = c ? (1 << chroma_shift_y(src.format)) : 1;
    const int bw = 16 / subx;  // block width in this plane
    const int nb = static_cast<int>(cur.size());
    const int n = nb * bw;
    const PlaneView& sp = src.planes[c];
    const PlaneView& dp = dst.planes[c];
    const int pw = sp.width;
    const int bd = src.bit_depth;
    const int bs = bd - 8;

    w.in.resize(static_cast<size_t>(n));
    for (int x = 0; x < pw; ++x) w.in[static_cast<size_t>(x)] = read_sample(sp, bd, py, x);
    // Past the right edge VFGS reads the (uninitialised) stride padding; it only
    // selects templates for grain that is never written, except when the last
    // block holds a single sample (width % 16 == 1 luma, == 2 subsampled
    // chroma): then the deblocking of the last edge reads it. We replicate the
    // last sample there.
    for (int x = pw; x < n; ++x) w.in[static_cast<size_t>(x)] = w.in[static_cast<size_t>(pw - 1)];

    const int out_bd = dst.bit_depth;
    if (!st.has_grain[c]) {
        for (int x = 0; x < pw; ++x) {
            const int v = blend_sample(w.in[static_cast<size_t>(x)], 0, bd);
            write_sample(dp, out_bd, py, x, out_bd < bd ? to_8bit(v) : v);
        }
        return;
    }

    const ComponentLuts& lut = st.luts[c];
    const auto& pool = c ? st.bank->chroma : st.bank->luma;
    const auto [c1, c2] = overlap_weights(j, suby, first_stripe);
    w.grain.resize(static_cast<size_t>(n));
    w.scale.resize(static_cast<size_t>(n));

    for (int b = 0; b < nb; ++b) {
        const BlockOffset o = block_offset(c, cur[static_cast<size_t>(b)], subx, suby);
        const int oy = o.oy + j / suby;
        BlockOffset ou{};
        int oyu = 0;
        if (c1) {
            ou = block_offset(c, up[static_cast<size_t>(b)], subx, suby);
            oyu = ou.oy + (16 + j) / suby;  // the block above continues below its 16 rows
        }
        for (int i = 0; i < bw; ++i) {
            const int x = b * bw + i;
            const int inten = std::min(w.in[static_cast<size_t>(x)] >> bs, 255);
            const int t = lut.tmpl[static_cast<size_t>(inten)];
            int p = pool[static_cast<size_t>(t)][static_cast<size_t>(oy)][static_cast<size_t>(o.ox + i)] * o.sign;
            if (c1)
                p = overlap_blend(p, pool[static_cast<size_t>(t)][static_cast<size_t>(oyu)][static_cast<size_t>(ou.ox + i)] * ou.sign,
                                  c1, c2);
            if (st.pattern_interpolation && lut.frac[static_cast<size_t>(inten)]) {
                // TR 23002-9 7.5.4: blend with the next template (weights in 1/16).
                const int f = lut.frac[static_cast<size_t>(inten)];
                const int tn = lut.tmpl_next[static_cast<size_t>(inten)];
                int pn = pool[static_cast<size_t>(tn)][static_cast<size_t>(oy)][static_cast<size_t>(o.ox + i)] * o.sign;
                if (c1)
                    pn = overlap_blend(
                        pn, pool[static_cast<size_t>(tn)][static_cast<size_t>(oyu)][static_cast<size_t>(ou.ox + i)] * ou.sign,
                        c1, c2);
                p = (p * (16 - f) + pn * f + 8) >> 4;
            }
            w.grain[static_cast<size_t>(x)] = p;
            w.scale[static_cast<size_t>(x)] = lut.scale[static_cast<size_t>(inten)];
        }
    }
    for (int b = 1; b < nb; ++b) deblock_edge(w.grain.data(), b * bw);

    for (int x = 0; x < pw; ++x) {
        const int g = scale_grain(w.scale[static_cast<size_t>(x)], w.grain[static_cast<size_t>(x)], st.scale_shift);
        const int v = blend_sample(w.in[static_cast<size_t>(x)], g, bd);
        write_sample(dp, out_bd, py, x, out_bd < bd ? to_8bit(v) : v);
    }
}

}  // namespace

void add_grain_frame(const FrameView& src, const FrameView& dst, const SynthesisSetup& st, LfsrCursor& cursor) {
    const int nb = blocks_per_stripe(src.width);
    const int ns = stripes_per_frame(src.height);
    const int planes = src.plane_count();
    const int suby_c = 1 << chroma_shift_y(src.format);

    std::vector<uint32_t> cur(static_cast<size_t>(nb)), up(static_cast<size_t>(nb));
    auto fill_states = [nb](std::vector<uint32_t>& v, uint32_t s) {
        for (int b = 0; b < nb; ++b) {
            v[static_cast<size_t>(b)] = s;
            s = lfsr_next(s);
        }
        return s;  // = s advanced nb times: the next stripe's state
    };
    RowWork work;
    for (int k = 0; k < ns; ++k) {
        // Stripe k starts where the previous stripe's blocks left the LFSR;
        // stripe 0 continues from the last stripe of the previous frame (VFGS
        // only moves to a new state when it reaches a row 16k with k >= 1, so
        // the last stripe of a frame and the first of the next share a state).
        if (k > 0) {
            cursor.upper = cursor.stripe;
            cursor.stripe = lfsr_advance(cursor.stripe, static_cast<uint32_t>(nb));
        }
        fill_states(cur, cursor.stripe);
        fill_states(up, cursor.upper);
        const int y_end = std::min(16 * (k + 1), src.height);
        for (int y = 16 * k; y < y_end; ++y) {
            const int j = y - 16 * k;
            process_row(src, dst, st, 0, y, j, k == 0, cur, up, work);
            if (planes > 1 && (y % suby_c) == 0)
                for (int c = 1; c < planes; ++c) process_row(src, dst, st, c, y / suby_c, j, k == 0, cur, up, work);
        }
    }
}

}  // namespace filmgrain::vfgs

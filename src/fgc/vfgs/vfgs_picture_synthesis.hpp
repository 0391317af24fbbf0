// Per-sample grain synthesis and blending of the VFGS flavour
// (TR 23002-9 clause 7.5, Annex B.2.2).
//
// VFGS works line by line on 16x16 luma blocks (4:2:0 chroma 8x8): every
// sample picks its template from the LUT of its own intensity (no block
// average), takes the block's randomly offset and signed template sample,
// blends the first rows of a block stripe with the block above (vertical
// overlap), smooths the vertical block edges (horizontal deblocking), scales
// the grain by the LUT and adds it with clipping.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "fgc/vfgs/vfgs_intensity_runs.hpp"
#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::vfgs {

// Vertical overlap at luma rows 16k and 16k+1 (k >= 1) and 4:2:0 chroma row 8k:
// P = (P * c1 + Pu * c2 + 16) >> 5, with (c1, c2) = (12, 24) then (24, 12)
// for luma, (20, 20) for 4:2:0 chroma. The weights sum to more than 32 (36,
// 40): that is VFGS's choice and is kept for bit-exactness.
inline int overlap_blend(int p, int p_up, int c1, int c2) { return (p * c1 + p_up * c2 + 16) >> 5; }

// Weights (c1, c2) of plane row `j` of a block stripe (luma row index inside
// the 16-row stripe), or (0, 0) when no overlap applies. `first_stripe`: no
// block above.
std::array<int, 2> overlap_weights(int j, int suby, bool first_stripe);

// Horizontal deblocking of the vertical block edge between g[e-1] and g[e],
// on unscaled grain: l0' = (l1 + 3 l0 + r0 + 2) >> 2, r0' = (l0 + 3 r0 + r1 + 2) >> 2,
// both from the values before the filter.
void deblock_edge(int* g, int e);

// Scaling: (scale * g + 2^(shift-1)) >> shift.
inline int scale_grain(int scale, int g, int shift) { return (scale * g + (1 << (shift - 1))) >> shift; }

// Additive blending with VFGS's clip to [0, 255 << (bitdepth - 8)]: in 10 bit
// the maximum is 1020, not 1023, and it applies to every sample of every
// plane, with or without grain (the reference clips its 8-bit range shifted up).
inline int blend_sample(int sample, int g, int bit_depth) {
    const int hi = 255 << (bit_depth - 8);
    const int v = sample + g;
    return v < 0 ? 0 : (v > hi ? hi : v);
}

// --outdepth 8 from 10-bit: (v + 2) >> 2.
inline int to_8bit(int v10) { return (v10 + 2) >> 2; }

// What one frame needs besides the pictures.
struct SynthesisSetup {
    const TemplateBank* bank = nullptr;
    std::array<ComponentLuts, 3> luts{};
    // luts as runs for the vector kernels (FrameSynthesis), made with them: they change only
    // with the parameter set, not per frame
    std::array<IntensityRuns, 3> runs{};
    std::array<bool, 3> has_grain{};  // false: the plane is only clipped
    int scale_shift = 0;
    bool pattern_interpolation = false;
};

// The LFSR position between frames: the state of the last block stripe
// processed and of the one above it (VFGS's per-line "current" and "upper"
// registers). A new frame starts its first stripe from `stripe`.
struct LfsrCursor {
    uint32_t stripe = 0;
    uint32_t upper = 0;
};

// Adds grain to one frame. `src` and `dst` have the same size and format;
// dst.bit_depth is src.bit_depth or 8 (from 10). dst may alias src.
// The serial scalar reference, in the reference's order (stripe after stripe, the LFSR
// stepped block by block). The synthesis runs FrameSynthesis (vfgs_frame_synthesis.hpp),
// which the tests hold to this function's output.
void add_grain_frame(const FrameView& src, const FrameView& dst, const SynthesisSetup& setup, LfsrCursor& cursor);

}  // namespace filmgrain::vfgs

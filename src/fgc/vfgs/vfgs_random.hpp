// Random state of the VFGS flavour (TR 23002-9 clause 7.5, Annex B.2.2).
//
// VFGS drives everything from one 32-bit LFSR: the RDD 5 generator with its bit
// order reversed (the feedback enters at bit 31 and the register shifts right),
// so that a hardware block can take its random bit fields from fixed register
// positions. The same register serves Y, Cb and Cr, and the reference never
// reseeds it (not per frame, not per component, not on a new parameter set).
#pragma once
#include <cstdint>

namespace filmgrain::vfgs {

// State the reference starts from when no seed is given (-r absent or 0).
inline constexpr uint32_t kDefaultLfsrState = 0xDEADBEEFu;

// One step: R' = (R >> 1) | ((bit1(R) ^ bit29(R)) << 31).
constexpr uint32_t lfsr_next(uint32_t r) {
    const uint32_t feedback = ((r >> 1) ^ (r >> 29)) & 1u;
    return (r >> 1) | (feedback << 31);
}

// `n` steps of lfsr_next.
uint32_t lfsr_advance(uint32_t r, uint32_t n);

// The register value a user seed S loads: S << 1 (mod 2^32). The reference
// shifts the seed up because bit 0 is never fed back, so only the 31 upper
// bits define the sequence. A seed of 0 means "no seed" in the reference
// (kDefaultLfsrState is used), and this function mirrors that.
uint32_t lfsr_state_from_seed(uint32_t seed);

// Sign and template offset of one block, taken from bit fields of the block's
// register value (TR 23002-9 Annex B.2.2). The fields of Y, Cb and Cr are
// placed at different bit positions so that the three components of a block
// pick decorrelated offsets from a single register value.
struct BlockOffset {
    int sign = 1;  // +1 or -1
    int ox = 0;    // horizontal offset into the template
    int oy = 0;    // vertical offset into the template
};

// Luma: sign = bit 31; ox = (R[9:0]*13 >> 10)*4 (0..48); oy = (R[23:14]*12 >> 10)*4 (0..44).
BlockOffset luma_block_offset(uint32_t r);
// Cb: sign = bit 2; ox from R[19:10], oy from R[31:24] with R[1:0] as its two MSBs;
// offsets are multiplied by 4/sub instead of 4.
BlockOffset cb_block_offset(uint32_t r, int subx, int suby);
// Cr: sign = bit 15; ox from R[29:20], oy from R[13:4].
BlockOffset cr_block_offset(uint32_t r, int subx, int suby);
// Dispatch on component index 0/1/2.
BlockOffset block_offset(int component, uint32_t r, int subx, int suby);

// Block grid of the reference: 16x16 luma blocks, so ceil(width/16) blocks per
// stripe and ceil(height/16) stripes per frame.
inline int blocks_per_stripe(int luma_width) { return (luma_width + 15) / 16; }
inline int stripes_per_frame(int luma_height) { return (luma_height + 15) / 16; }

}  // namespace filmgrain::vfgs

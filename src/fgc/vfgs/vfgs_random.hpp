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

namespace detail {
// 10-bit field mapped onto `bins` bins by a multiply and shift (12 or 13 bins
// keep the distribution within ~1% of uniform, as the reference notes).
constexpr int bin_of(uint32_t field10, uint32_t bins) { return static_cast<int>((field10 * bins) >> 10); }
// 4 / sub for a subsampling factor sub of 1 or 2, without a division: the synthesis
// takes block offsets for every block of every stripe.
constexpr int offset_unit(int sub) { return 4 >> (sub - 1); }
}  // namespace detail

// Luma: sign = bit 31; ox = (R[9:0]*13 >> 10)*4 (0..48); oy = (R[23:14]*12 >> 10)*4 (0..44).
inline BlockOffset luma_block_offset(uint32_t r) {
    BlockOffset o;
    o.sign = ((r >> 31) & 1u) ? -1 : 1;
    o.ox = detail::bin_of(r & 0x3FFu, 13) * 4;
    o.oy = detail::bin_of((r >> 14) & 0x3FFu, 12) * 4;
    return o;
}
// Cb: sign = bit 2; ox from R[19:10], oy from R[31:24] with R[1:0] as its two MSBs;
// offsets are multiplied by 4/sub instead of 4 (sub = 1 or 2).
inline BlockOffset cb_block_offset(uint32_t r, int subx, int suby) {
    BlockOffset o;
    o.sign = ((r >> 2) & 1u) ? -1 : 1;
    o.ox = detail::bin_of((r >> 10) & 0x3FFu, 13) * detail::offset_unit(subx);
    const uint32_t fy = ((r >> 24) & 0xFFu) | ((r << 8) & 0x300u);
    o.oy = detail::bin_of(fy, 12) * detail::offset_unit(suby);
    return o;
}
// Cr: sign = bit 15; ox from R[29:20], oy from R[13:4].
inline BlockOffset cr_block_offset(uint32_t r, int subx, int suby) {
    BlockOffset o;
    o.sign = ((r >> 15) & 1u) ? -1 : 1;
    o.ox = detail::bin_of((r >> 20) & 0x3FFu, 13) * detail::offset_unit(subx);
    o.oy = detail::bin_of((r >> 4) & 0x3FFu, 12) * detail::offset_unit(suby);
    return o;
}
// Dispatch on component index 0/1/2.
inline BlockOffset block_offset(int component, uint32_t r, int subx, int suby) {
    if (component == 0) return luma_block_offset(r);
    if (component == 1) return cb_block_offset(r, subx, suby);
    return cr_block_offset(r, subx, suby);
}

// Block grid of the reference: 16x16 luma blocks, so ceil(width/16) blocks per
// stripe and ceil(height/16) stripes per frame.
inline int blocks_per_stripe(int luma_width) { return (luma_width + 15) / 16; }
inline int stripes_per_frame(int luma_height) { return (luma_height + 15) / 16; }

}  // namespace filmgrain::vfgs

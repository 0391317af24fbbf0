// Random state of the VFGS flavour: see vfgs_random.hpp.
#include "fgc/vfgs/vfgs_random.hpp"

namespace filmgrain::vfgs {

uint32_t lfsr_advance(uint32_t r, uint32_t n) {
    for (uint32_t i = 0; i < n; ++i) r = lfsr_next(r);
    return r;
}

uint32_t lfsr_state_from_seed(uint32_t seed) {
    // VFGS's command line treats -r 0 as "not given".
    if (seed == 0) return kDefaultLfsrState;
    return seed << 1;
}

namespace {
// 10-bit field mapped onto `bins` bins by a multiply and shift (12 or 13 bins
// keep the distribution within ~1% of uniform, as the reference notes).
constexpr int bin_of(uint32_t field10, uint32_t bins) { return static_cast<int>((field10 * bins) >> 10); }
}  // namespace

BlockOffset luma_block_offset(uint32_t r) {
    BlockOffset o;
    o.sign = ((r >> 31) & 1u) ? -1 : 1;
    o.ox = bin_of(r & 0x3FFu, 13) * 4;
    o.oy = bin_of((r >> 14) & 0x3FFu, 12) * 4;
    return o;
}

BlockOffset cb_block_offset(uint32_t r, int subx, int suby) {
    BlockOffset o;
    o.sign = ((r >> 2) & 1u) ? -1 : 1;
    o.ox = bin_of((r >> 10) & 0x3FFu, 13) * (4 / subx);
    const uint32_t fy = ((r >> 24) & 0xFFu) | ((r << 8) & 0x300u);
    o.oy = bin_of(fy, 12) * (4 / suby);
    return o;
}

BlockOffset cr_block_offset(uint32_t r, int subx, int suby) {
    BlockOffset o;
    o.sign = ((r >> 15) & 1u) ? -1 : 1;
    o.ox = bin_of((r >> 20) & 0x3FFu, 13) * (4 / subx);
    o.oy = bin_of((r >> 4) & 0x3FFu, 12) * (4 / suby);
    return o;
}

BlockOffset block_offset(int component, uint32_t r, int subx, int suby) {
    if (component == 0) return luma_block_offset(r);
    if (component == 1) return cb_block_offset(r, subx, suby);
    return cr_block_offset(r, subx, suby);
}

}  // namespace filmgrain::vfgs

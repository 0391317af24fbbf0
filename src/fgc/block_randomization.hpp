// Per-picture randomization of the FGC model (TR 23002-9 7.3.1, RDD 5 4.3): one LFSR per
// colour component, seeded from the picture offset, stepped once per 16x16 (32x32 in the
// vtm flavour's largest mode) block in raster order; each state gives the block's template
// offset and sign.
#pragma once
#include <cstdint>
#include <vector>

namespace filmgrain::fgc {

// RDD 5 colour offsets added to pic_offset before the Seed_LUT look-up. HM names 85 "Cr"
// and 170 "Cb" but assigns them to component 1 and 2 respectively; the goldens follow that.
inline constexpr int kColourOffset[3] = {0, 85, 170};

// pic_offset: RDD 5 uses POC + (idr_pic_id << 5); the vtm flavour POC alone.
uint32_t component_seed(int32_t pic_offset, int component);

struct BlockOffset {
    int x = 0;      // horizontal offset into the template (multiple of 4)
    int y = 0;      // vertical offset into the template (multiple of 8)
    int sign = 1;   // +1 or -1
};

// The offsets of a block from its LFSR state. The moduli keep a block of `block_size`
// inside the 64x64 template: 52/56 for 8 and 16 sample blocks, 36/40 for 32.
inline BlockOffset block_offset_from_state(uint32_t state, int block_size) {
    const uint32_t mod_x = block_size == 32 ? 36 : 52, mod_y = block_size == 32 ? 40 : 56;
    BlockOffset o;
    o.x = int(((state >> 16) % mod_x) & 0xFFFC);
    o.y = int(((state & 0xFFFF) % mod_y) & 0xFFF8);
    o.sign = (state & 1) ? -1 : 1;
    return o;
}

// States for every randomization block of a plane, row by row.
void fill_block_states(uint32_t seed, int blocks_x, int blocks_y, std::vector<uint32_t>& states);

}  // namespace filmgrain::fgc

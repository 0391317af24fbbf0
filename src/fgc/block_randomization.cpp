#include "fgc/block_randomization.hpp"

#include "fgc/fgc_tables.hpp"
#include "fgc/pseudo_random.hpp"

namespace filmgrain::fgc {

uint32_t component_seed(int32_t pic_offset, int component) {
    return kSeedLut[uint32_t(pic_offset + kColourOffset[component]) & 0xFF];
}

void fill_block_states(uint32_t seed, int blocks_x, int blocks_y, std::vector<uint32_t>& states) {
    states.resize(std::size_t(blocks_x) * blocks_y);
    uint32_t s = seed;
    for (auto& st : states) {
        st = s;
        s = lfsr_next(s);
    }
}

}  // namespace filmgrain::fgc

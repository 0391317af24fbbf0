#include "fgc/block_randomization.hpp"

#include "fgc/fgc_tables.hpp"
#include "fgc/pseudo_random.hpp"

namespace filmgrain::fgc {

uint32_t component_seed(int32_t pic_offset, int component) {
    // Modulo 2^32: only the low 8 bits select the entry, and every int32 picture offset is
    // legal (POC = INT32_MAX + 170 must not overflow); the low bits equal the references'
    // (POC + offset) % 256 wherever their int arithmetic does not overflow.
    return kSeedLut[(uint32_t(pic_offset) + uint32_t(kColourOffset[component])) & 0xFF];
}

void fill_block_states(uint32_t seed, int blocks_x, int blocks_y, std::vector<uint32_t>& states) {
    states.resize(std::size_t(blocks_x) * blocks_y);
    const std::size_t n = states.size();
    uint32_t s = seed;
    std::size_t i = 0;
    // the step-by-step chain is the latency of a few dependent operations per block; three
    // steps from one state cut it to a third (the two states in between are independent)
    for (; i + 3 <= n; i += 3) {
        states[i] = s;
        states[i + 1] = lfsr_next(s);
        states[i + 2] = lfsr_next2(s);
        s = lfsr_next3(s);
    }
    for (; i < n; i++) {
        states[i] = s;
        s = lfsr_next(s);
    }
}

}  // namespace filmgrain::fgc

// Where each block of a VFGS block stripe reads its template and with which sign: the
// block offsets of TR 23002-9 Annex B.2.2 (vfgs_random.hpp) for every block of a stripe,
// from the blocks' LFSR states, as the row kernels read them (GrainBlock). Each block takes
// its own offset and that of the block above (the overlap rows blend both), so a stripe
// computes two per block and component: on a Zen 3 the scalar form was a tenth of a 1080p
// 8-bit frame's synthesis once the rows ran in one pass.
//
// A scalar reference (vfgs_block_grains_scalar.cpp, from block_offset()) and a Highway twin
// (beside the row kernels' in simd/vfgs_kernels_hwy.cpp) that
// tests/fgc/vfgs/vfgs_block_grains_test.cpp proves equal on random states for every
// compiled target.
#pragma once
#include <cstdint>

#include "fgc/vfgs/vfgs_row_kernels.hpp"

namespace filmgrain::vfgs {

// What block_grains() computes: `count` blocks of component `component` (0 Y, 1 Cb, 2 Cr)
// with subsampling factors subx, suby (1 or 2), block b from states[b] and the block above
// from states_up[b] (pass `states` again where there is no block above).
struct BlockGrainsJob {
    int component = 0;
    int subx = 1, suby = 1;
    const uint32_t* states = nullptr;
    const uint32_t* states_up = nullptr;
    int count = 0;
};

namespace scalar {
void block_grains(const BlockGrainsJob& job, GrainBlock* out);
}
namespace simd {
void block_grains(const BlockGrainsJob& job, GrainBlock* out);
}

}  // namespace filmgrain::vfgs

// Where every block stripe of a frame starts in the VFGS random sequence.
//
// The reference steps its one LFSR once per block, left to right, stripe after stripe,
// and a stripe's overlap rows re-walk the states of the stripe above. Here the starting
// state of every stripe is computed before the stripes run (one jump of a stripe's block
// count per stripe), so that a stripe needs nothing from the stripes above it.
#pragma once
#include <cstdint>
#include <vector>

#include "fgc/vfgs/vfgs_lfsr_jump.hpp"
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"

namespace filmgrain::vfgs {

// `starts` becomes stripes + 1 states: [0] the stripe above stripe 0 (the cursor's
// upper; stripe 0 has no overlap, so it is never read), [k + 1] stripe k's first block.
// `stripe_step` is LfsrJump(blocks per stripe). The cursor moves where add_grain_frame()
// leaves it: the last stripe's state and the one above (the next frame's first stripe
// starts from the last stripe's state again, as in the reference).
void plan_stripe_states(LfsrCursor& cursor, int stripes, const LfsrJump& stripe_step, std::vector<uint32_t>& starts);

// The state of each of `blocks` blocks from the stripe's first state: one step per block.
void fill_block_states(uint32_t first, int blocks, uint32_t* states);

}  // namespace filmgrain::vfgs

// Stripe starting states: see vfgs_stripe_states.hpp.
#include "fgc/vfgs/vfgs_stripe_states.hpp"

#include "fgc/vfgs/vfgs_random.hpp"

namespace filmgrain::vfgs {

void plan_stripe_states(LfsrCursor& cursor, int stripes, const LfsrJump& stripe_step, std::vector<uint32_t>& starts) {
    starts.resize(static_cast<size_t>(stripes) + 1);
    starts[0] = cursor.upper;
    starts[1] = cursor.stripe;
    for (int k = 1; k < stripes; ++k) starts[static_cast<size_t>(k) + 1] = stripe_step.apply(starts[static_cast<size_t>(k)]);
    if (stripes > 1) cursor = LfsrCursor{starts[static_cast<size_t>(stripes)], starts[static_cast<size_t>(stripes) - 1]};
}

void fill_block_states(uint32_t first, int blocks, uint32_t* states) {
    for (int b = 0; b < blocks; ++b) {
        states[b] = first;
        first = lfsr_next(first);
    }
}

}  // namespace filmgrain::vfgs

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

}  // namespace filmgrain::vfgs

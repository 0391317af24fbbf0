// Jump-ahead of the VFGS LFSR: see vfgs_lfsr_jump.hpp.
#include "fgc/vfgs/vfgs_lfsr_jump.hpp"

#include "fgc/vfgs/vfgs_random.hpp"

namespace filmgrain::vfgs {

LfsrJump LfsrJump::then(const LfsrJump& after) const {
    LfsrJump m;
    for (std::size_t i = 0; i < 32; ++i) m.column_[i] = after.apply(column_[i]);
    return m;
}

LfsrJump::LfsrJump(uint64_t steps) {
    for (int i = 0; i < 32; ++i) column_[static_cast<std::size_t>(i)] = 1u << i;  // identity
    LfsrJump power;  // one step, then squared: the map of 2^b steps at bit b
    for (int i = 0; i < 32; ++i) power.column_[static_cast<std::size_t>(i)] = lfsr_next(1u << i);
    for (; steps; steps >>= 1) {
        if (steps & 1u) *this = then(power);  // powers of one map commute: order is free
        if (steps > 1) power = power.then(power);
    }
}

}  // namespace filmgrain::vfgs

// Scalar reference of block_grains() (vfgs_block_grains.hpp): block_offset() per block.
#include "fgc/vfgs/vfgs_block_grains.hpp"

#include "fgc/vfgs/vfgs_random.hpp"

namespace filmgrain::vfgs::scalar {

void block_grains(const BlockGrainsJob& job, GrainBlock* out) {
    for (int b = 0; b < job.count; ++b) {
        const BlockOffset o = block_offset(job.component, job.states[b], job.subx, job.suby);
        const BlockOffset u = block_offset(job.component, job.states_up[b], job.subx, job.suby);
        out[b].offset = o.oy * kTemplatePitch + o.ox;
        out[b].offset_up = u.oy * kTemplatePitch + u.ox;
        out[b].sign = o.sign;
        out[b].sign_up = u.sign;
    }
}

}  // namespace filmgrain::vfgs::scalar

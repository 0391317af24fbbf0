// The VFGS synthesis of one frame on a pool of stripe threads, with the vector kernels.
//
// The output is add_grain_frame()'s (the serial reference of vfgs_picture_synthesis.cpp)
// for every thread count and every kernel choice: each 16-row block stripe starts from
// its own LFSR state (vfgs_stripe_states.hpp) and reads nothing but its own rows, so the
// stripes can run in any order.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/kernels.hpp"
#include "fgc/vfgs/vfgs_lfsr_jump.hpp"
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "fgc/vfgs/vfgs_row_kernels.hpp"

namespace filmgrain {
class ThreadPool;
}

namespace filmgrain::vfgs {

// Kernels (core/kernels.hpp): kReference the scalar row kernels; kOptimized the Highway row
// kernels where they apply (no pattern interpolation, at most kMaxVectorRuns runs in a
// component's tables), scalar elsewhere.
using filmgrain::Kernels;

class FrameSynthesis {
public:
    // threads: stripe workers including the caller (0 = every hardware thread).
    explicit FrameSynthesis(int threads = 1, Kernels kernels = Kernels::kOptimized);
    ~FrameSynthesis();
    FrameSynthesis(const FrameSynthesis&) = delete;
    FrameSynthesis& operator=(const FrameSynthesis&) = delete;

    int threads() const;

    // As add_grain_frame(): grain on src into dst (which may alias src), the cursor moved
    // past the frame.
    void apply(const FrameView& src, const FrameView& dst, const SynthesisSetup& setup, LfsrCursor& cursor);
    // The cursor moved past a frame of this luma size as apply() moves it, without synthesis.
    void skip(int luma_width, int luma_height, LfsrCursor& cursor);

    // One worker's buffers, sized on the calling thread for the frame and reused.
    struct Scratch {
        std::vector<uint32_t> states_cur, states_up;  // the stripe's and the stripe above's blocks
        std::vector<GrainBlock> blocks;               // one component's blocks of the stripe
        std::vector<uint16_t> in;                     // a last block that sticks out of the row, padded
        std::vector<int16_t> grain, scale;
    };

private:
    // Every stripe's starting state into stripe_starts_, the cursor past the frame.
    void plan_stripes(int luma_width, int luma_height, LfsrCursor& cursor);

    std::unique_ptr<ThreadPool> pool_;
    Kernels kernels_;
    std::vector<Scratch> scratch_;
    std::vector<uint32_t> stripe_starts_;
    // The jump of one stripe's blocks, made when the picture width changes, not per frame.
    int stripe_step_blocks_ = -1;
    LfsrJump stripe_step_{0};
};

}  // namespace filmgrain::vfgs

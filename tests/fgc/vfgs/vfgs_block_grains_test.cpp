// block_grains() (vfgs_block_grains.hpp): the Highway twin against the scalar reference on
// random LFSR states for every vector target this CPU runs, and the scalar reference
// against hand-worked bit fields of Annex B.2.2, so that a wrong field position fails here
// and not only in the goldens.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/simd_targets.hpp"
#include "fgc/vfgs/vfgs_block_grains.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

bool operator==(const GrainBlock& a, const GrainBlock& b) {
    return a.offset == b.offset && a.offset_up == b.offset_up && a.sign == b.sign && a.sign_up == b.sign_up;
}

// Y: sign bit 31, ox from R[9:0] in 13 bins of 4, oy from R[23:14] in 12 bins of 4.
// Cb: sign bit 2, ox from R[19:10], oy from R[31:24] with R[1:0] on top, units 4 / sub.
// Cr: sign bit 15, ox from R[29:20], oy from R[13:4].
TEST(VfgsBlockGrains, ScalarFieldsAsAnnexB) {
    const uint32_t states[2] = {0x80000000u | (1023u << 14) | 1023u, 0x00000000u};
    BlockGrainsJob job;
    job.states = states;
    job.states_up = states + 1;
    job.count = 1;
    GrainBlock g;
    vfgs::scalar::block_grains(job, &g);
    EXPECT_EQ(g.sign, -1);
    EXPECT_EQ(g.offset, (1023 * 12 >> 10) * 4 * 64 + (1023 * 13 >> 10) * 4);  // oy 44, ox 48
    EXPECT_EQ(g.sign_up, 1);
    EXPECT_EQ(g.offset_up, 0);

    // Cb at 4:2:0: R[1:0] = 3 and R[31:24] = 0 give the vertical field 0x300.
    const uint32_t cb[2] = {0x3u | (0x4u) | (512u << 10), 0xFF000000u};
    job.component = 1;
    job.subx = job.suby = 2;
    job.states = cb;
    job.states_up = cb + 1;
    vfgs::scalar::block_grains(job, &g);
    EXPECT_EQ(g.sign, -1);
    EXPECT_EQ(g.offset, (0x300 * 12 >> 10) * 2 * 64 + (512 * 13 >> 10) * 2);
    EXPECT_EQ(g.sign_up, 1);
    EXPECT_EQ(g.offset_up, (0xFF * 12 >> 10) * 2 * 64);

    const uint32_t cr[2] = {(1u << 15) | (700u << 20) | (300u << 4), 0u};
    job.component = 2;
    job.subx = 2;
    job.suby = 1;
    job.states = cr;
    job.states_up = cr + 1;
    vfgs::scalar::block_grains(job, &g);
    EXPECT_EQ(g.sign, -1);
    EXPECT_EQ(g.offset, (300 * 12 >> 10) * 4 * 64 + (700 * 13 >> 10) * 2);
}

class VfgsBlockGrainsEquivalence : public test_support::ForcedSimdTarget<20261128u> {};

TEST_P(VfgsBlockGrainsEquivalence, EqualsScalarOnRandomStates) {
    for (int iter = 0; iter < 400; ++iter) {
        const int count = uniform(0, 3) ? uniform(1, 40) : uniform(41, 300);
        std::vector<uint32_t> states(static_cast<size_t>(count)), up(static_cast<size_t>(count));
        for (auto& s : states) s = std::uniform_int_distribution<uint32_t>()(rng);
        for (auto& s : up) s = std::uniform_int_distribution<uint32_t>()(rng);
        BlockGrainsJob job;
        job.component = uniform(0, 2);
        job.subx = job.component ? uniform(1, 2) : 1;
        job.suby = job.component ? uniform(1, 2) : 1;
        job.states = states.data();
        job.states_up = up.data();
        job.count = count;
        // one block past the count, which neither may write
        std::vector<GrainBlock> want(static_cast<size_t>(count) + 1, GrainBlock{7, 7, 7, 7}), got(want);
        vfgs::scalar::block_grains(job, want.data());
        vfgs::simd::block_grains(job, got.data());
        for (int b = 0; b <= count; ++b)
            ASSERT_TRUE(got[static_cast<size_t>(b)] == want[static_cast<size_t>(b)])
                << "iteration " << iter << " component " << job.component << " block " << b << " of " << count
                << ": offset " << got[static_cast<size_t>(b)].offset << " want " << want[static_cast<size_t>(b)].offset;
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, VfgsBlockGrainsEquivalence, ::testing::ValuesIn(filmgrain::simd::available_targets()),
                         [](const ::testing::TestParamInfo<filmgrain::simd::Target>& i) { return i.param.name; });

}  // namespace

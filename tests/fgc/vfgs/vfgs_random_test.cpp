// VFGS random state (TR 23002-9 clause 7.5 / Annex B.2.2): the bit-reversed RDD 5
// LFSR, seeding, block bit fields and the stripe/frame state progression.
#include <gtest/gtest.h>

#include <set>

#include "core/frame_buffer.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "filmgrain/vfgs.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

uint32_t bit_reverse(uint32_t x) {
    uint32_t r = 0;
    for (int i = 0; i < 32; ++i) r |= ((x >> i) & 1u) << (31 - i);
    return r;
}

// The RDD 5 generator: x' = (x << 1) | (bit30(x) ^ bit2(x)).
uint32_t rdd5_next(uint32_t x) { return (x << 1) | (((x >> 30) ^ (x >> 2)) & 1u); }

}  // namespace

TEST(VfgsRandom, KnownSequenceFromDefaultState) {
    uint32_t r = kDefaultLfsrState;
    const uint32_t expected[] = {0xEF56DF77u, 0x77AB6FBBu, 0x3BD5B7DDu, 0x9DEADBEEu, 0xCEF56DF7u};
    for (uint32_t e : expected) {
        r = lfsr_next(r);
        EXPECT_EQ(r, e);
    }
    EXPECT_EQ(lfsr_advance(0xC6u, 1000), 0xD7CB6996u);
    EXPECT_EQ(lfsr_advance(0x12345678u, 0), 0x12345678u);
}

TEST(VfgsRandom, IsTheBitReversedRdd5Generator) {
    uint32_t r = 0x0BADF00Du;
    for (int i = 0; i < 10000; ++i) {
        // The low bit of the reversed register (bit 0 here) is never fed back,
        // so compare the 31 bits the RDD 5 register keeps.
        EXPECT_EQ(bit_reverse(lfsr_next(r)) & ~1u, rdd5_next(bit_reverse(r)) & ~1u) << i;
        r = lfsr_next(r);
    }
}

TEST(VfgsRandom, SeedLoading) {
    EXPECT_EQ(lfsr_state_from_seed(99), 0xC6u);            // vfgs-multicfg-420p8 vfgs_lfsr_init
    EXPECT_EQ(lfsr_state_from_seed(987654), 0x001E240Cu);  // vfgs-ff-420p10-200x136
    EXPECT_EQ(lfsr_state_from_seed(0x80000001u), 2u);      // mod 2^32
    EXPECT_EQ(lfsr_state_from_seed(0), kDefaultLfsrState); // -r 0 = no seed
    EXPECT_EQ(Synthesizer(Options{}).lfsr_state(), 0xDEADBEEFu);
    Options o;
    o.seed = 31;
    EXPECT_EQ(Synthesizer(o).lfsr_state(), 0x3Eu);
}

TEST(VfgsRandom, LumaBitFields) {
    // sign = bit 31, ox from bits 0..9 (13 bins, *4), oy from bits 14..23 (12 bins, *4)
    EXPECT_EQ(luma_block_offset(0).sign, 1);
    EXPECT_EQ(luma_block_offset(0x80000000u).sign, -1);
    EXPECT_EQ(luma_block_offset(0x3FFu).ox, 48);
    EXPECT_EQ(luma_block_offset(0x3FFu).oy, 0);
    EXPECT_EQ(luma_block_offset(0x3FFu << 14).oy, 44);
    EXPECT_EQ(luma_block_offset(0x3FFu << 14).ox, 0);
    EXPECT_EQ(luma_block_offset(512).ox, ((512 * 13) >> 10) * 4);  // 6*4
}

TEST(VfgsRandom, ChromaBitFields) {
    // Cb: sign = bit 2; ox from bits 10..19; oy from bits 24..31 with bits 0..1 on top.
    EXPECT_EQ(cb_block_offset(0x4u, 2, 2).sign, -1);
    EXPECT_EQ(cb_block_offset(0x3FFu << 10, 2, 2).ox, 24);
    EXPECT_EQ(cb_block_offset(0x3u, 2, 2).oy, ((0x300 * 12) >> 10) * 2);  // 18
    EXPECT_EQ(cb_block_offset(0xFF000000u, 2, 2).oy, ((0xFF * 12) >> 10) * 2);  // 4
    EXPECT_EQ(cb_block_offset(0xFF000003u, 2, 2).oy, 22);
    // Cr: sign = bit 15; ox from bits 20..29; oy from bits 4..13.
    EXPECT_EQ(cr_block_offset(0x8000u, 2, 2).sign, -1);
    EXPECT_EQ(cr_block_offset(0x3FFu << 20, 2, 2).ox, 24);
    EXPECT_EQ(cr_block_offset(0x3FFu << 4, 2, 2).oy, 22);
    // Non-subsampled chroma multiplies by 4 like luma.
    EXPECT_EQ(cr_block_offset(0x3FFu << 20, 1, 1).ox, 48);
}

TEST(VfgsRandom, OffsetsStayInsideTheTemplates) {
    std::set<int> lx, ly, cx, cy;
    uint32_t r = 0x12345678u;
    for (int i = 0; i < 200000; ++i) {
        const auto l = luma_block_offset(r);
        lx.insert(l.ox);
        ly.insert(l.oy);
        for (int c = 1; c < 3; ++c) {
            const auto o = block_offset(c, r, 2, 2);
            cx.insert(o.ox);
            cy.insert(o.oy);
        }
        r = lfsr_next(r);
    }
    EXPECT_EQ(lx.size(), 13u);
    EXPECT_EQ(ly.size(), 12u);
    EXPECT_EQ(*lx.rbegin() + 16, 64);  // a 16-wide block ends at the template edge
    EXPECT_LE(*ly.rbegin() + 16 + 1, 63);  // the block above is read at rows 16 and 17
    EXPECT_EQ(cx.size(), 13u);
    EXPECT_EQ(*cx.rbegin() + 8, 32);
    EXPECT_LE(*cy.rbegin() + 8, 31);  // 4:2:0 chroma overlap reads row 8 of the block above
}

TEST(VfgsRandom, StateAdvancesByStripesAcrossFrames) {
    // W = 256 -> 16 blocks per stripe; H = 144 -> 9 stripes. Each frame moves the
    // state by (9 - 1) stripes: the last stripe of a frame and the first of the
    // next share a state. A new parameter set does not reseed.
    Options o;
    o.seed = 7;
    Synthesizer s(o);
    FgcParams p;
    p.log2_scale_factor = 5;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 0;
    p.comp[0].intervals.push_back({0, 255, {50, 0, 0, 0, 0, 0}});
    s.set_params(p);
    FrameBuffer f(256, 144, {ChromaFormat::k420, 8});
    const uint32_t r0 = lfsr_state_from_seed(7);
    s.apply(f.view(), f.view());
    EXPECT_EQ(s.lfsr_state(), lfsr_advance(r0, 8 * 16));
    s.set_params(p);
    s.apply(f.view(), f.view());
    EXPECT_EQ(s.lfsr_state(), lfsr_advance(r0, 2 * 8 * 16));
    // Partial blocks and stripes count as whole ones: 200x136 -> 13 blocks, 9 stripes.
    Synthesizer s2(o);
    s2.set_params(p);
    FrameBuffer g(200, 136, {ChromaFormat::k420, 8});
    s2.apply(g.view(), g.view());
    EXPECT_EQ(s2.lfsr_state(), lfsr_advance(r0, 8 * 13));
}

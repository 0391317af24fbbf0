// Checkasm-style equivalence of the VFGS row kernels (vfgs_row_kernels.hpp): the Highway
// twins against the scalar references on random input, for every vector target this CPU
// runs (each forced in turn). Random tables with 1 to kMaxVectorRuns runs (the kernels
// specialise 1..4), template offsets over the whole pool, both block widths, every
// overlap weight pair, samples above the bit depth, and grain, scales and shifts at their
// extremes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "core/simd_targets.hpp"
#include "hwy/targets.h"
#include "fgc/vfgs/vfgs_intensity_runs.hpp"
#include "fgc/vfgs/vfgs_row_kernels.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

class VfgsSimdEquivalence : public test_support::ForcedSimdTarget<20261125u> {};

// Tables with `runs` random breakpoints (fewer when two coincide).
ComponentLuts random_luts(std::mt19937& rng, int runs) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    ComponentLuts lut;
    std::vector<int> starts = {0};
    for (int r = 1; r < runs; ++r) starts.push_back(uniform(1, 255));
    std::sort(starts.begin(), starts.end());
    for (size_t r = 0; r < starts.size(); ++r) {
        const int t = uniform(0, kMaxTemplates - 1);
        const int s = uniform(0, 3) == 0 ? 0 : uniform(0, 3) == 0 ? 255 : uniform(1, 255);
        for (int i = starts[r]; i < 256; ++i) {
            lut.tmpl[static_cast<size_t>(i)] = static_cast<uint8_t>(t);
            lut.scale[static_cast<size_t>(i)] = static_cast<uint8_t>(s);
        }
    }
    return lut;
}

// A row job of `block_count` blocks of either width, with any overlap weights, reading
// random template rows of `pool`; its blocks come from random_blocks().
GrainRowJob random_grain_job(std::mt19937& rng, const std::vector<int8_t>& pool, const ComponentLuts& lut,
                             const IntensityRuns& runs, int block_count) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    GrainRowJob job;
    job.block_width = uniform(0, 1) ? 16 : 8;
    job.block_count = block_count;
    const int weights[4][2] = {{0, 0}, {12, 24}, {24, 12}, {20, 20}};
    const int w = uniform(0, 3);
    job.overlap_c1 = weights[w][0];
    job.overlap_c2 = weights[w][1];
    job.pool = pool.data() + uniform(0, 63) * kTemplatePitch;
    job.pool_up = pool.data() + uniform(0, 63) * kTemplatePitch;
    job.luts = &lut;
    job.runs = &runs;
    return job;
}

// Template places anywhere below the job's rows in `pool`, and random signs.
std::vector<GrainBlock> random_blocks(std::mt19937& rng, const std::vector<int8_t>& pool, const GrainRowJob& job) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    const int row = static_cast<int>((job.pool - pool.data()) / kTemplatePitch);
    const int row_up = static_cast<int>((job.pool_up - pool.data()) / kTemplatePitch);
    std::vector<GrainBlock> blocks(static_cast<size_t>(job.block_count));
    for (auto& b : blocks) {
        b.offset = uniform(0, 63 - row) * kTemplatePitch + uniform(0, kTemplatePitch - job.block_width);
        b.offset_up = uniform(0, 63 - row_up) * kTemplatePitch + uniform(0, kTemplatePitch - job.block_width);
        b.sign = uniform(0, 1) ? 1 : -1;
        b.sign_up = uniform(0, 1) ? 1 : -1;
    }
    return blocks;
}

template <typename In>
void check_grain_rows(std::mt19937& rng, int iterations) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    std::vector<int8_t> pool(static_cast<size_t>(kTemplateBytes) * kMaxTemplates);
    for (int iter = 0; iter < iterations; ++iter) {
        for (auto& v : pool) v = static_cast<int8_t>(uniform(0, 9) == 0 ? (uniform(0, 1) ? 127 : -127) : uniform(-127, 127));
        const ComponentLuts lut = random_luts(rng, uniform(0, 1) ? uniform(1, 5) : uniform(6, kMaxVectorRuns));
        const IntensityRuns runs = intensity_runs(lut);
        ASSERT_LE(runs.count, kMaxVectorRuns);
        GrainRowJob job = random_grain_job(rng, pool, lut, runs, uniform(1, 30));
        job.intensity_shift = sizeof(In) == 1 ? 0 : 2;
        std::vector<GrainBlock> blocks = random_blocks(rng, pool, job);
        job.blocks = blocks.data();
        const size_t n = static_cast<size_t>(job.block_count * job.block_width);
        std::vector<In> in(n);
        const int top = sizeof(In) == 1 ? 255 : uniform(0, 3) == 0 ? 65535 : 1023;  // above 10 bits too
        for (auto& v : in) v = static_cast<In>(uniform(0, top));
        std::vector<int16_t> want_g(n + 1, 0x5A5A), want_s(n + 1, 0x5A5A), got_g(want_g), got_s(want_s);
        if constexpr (sizeof(In) == 1) {
            vfgs::scalar::grain_row_u8(job, in.data(), want_g.data(), want_s.data());
            vfgs::simd::grain_row_u8(job, in.data(), got_g.data(), got_s.data());
        } else {
            vfgs::scalar::grain_row_u16(job, in.data(), want_g.data(), want_s.data());
            vfgs::simd::grain_row_u16(job, in.data(), got_g.data(), got_s.data());
        }
        ASSERT_EQ(got_g, want_g) << "iteration " << iter << " blocks " << job.block_count << "x" << job.block_width
                                 << " runs " << runs.count << " overlap " << job.overlap_c1;
        ASSERT_EQ(got_s, want_s) << "iteration " << iter;
    }
}

TEST_P(VfgsSimdEquivalence, GrainRow8Bit) { check_grain_rows<uint8_t>(rng, 600); }

// The grain range the 10-bit blends rely on (kMaxBlendGrain): the reference's grain row at
// its extremes, every template sample at +-127 with the heaviest overlap (20, 20), is
// +-199 (159 after the overlap, times 5 / 4 at the deblocked edges) and no more.
TEST(VfgsGrainRange, ExtremesStayWithinTheBlendRange) {
    for (const int v : {127, -127}) {
        const std::vector<int8_t> pool(static_cast<size_t>(kTemplateBytes) * kMaxTemplates, static_cast<int8_t>(v));
        ComponentLuts lut;
        lut.tmpl.fill(0);
        lut.scale.fill(255);
        const IntensityRuns runs = intensity_runs(lut);
        GrainRowJob job;
        job.block_width = 16;
        job.block_count = 4;
        job.overlap_c1 = job.overlap_c2 = 20;
        job.pool = job.pool_up = pool.data();
        job.luts = &lut;
        job.runs = &runs;
        const std::vector<GrainBlock> blocks(static_cast<size_t>(job.block_count));
        job.blocks = blocks.data();
        const std::vector<uint16_t> in(64, 512);
        std::vector<int16_t> grain(64), scale(64);
        vfgs::scalar::grain_row_u16(job, in.data(), grain.data(), scale.data());
        const auto [lo, hi] = std::minmax_element(grain.begin(), grain.end());
        EXPECT_EQ(v > 0 ? *hi : -*lo, 199) << v;
        EXPECT_EQ(v > 0 ? *lo : -*hi, 159) << v;  // the samples away from the edges
        EXPECT_LE(199, kMaxBlendGrain);
    }
}

// grain_blend_row_u8 (_u16, _u16_to_u8) against scalar::grain_row_u8 then
// scalar::blend_row_u8 (grain_row_u16 then blend_row_u16, blend_row_u16_to_u8). It runs on
// every 256-bit target and row of whole vectors (and must run there: the count of fused rows
// is checked), and leaves the output alone where it declines.
template <typename In, typename Out>
void check_grain_blend_rows(std::mt19937& rng, bool fusing_target, int iterations) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    constexpr bool k8Bit = sizeof(In) == 1;
    std::vector<int8_t> pool(static_cast<size_t>(kTemplateBytes) * kMaxTemplates);
    int fused = 0, eligible = 0;
    for (int iter = 0; iter < iterations; ++iter) {
        for (auto& v : pool) v = static_cast<int8_t>(uniform(0, 9) == 0 ? (uniform(0, 1) ? 127 : -127) : uniform(-127, 127));
        const ComponentLuts lut = random_luts(rng, uniform(0, 1) ? uniform(1, 5) : uniform(6, kMaxVectorRuns));
        const IntensityRuns runs = intensity_runs(lut);
        GrainRowJob job = random_grain_job(rng, pool, lut, runs, uniform(0, 3) ? 2 * uniform(1, 15) : uniform(1, 30));
        job.intensity_shift = k8Bit ? 0 : 2;
        std::vector<GrainBlock> blocks = random_blocks(rng, pool, job);
        job.blocks = blocks.data();
        BlendRowJob blend;
        blend.width = job.block_count * job.block_width;
        blend.bit_depth = k8Bit ? 8 : 10;
        // scale_shift()'s range (8..13, 6..11), and now and then the rest of what the kernel takes
        blend.shift = uniform(0, 9) == 0 ? uniform(k8Bit ? 14 : 12, 15) : uniform(k8Bit ? 8 : 6, k8Bit ? 13 : 11);
        const size_t n = static_cast<size_t>(blend.width);
        const int top = k8Bit ? 255 : uniform(0, 3) == 0 ? 65535 : 1023;  // above 10 bits too
        std::vector<In> in(n);
        for (auto& v : in) v = static_cast<In>(uniform(0, 3) == 0 ? top * uniform(0, 1) : uniform(0, top));
        std::vector<int16_t> grain(n), scale(n);
        const Out fill = static_cast<Out>(0xA5A5);
        std::vector<Out> want(n + 1, fill), got(want);
        if constexpr (k8Bit) {
            vfgs::scalar::grain_row_u8(job, in.data(), grain.data(), scale.data());
            vfgs::scalar::blend_row_u8(blend, in.data(), grain.data(), scale.data(), want.data());
        } else {
            vfgs::scalar::grain_row_u16(job, in.data(), grain.data(), scale.data());
            if constexpr (sizeof(Out) == 1)
                vfgs::scalar::blend_row_u16_to_u8(blend, in.data(), grain.data(), scale.data(), want.data());
            else
                vfgs::scalar::blend_row_u16(blend, in.data(), grain.data(), scale.data(), want.data());
        }
        const auto fuse = [&](const In* from, Out* to) {
            if constexpr (k8Bit) return vfgs::simd::grain_blend_row_u8(job, blend, from, to);
            else if constexpr (sizeof(Out) == 1) return vfgs::simd::grain_blend_row_u16_to_u8(job, blend, from, to);
            else return vfgs::simd::grain_blend_row_u16(job, blend, from, to);
        };
        const bool whole_vectors = n % 16 == 0;
        eligible += whole_vectors;
        const std::string what = "iteration " + std::to_string(iter) + " blocks " + std::to_string(job.block_count) + "x" +
                                 std::to_string(job.block_width) + " runs " + std::to_string(runs.count) + " overlap " +
                                 std::to_string(job.overlap_c1) + " shift " + std::to_string(blend.shift);
        if (!fuse(in.data(), got.data())) {
            ASSERT_FALSE(fusing_target && whole_vectors) << what;
            ASSERT_EQ(got, std::vector<Out>(n + 1, fill)) << what;
            continue;
        }
        ++fused;
        ASSERT_EQ(got, want) << what;
        if constexpr (std::is_same_v<In, Out>) {
            std::vector<In> inplace(in);  // out == in
            ASSERT_TRUE(fuse(inplace.data(), inplace.data()));
            inplace.push_back(fill);
            ASSERT_EQ(inplace, want) << what;
        }
    }
    if (fusing_target) EXPECT_EQ(fused, eligible);
    else EXPECT_EQ(fused, 0);
    EXPECT_GT(eligible, iterations * 2 / 3);
}

TEST_P(VfgsSimdEquivalence, GrainBlendRow8Bit) {
    check_grain_blend_rows<uint8_t, uint8_t>(rng, GetParam().bits <= HWY_AVX2, 1500);
}
TEST_P(VfgsSimdEquivalence, GrainBlendRow10Bit) {
    check_grain_blend_rows<uint16_t, uint16_t>(rng, GetParam().bits <= HWY_AVX2, 1500);
}
TEST_P(VfgsSimdEquivalence, GrainBlendRow10BitTo8Bit) {
    check_grain_blend_rows<uint16_t, uint8_t>(rng, GetParam().bits <= HWY_AVX2, 1000);
}
TEST_P(VfgsSimdEquivalence, GrainRow10Bit) { check_grain_rows<uint16_t>(rng, 600); }

// kind 0: u8 -> u8, 1: u16 -> u16, 2: u16 -> u8 (--outdepth 8)
void check_blend_rows(std::mt19937& rng, int kind, int iterations) {
    auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int iter = 0; iter < iterations; ++iter) {
        BlendRowJob job;
        job.width = uniform(0, 3) ? uniform(1, 300) : 16 * uniform(1, 20);
        job.bit_depth = kind == 0 ? 8 : 10;
        // scale_shift()'s range, and now and then any shift (the kernels' other forms)
        job.shift = uniform(0, 9) == 0 ? uniform(1, 15) : uniform(job.bit_depth == 8 ? 8 : 6, job.bit_depth == 8 ? 13 : 11);
        const size_t n = static_cast<size_t>(job.width);
        std::vector<int16_t> grain(n), scale(n);
        // beyond the synthesis' range (199) too: any int16 at 8 bits, up to the contract's
        // kMaxBlendGrain above
        const int gmax = uniform(0, 3) == 0 ? (kind == 0 ? 32767 : kMaxBlendGrain) : 199;
        for (auto& g : grain) g = static_cast<int16_t>(uniform(0, 7) == 0 ? (uniform(0, 1) ? gmax : -gmax) : uniform(-gmax, gmax));
        for (auto& s : scale) s = static_cast<int16_t>(uniform(0, 5) == 0 ? 255 * uniform(0, 1) : uniform(0, 255));
        const int16_t* g = grain.data();
        const int top = kind == 0 ? 255 : uniform(0, 3) == 0 ? 65535 : 1023;
        std::vector<uint16_t> in(n);
        for (auto& v : in) v = static_cast<uint16_t>(uniform(0, 3) == 0 ? top * uniform(0, 1) : uniform(0, top));
        const std::string what = "iteration " + std::to_string(iter) + " width " + std::to_string(job.width) + " shift " +
                                 std::to_string(job.shift);
        if (kind == 0) {
            const std::vector<uint8_t> in8(in.begin(), in.end());
            std::vector<uint8_t> want(n + 1, 0xA5), got(want);
            vfgs::scalar::blend_row_u8(job, in8.data(), g, scale.data(), want.data());
            vfgs::simd::blend_row_u8(job, in8.data(), g, scale.data(), got.data());
            ASSERT_EQ(got, want) << what;
            std::vector<uint8_t> inplace(in8);  // out == in, as the synthesis' in-place frames
            vfgs::simd::blend_row_u8(job, inplace.data(), g, scale.data(), inplace.data());
            inplace.push_back(0xA5);
            ASSERT_EQ(inplace.size(), want.size());
            for (int x = 0; x < job.width; ++x) ASSERT_EQ(inplace[static_cast<size_t>(x)], want[static_cast<size_t>(x)]) << what;
        } else if (kind == 1) {
            std::vector<uint16_t> want(n + 1, 0xA5A5), got(want);
            vfgs::scalar::blend_row_u16(job, in.data(), g, scale.data(), want.data());
            vfgs::simd::blend_row_u16(job, in.data(), g, scale.data(), got.data());
            ASSERT_EQ(got, want) << what;
        } else {
            std::vector<uint8_t> want(n + 1, 0xA5), got(want);
            vfgs::scalar::blend_row_u16_to_u8(job, in.data(), g, scale.data(), want.data());
            vfgs::simd::blend_row_u16_to_u8(job, in.data(), g, scale.data(), got.data());
            ASSERT_EQ(got, want) << what;
        }
    }
}

TEST_P(VfgsSimdEquivalence, BlendRow8Bit) { check_blend_rows(rng, 0, 1500); }
TEST_P(VfgsSimdEquivalence, BlendRow10Bit) { check_blend_rows(rng, 1, 1500); }
TEST_P(VfgsSimdEquivalence, BlendRow10BitTo8Bit) { check_blend_rows(rng, 2, 1500); }

INSTANTIATE_TEST_SUITE_P(Targets, VfgsSimdEquivalence, ::testing::ValuesIn(filmgrain::simd::available_targets()),
                         [](const ::testing::TestParamInfo<filmgrain::simd::Target>& i) { return i.param.name; });

}  // namespace

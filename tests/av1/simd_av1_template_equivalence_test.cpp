// Checkasm-style equivalence of the optimized AV1 grain templates
// (grain_template_optimized: batched Gaussian fill + vector AR filter) with the scalar
// reference of 7.18.3.3 (one plane at a time and Cb/Cr together), for every vector target this CPU runs (each forced in turn):
// every lag, ar_coeff_shift, grain_scale_shift, bit depth and subsampling, with and
// without luma grain, with chroma_scaling_from_luma, and coefficients over their whole
// range (so the clipping to the grain range is exercised). Any difference is reported with
// its plane and position.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "av1/grain_template_generation.hpp"
#include "av1/grain_template_optimized.hpp"
#include "core/simd_targets.hpp"
#include "forced_simd_target.hpp"

using namespace filmgrain;

namespace {

class SimdAv1TemplateEquivalence : public test_support::ForcedSimdTarget<20261123u> {};

// First differing sample, or "" when the templates are equal.
std::string diff(const av1::GrainTemplate& got, const av1::GrainTemplate& want) {
    if (got.width != want.width || got.height != want.height)
        return "size " + std::to_string(got.width) + "x" + std::to_string(got.height) + " vs " +
               std::to_string(want.width) + "x" + std::to_string(want.height);
    for (int y = 0; y < want.height; y++)
        for (int x = 0; x < want.width; x++)
            if (got.at(y, x) != want.at(y, x))
                return "row " + std::to_string(y) + " column " + std::to_string(x) + ": " +
                       std::to_string(got.at(y, x)) + " vs " + std::to_string(want.at(y, x));
    return "";
}

// Coefficients near zero keep the filter stable (typical encoder output); over the whole
// range they drive many samples into the clip.
int random_coefficient(std::mt19937& rng, bool extreme) {
    return std::uniform_int_distribution<int>(extreme ? 0 : 96, extreme ? 255 : 160)(rng);
}

TEST_P(SimdAv1TemplateEquivalence, LumaAndChromaTemplates) {
    const int subsamplings[4][2] = {{1, 1}, {1, 0}, {0, 0}, {0, 1}};
    int counts[4] = {0, 0, 0, 0};  // per lag, to show every lag was covered
    int with_luma_term = 0, without_luma_term = 0;
    for (int iter = 0; iter < 400; iter++) {
        Av1FilmGrainParams p;
        p.apply_grain = 1;
        p.grain_seed = uniform(0, 65535);
        const int bd = 8 + 2 * uniform(0, 2);
        p.ar_coeff_lag = iter % 4;
        p.ar_coeff_shift_minus_6 = uniform(0, 3);
        p.grain_scale_shift = uniform(0, 3);
        p.num_y_points = uniform(0, 3) == 0 ? 0 : uniform(1, 14);
        p.chroma_scaling_from_luma = uniform(0, 4) == 0;
        p.num_cb_points = uniform(0, 3) == 0 ? 0 : uniform(1, 10);
        p.num_cr_points = uniform(0, 3) == 0 ? 0 : uniform(1, 10);
        const bool extreme = uniform(0, 2) == 0;
        for (auto& c : p.ar_coeffs_y_plus_128) c = random_coefficient(rng, extreme);
        for (auto& c : p.ar_coeffs_cb_plus_128) c = random_coefficient(rng, extreme);
        for (auto& c : p.ar_coeffs_cr_plus_128) c = random_coefficient(rng, extreme);
        const int* sub = subsamplings[iter % 4 == 0 ? uniform(0, 3) : (iter / 4) % 4];
        const std::string where = "iteration " + std::to_string(iter) + " lag " + std::to_string(p.ar_coeff_lag) +
                                  " bd " + std::to_string(bd) + " sub " + std::to_string(sub[0]) +
                                  std::to_string(sub[1]) + " y points " + std::to_string(p.num_y_points);

        const av1::GrainTemplate want_y = av1::generate_luma_template(p, bd);
        av1::GrainTemplate got_y;
        got_y.samples.assign(7, int16_t(99));  // reused storage of another size must not matter
        av1::generate_luma_template_optimized(p, bd, got_y);
        ASSERT_EQ(diff(got_y, want_y), "") << "luma, " << where;
        av1::GrainTemplate want[3], got[3];
        for (int plane = 1; plane <= 2; plane++) {
            want[plane] = av1::generate_chroma_template(p, bd, plane, sub[0], sub[1], want_y);
            av1::generate_chroma_template_optimized(p, bd, plane, sub[0], sub[1], want_y, got[plane]);
            ASSERT_EQ(diff(got[plane], want[plane]), "") << "plane " << plane << ", " << where;
        }
        // Cb and Cr filtered in lockstep (what the synthesizer uses)
        av1::generate_chroma_templates_optimized(p, bd, sub[0], sub[1], want_y, got[1], got[2]);
        ASSERT_EQ(diff(got[1], want[1]), "") << "Cb of the pair, " << where;
        ASSERT_EQ(diff(got[2], want[2]), "") << "Cr of the pair, " << where;
        counts[p.ar_coeff_lag]++;
        (p.num_y_points > 0 ? with_luma_term : without_luma_term)++;
    }
    for (int lag = 0; lag < 4; lag++) EXPECT_GE(counts[lag], 100) << "lag " << lag;
    EXPECT_GE(with_luma_term, 100);
    EXPECT_GE(without_luma_term, 50);
}

// Monochrome and "no grain" planes: the optimized generator must also give the all-zero
// templates, and reuse a template that held grain of another frame.
TEST_P(SimdAv1TemplateEquivalence, PlanesWithoutGrainAreZero) {
    for (int iter = 0; iter < 40; iter++) {
        Av1FilmGrainParams p;
        p.apply_grain = 1;
        p.grain_seed = uniform(0, 65535);
        p.ar_coeff_lag = uniform(0, 3);
        p.num_y_points = 1;
        for (auto& c : p.ar_coeffs_y_plus_128) c = random_coefficient(rng, false);
        for (auto& c : p.ar_coeffs_cb_plus_128) c = random_coefficient(rng, false);
        const int bd = 8 + 2 * uniform(0, 2), sx = uniform(0, 1), sy = uniform(0, 1);
        av1::GrainTemplate y, cb;
        av1::generate_luma_template_optimized(p, bd, y);
        av1::generate_chroma_template_optimized(p, bd, 1, sx, sy, y, cb);  // cb with grain first
        p.num_y_points = 0;
        p.num_cb_points = 0;
        p.chroma_scaling_from_luma = 0;
        av1::generate_luma_template_optimized(p, bd, y);
        ASSERT_EQ(diff(y, av1::generate_luma_template(p, bd)), "") << "iteration " << iter;
        av1::generate_chroma_template_optimized(p, bd, 1, sx, sy, y, cb);
        ASSERT_EQ(diff(cb, av1::generate_chroma_template(p, bd, 1, sx, sy, y)), "") << "iteration " << iter;
        for (int16_t v : cb.samples) ASSERT_EQ(v, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, SimdAv1TemplateEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

}  // namespace

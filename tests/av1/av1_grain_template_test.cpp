// Grain templates (AV1 spec 7.18.3.3).
#include <gtest/gtest.h>

#include "av1/gaussian_sequence.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/random_number.hpp"

using namespace filmgrain;
using namespace filmgrain::av1;

namespace {

Av1FilmGrainParams base_params(int lag) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 4321;
    p.num_y_points = 1;
    p.point_y_value[0] = 128;
    p.point_y_scaling[0] = 64;
    p.num_cb_points = 1;
    p.point_cb_value[0] = 128;
    p.point_cb_scaling[0] = 64;
    p.num_cr_points = 1;
    p.point_cr_value[0] = 128;
    p.point_cr_scaling[0] = 64;
    p.ar_coeff_lag = lag;
    for (int i = 0; i < 24; ++i) p.ar_coeffs_y_plus_128[i] = 128 + ((i * 7) % 21) - 10;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cb_plus_128[i] = 128 + ((i * 5) % 17) - 8;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cr_plus_128[i] = 128 - ((i * 3) % 13) + 6;
    p.ar_coeff_shift_minus_6 = 1;
    return p;
}

int round2(int x, int n) { return (x + (1 << (n - 1))) >> n; }

}  // namespace

TEST(Av1GrainTemplate, Sizes) {
    const auto p = base_params(2);
    const auto y = generate_luma_template(p, 8);
    EXPECT_EQ(y.width, 82);
    EXPECT_EQ(y.height, 73);
    struct {
        int sx, sy, w, h;
    } cases[] = {{1, 1, 44, 38}, {1, 0, 44, 73}, {0, 0, 82, 73}};
    for (auto c : cases) {
        const auto cb = generate_chroma_template(p, 8, 1, c.sx, c.sy, y);
        EXPECT_EQ(cb.width, c.w);
        EXPECT_EQ(cb.height, c.h);
    }
}

TEST(Av1GrainTemplate, LagZeroIsScaledWhiteNoise) {
    for (int bd : {8, 10, 12})
        for (int gss : {0, 3}) {
            auto p = base_params(0);
            p.grain_scale_shift = gss;
            const auto t = generate_luma_template(p, bd);
            RandomNumberGenerator rng(static_cast<uint16_t>(p.grain_seed));
            const int shift = 12 - bd + gss;
            for (int i = 0; i < t.width * t.height; ++i) {
                const int g = kGaussianSequence[static_cast<std::size_t>(rng.get(11))];
                ASSERT_EQ(t.samples[static_cast<std::size_t>(i)], shift ? round2(g, shift) : g)
                    << "bd " << bd << " i " << i;
            }
        }
}

TEST(Av1GrainTemplate, ArFilterLeavesBorderAndStaysInRange) {
    for (int bd : {8, 10, 12}) {
        const auto white = generate_luma_template(base_params(0), bd);
        auto p = base_params(3);
        p.ar_coeff_shift_minus_6 = 0;
        for (auto& c : p.ar_coeffs_y_plus_128) c = 255;  // strongly unstable filter: exercises the clip
        const auto t = generate_luma_template(p, bd);
        const int lim = 128 << (bd - 8);
        int changed = 0, at_limit = 0;
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x) {
                const bool border = y < 3 || x < 3 || x >= t.width - 3;
                if (border) {
                    EXPECT_EQ(t.at(y, x), white.at(y, x));
                }
                changed += t.at(y, x) != white.at(y, x);
                EXPECT_GE(t.at(y, x), -lim);
                EXPECT_LE(t.at(y, x), lim - 1);
                at_limit += t.at(y, x) == lim - 1 || t.at(y, x) == -lim;
            }
        EXPECT_GT(changed, 1000);
        EXPECT_GT(at_limit, 0);
    }
}

TEST(Av1GrainTemplate, FirstFilteredSampleByHand) {
    // lag 1: neighbours (-1,-1) (-1,0) (-1,+1) (0,-1) with coefficients c0..c3.
    auto p = base_params(1);
    const auto white = generate_luma_template(base_params(0), 8);
    const auto t = generate_luma_template(p, 8);
    int sum = 0;
    const int c[4] = {p.ar_coeffs_y_plus_128[0] - 128, p.ar_coeffs_y_plus_128[1] - 128,
                      p.ar_coeffs_y_plus_128[2] - 128, p.ar_coeffs_y_plus_128[3] - 128};
    sum = c[0] * white.at(2, 2) + c[1] * white.at(2, 3) + c[2] * white.at(2, 4) + c[3] * white.at(3, 2);
    const int expected = std::clamp(white.at(3, 3) + round2(sum, 7), -128, 127);
    EXPECT_EQ(t.at(3, 3), expected);
}

TEST(Av1GrainTemplate, NoLumaPointsGivesZeroLuma) {
    auto p = base_params(2);
    p.num_y_points = 0;
    const auto t = generate_luma_template(p, 10);
    for (auto v : t.samples) ASSERT_EQ(v, 0);
}

TEST(Av1GrainTemplate, ChromaWithoutPointsIsZero) {
    auto p = base_params(2);
    p.num_cb_points = 0;
    const auto y = generate_luma_template(p, 8);
    const auto cb = generate_chroma_template(p, 8, 1, 1, 1, y);
    for (auto v : cb.samples) ASSERT_EQ(v, 0);
    const auto cr = generate_chroma_template(p, 8, 2, 1, 1, y);
    bool any = false;
    for (auto v : cr.samples) any |= v != 0;
    EXPECT_TRUE(any);
    // chroma_scaling_from_luma enables chroma grain without points.
    p.chroma_scaling_from_luma = 1;
    const auto cb2 = generate_chroma_template(p, 8, 1, 1, 1, y);
    any = false;
    for (auto v : cb2.samples) any |= v != 0;
    EXPECT_TRUE(any);
}

TEST(Av1GrainTemplate, ChromaLumaCoefficient) {
    auto p = base_params(1);
    const int luma_pos = p.num_pos_luma();  // 4
    const auto y = generate_luma_template(p, 8);
    p.ar_coeffs_cb_plus_128[static_cast<std::size_t>(luma_pos)] = 128;
    const auto without = generate_chroma_template(p, 8, 1, 1, 1, y);
    p.ar_coeffs_cb_plus_128[static_cast<std::size_t>(luma_pos)] = 200;
    const auto with = generate_chroma_template(p, 8, 1, 1, 1, y);
    EXPECT_NE(without.samples, with.samples);
    // Hand check of the first filtered sample in 4:2:0: luma average over the
    // 2x2 co-located luma grain at (3,3)..(4,4).
    const auto white = generate_chroma_template(base_params(0), 8, 1, 1, 1, y);
    // base_params(0) has lag 0: only the luma coefficient, index 0.
    auto p0 = base_params(0);
    p0.ar_coeffs_cb_plus_128[0] = 160;
    const auto y0 = generate_luma_template(p0, 8);
    const auto c0 = generate_chroma_template(p0, 8, 1, 1, 1, y0);
    const int avg = round2(y0.at(3, 3) + y0.at(3, 4) + y0.at(4, 3) + y0.at(4, 4), 2);
    auto q = p0;
    q.ar_coeffs_cb_plus_128[0] = 128;
    const auto w0 = generate_chroma_template(q, 8, 1, 1, 1, y0);
    EXPECT_EQ(c0.at(3, 3), std::clamp(w0.at(3, 3) + round2(avg * 32, 7), -128, 127));
    (void)white;
    // Without luma points the luma coefficient is not part of the filter.
    auto r = base_params(1);
    r.num_y_points = 0;
    const auto yz = generate_luma_template(r, 8);
    r.ar_coeffs_cb_plus_128[4] = 128;
    const auto a = generate_chroma_template(r, 8, 1, 1, 1, yz);
    r.ar_coeffs_cb_plus_128[4] = 255;
    const auto b = generate_chroma_template(r, 8, 1, 1, 1, yz);
    EXPECT_EQ(a.samples, b.samples);
}

TEST(Av1GrainTemplate, ChromaSeedsDiffer) {
    const auto p = base_params(0);
    const auto y = generate_luma_template(p, 8);
    EXPECT_NE(generate_chroma_template(p, 8, 1, 0, 0, y).samples, generate_chroma_template(p, 8, 2, 0, 0, y).samples);
}

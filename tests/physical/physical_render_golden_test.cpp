// Pins the Boolean renderer's output bit for bit: hashes of small renders computed with the
// code before the binning and mask kernels were reorganized for speed. The renderer's
// contract is that a speed-up never changes a pixel, and no other test compares against an
// earlier version of the code (the other tests compare algorithms and kernels with each
// other, which would all move together).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>

#include "physical/boolean_model.hpp"

using namespace filmgrain;
using namespace filmgrain::physical;

namespace {

uint64_t fnv1a(const FloatPlane& f) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (float v : f.v) {
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        for (int i = 0; i < 4; i++) {
            h ^= (bits >> (8 * i)) & 0xffu;
            h *= 0x100000001b3ull;
        }
    }
    return h;
}

// Grey levels from black to past the clamp at 1 - epsilon, so that empty cells, dense cells
// and the edge continuation all take part.
FloatPlane ramp(int w, int h) {
    FloatPlane u(w, h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            u.at(x, y) = float(std::clamp(0.5 + 0.55 * std::sin(x * 0.21 + 0.3) * std::cos(y * 0.17), 0.0, 1.0));
    return u;
}

struct GoldenCase {
    const char* name;
    double radius, spread;  // spread: radius_sigma / radius
    double zoom;
    BooleanAlgorithm algorithm;
    double tolerance;
    uint64_t hash;
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

class RenderGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(RenderGolden, OutputHashIsUnchanged) {
    const GoldenCase c = GetParam();
    BooleanModelParams p;
    p.radius_mean = c.radius;
    p.radius_sigma = c.radius * c.spread;
    p.zoom = c.zoom;
    p.algorithm = c.algorithm;
    p.samples = 96;
    p.tolerance = c.tolerance;
    p.max_samples = 256;
    const FloatPlane u = ramp(45, 38);
    FloatPlane out;
    render_boolean_model(u, p, {}, 11, out);
    EXPECT_EQ(fnv1a(out), c.hash) << c.name << std::hex << " got 0x" << fnv1a(out);
    // Two threads and a region: every tile must come out the same.
    p.threads = 2;
    FloatPlane two;
    render_boolean_model(u, p, {}, 11, two);
    EXPECT_EQ(two.v, out.v) << c.name;
}

constexpr auto kPixel = BooleanAlgorithm::kPixelWise;
constexpr auto kGrain = BooleanAlgorithm::kGrainWise;

INSTANTIATE_TEST_SUITE_P(
    Cases, RenderGolden,
    ::testing::Values(GoldenCase{"masks_r005", 0.05, 0, 1, kPixel, 0, 0xa21d133ddb0655c9ull},
                      GoldenCase{"masks_r005_spread", 0.05, 0.5, 1, kPixel, 0, 0x212cef3321607f2full},
                      GoldenCase{"masks_r01", 0.1, 0, 1, kPixel, 0, 0xdedf5d8c5e9db8a5ull},
                      GoldenCase{"masks_r01_spread", 0.1, 0.5, 1, kPixel, 0, 0x89db1782f39f1d51ull},
                      GoldenCase{"masks_r03", 0.3, 0, 1, kPixel, 0, 0xcb903c77a22cf20full},
                      GoldenCase{"masks_r03_spread", 0.3, 0.5, 1, kPixel, 0, 0x26066fa87134048eull},
                      GoldenCase{"grain_r005", 0.05, 0.5, 1, kGrain, 0, 0x212cef3321607f2full},
                      GoldenCase{"grain_r03", 0.3, 0, 1, kGrain, 0, 0xcb903c77a22cf20full},
                      GoldenCase{"zoomed_r005", 0.05, 0.5, 1.5, kPixel, 0, 0x2a12e67b33dcfc50ull},
                      GoldenCase{"zoomed_r01", 0.1, 0, 0.75, kPixel, 0, 0x977d51fd6241ba69ull},
                      GoldenCase{"tolerance_r005", 0.05, 0, 1, kPixel, 0.05, 0x477dc2aebd120d5aull},
                      GoldenCase{"tolerance_r03", 0.3, 0.5, 1, kPixel, 0.05, 0x7a4287e9bf84a270ull}),
    [](const ::testing::TestParamInfo<GoldenCase>& i) { return std::string(i.param.name); });

}  // namespace

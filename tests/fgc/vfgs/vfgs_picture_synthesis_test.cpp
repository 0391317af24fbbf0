// VFGS per-sample synthesis (TR 23002-9 clause 7.5 / Annex B.2.2): overlap
// and deblocking arithmetic, scaling, clipping incl. the 10-bit 1020 maximum,
// --outdepth 8, format checks and pattern interpolation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/frame_buffer.hpp"
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/vfgs.hpp"

using namespace filmgrain;
using namespace filmgrain::vfgs;

namespace {

FgcParams luma_params(int scale, int h = 8, int v = 8) {
    FgcParams p;
    p.log2_scale_factor = 5;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    p.comp[0].intervals.push_back({0, 255, {scale, h, v, 0, 0, 0}});
    return p;
}

void fill(FrameBuffer& f, int value) {
    FrameView v = f.view();
    for (int p = 0; p < v.plane_count(); ++p)
        for (int y = 0; y < v.planes[p].height; ++y)
            for (int x = 0; x < v.planes[p].width; ++x) {
                if (v.bit_depth > 8) v.planes[p].row<uint16_t>(y)[x] = static_cast<uint16_t>(value);
                else v.planes[p].row<uint8_t>(y)[x] = static_cast<uint8_t>(value);
            }
}

int sample(const FrameBuffer& f, int p, int y, int x) {
    FrameBuffer& m = const_cast<FrameBuffer&>(f);
    const FrameView v = m.view();
    return v.bit_depth > 8 ? v.planes[p].row<uint16_t>(y)[x] : v.planes[p].row<uint8_t>(y)[x];
}

template <typename F>
ErrorCode error_code(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.code();
    }
    return ErrorCode::kOk;
}

}  // namespace

// Samples beyond the declared bit depth are bad input the library cannot afford to scan
// for: the intensity look-ups must still stay inside their tables (the sanitizer build
// checks) and the output within the range.
TEST(VfgsSynthesis, SamplesAboveTheBitDepthStayInBounds) {
    for (int bd : {10}) {  // VFGS stops at 10 bits
        FrameBuffer src(288, 144, PixelFormat{ChromaFormat::k420, bd}), dst(288, 144, src.format());
        auto* in = reinterpret_cast<uint16_t*>(src.bytes());
        for (std::size_t i = 0; i < src.byte_size() / 2; ++i)
            in[i] = uint16_t(i % 3 == 0 ? 0xFFFF : (1 << bd) + (i * 7919) % 60000);
        Synthesizer s(Options{});
        FgcParams p = luma_params(120);
        p.comp[0].intervals = {{0, 99, {80, 8, 8, 0, 0, 0}}, {100, 255, {120, 10, 10, 0, 0, 0}}};
        s.set_params(p);
        s.apply(src.view(), dst.view());
        const auto* out = reinterpret_cast<const uint16_t*>(dst.bytes());
        for (std::size_t i = 0; i < dst.byte_size() / 2; ++i) ASSERT_LT(out[i], 1 << bd) << "sample " << i;
    }
}

TEST(VfgsSynthesis, OverlapArithmetic) {
    EXPECT_EQ(overlap_blend(10, 20, 12, 24), (120 + 480 + 16) >> 5);  // 19
    EXPECT_EQ(overlap_blend(-10, -20, 12, 24), (-120 - 480 + 16) >> 5);  // -19 (floor)
    EXPECT_EQ(overlap_blend(7, -7, 20, 20), 0);
    EXPECT_EQ(overlap_weights(0, 1, true), (std::array<int, 2>{0, 0}));
    EXPECT_EQ(overlap_weights(0, 1, false), (std::array<int, 2>{12, 24}));
    EXPECT_EQ(overlap_weights(1, 1, false), (std::array<int, 2>{24, 12}));
    EXPECT_EQ(overlap_weights(2, 1, false), (std::array<int, 2>{0, 0}));
    EXPECT_EQ(overlap_weights(0, 2, false), (std::array<int, 2>{20, 20}));
}

TEST(VfgsSynthesis, DeblockUsesUnfilteredValues) {
    int g[] = {0, 8, 40, -40, 4, 0};
    deblock_edge(g, 3);
    EXPECT_EQ(g[2], (8 + 3 * 40 - 40 + 2) >> 2);   // 22
    EXPECT_EQ(g[3], (40 - 3 * 40 + 4 + 2) >> 2);   // -19 (floor of -18.5)
    EXPECT_EQ(g[1], 8);
    EXPECT_EQ(g[4], 4);
}

TEST(VfgsSynthesis, ScalingAndClipping) {
    EXPECT_EQ(scale_grain(100, 50, 11), (5000 + 1024) >> 11);  // 2
    EXPECT_EQ(scale_grain(100, -50, 11), (-5000 + 1024) >> 11);  // -2 (floor)
    EXPECT_EQ(scale_grain(0, -127, 6), 0);
    EXPECT_EQ(blend_sample(250, 10, 8), 255);
    EXPECT_EQ(blend_sample(3, -10, 8), 0);
    // 10 bit: the maximum is 255 << 2 = 1020, also without grain.
    EXPECT_EQ(blend_sample(1023, 0, 10), 1020);
    EXPECT_EQ(blend_sample(1021, -1, 10), 1020);
    EXPECT_EQ(blend_sample(1019, 1, 10), 1020);
    EXPECT_EQ(blend_sample(1000, 5, 10), 1005);
    EXPECT_EQ(to_8bit(1020), 255);
    EXPECT_EQ(to_8bit(1), 0);
    EXPECT_EQ(to_8bit(2), 1);
}

TEST(VfgsSynthesis, TenBitMaximumAppliesToEveryPlane) {
    // Luma grain with scale 0 everywhere and no chroma: every sample is only
    // clipped, and 1021..1023 come out as 1020.
    Synthesizer s(Options{});
    s.set_params(luma_params(0));
    FrameBuffer f(160, 128, {ChromaFormat::k420, 10});
    fill(f, 1023);
    s.apply(f.view(), f.view());
    for (int p = 0; p < 3; ++p) {
        EXPECT_EQ(sample(f, p, 0, 0), 1020);
        EXPECT_EQ(sample(f, p, 63, 79), 1020);
    }
    // --outdepth 8 from there: (1020 + 2) >> 2 = 255.
    Options o;
    o.output_bit_depth = 8;
    Synthesizer s8(o);
    s8.set_params(luma_params(0));
    FrameBuffer in(160, 128, {ChromaFormat::k420, 10}), out(160, 128, {ChromaFormat::k420, 8});
    fill(in, 513);
    s8.apply(in.view(), out.view());
    EXPECT_EQ(sample(out, 0, 5, 5), (513 + 2) >> 2);
    EXPECT_EQ(sample(out, 2, 5, 5), (513 + 2) >> 2);
}

TEST(VfgsSynthesis, GrainIsZeroMeanAndScaled) {
    Options o;
    o.seed = 1234;
    Synthesizer s(o);
    s.set_params(luma_params(255, 14, 14));
    FrameBuffer f(256, 256, {ChromaFormat::k444, 8});
    fill(f, 128);
    s.apply(f.view(), f.view());
    double sum = 0, sq = 0;
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const int d = sample(f, 0, y, x) - 128;
            sum += d;
            sq += d * d;
        }
    const double n = 256.0 * 256.0;
    EXPECT_LT(std::fabs(sum / n), 0.5);
    EXPECT_GT(std::sqrt(sq / n), 2.0);
    // Chroma untouched (no chroma model) in 4:4:4.
    EXPECT_EQ(sample(f, 1, 100, 100), 128);
}

TEST(VfgsSynthesis, InPlaceEqualsSeparateOutput) {
    FrameBuffer a(176, 144, {ChromaFormat::k420, 8});
    FrameView v = a.view();
    for (int p = 0; p < 3; ++p)
        for (int y = 0; y < v.planes[p].height; ++y)
            for (int x = 0; x < v.planes[p].width; ++x) v.planes[p].row<uint8_t>(y)[x] = static_cast<uint8_t>((x * 3 + y * 5) & 255);
    FrameBuffer b = a, out(176, 144, {ChromaFormat::k420, 8});
    FgcParams p = luma_params(200);
    p.comp[1].comp_model_present_flag = true;
    p.comp[1].intervals.push_back({0, 255, {150, 6, 6, 0, 0, 0}});
    p.comp[1].num_model_values_minus1 = 2;
    Synthesizer s1(Options{}), s2(Options{});
    s1.set_params(p);
    s2.set_params(p);
    s1.apply(a.view(), a.view());
    s2.apply(b.view(), out.view());
    EXPECT_EQ(std::memcmp(a.bytes(), out.bytes(), a.byte_size()), 0);
    EXPECT_NE(std::memcmp(a.bytes(), b.bytes(), a.byte_size()), 0);
}

TEST(VfgsSynthesis, CancelCopies) {
    Synthesizer s(Options{});
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = true;
    s.set_params(p);
    FrameBuffer f(160, 128, {ChromaFormat::k420, 10});
    fill(f, 1023);
    const uint32_t before = s.lfsr_state();
    s.apply(f.view(), f.view());
    EXPECT_EQ(sample(f, 0, 3, 3), 1023);
    EXPECT_EQ(s.lfsr_state(), before);
}

TEST(VfgsSynthesis, UnsupportedFormatsAndSizes) {
    Synthesizer s(Options{});
    EXPECT_EQ(error_code([&] {
                  FrameBuffer f(160, 128, {ChromaFormat::k420, 8});
                  s.apply(f.view(), f.view());
              }),
              ErrorCode::kInvalidArgument);  // no params yet
    s.set_params(luma_params(100));
    auto run = [&](int w, int h, ChromaFormat c, int bd) {
        return error_code([&] {
            FrameBuffer f(w, h, {c, bd});
            s.apply(f.view(), f.view());
        });
    };
    EXPECT_EQ(run(160, 128, ChromaFormat::k400, 8), ErrorCode::kUnsupported);
    EXPECT_EQ(run(160, 128, ChromaFormat::k420, 12), ErrorCode::kUnsupported);
    EXPECT_EQ(run(128, 128, ChromaFormat::k420, 8), ErrorCode::kUnsupported);
    EXPECT_EQ(run(160, 126, ChromaFormat::k420, 8), ErrorCode::kUnsupported);
    EXPECT_EQ(run(161, 128, ChromaFormat::k420, 8), ErrorCode::kUnsupported);
    EXPECT_EQ(run(161, 128, ChromaFormat::k444, 8), ErrorCode::kOk);
    EXPECT_EQ(run(129, 129, ChromaFormat::k422, 10), ErrorCode::kUnsupported);
    EXPECT_EQ(run(130, 129, ChromaFormat::k422, 10), ErrorCode::kOk);
    EXPECT_EQ(error_code([] { Synthesizer x(Options{.seed = {}, .gain_percent = -1}); }), ErrorCode::kInvalidArgument);
}

TEST(VfgsSynthesis, PatternInterpolationSmoothsTheIntervalBoundary) {
    // Two intervals with the same scale but very different templates (cut-offs
    // 2 and 14) meet at intensity 128. Without interpolation the grain texture
    // jumps from one template to the other between intensities 127 and 128; with
    // it, the two flat pictures at 127 and 128 get nearly the same grain.
    FgcParams p;
    p.log2_scale_factor = 4;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    p.comp[0].intervals = {{0, 127, {255, 2, 2, 0, 0, 0}}, {128, 255, {255, 14, 14, 0, 0, 0}}};
    auto grain_at = [&](bool interp, int level) {
        Options o;
        o.seed = 42;
        o.pattern_interpolation = interp;
        Synthesizer s(o);
        s.set_params(p);
        FrameBuffer f(256, 256, {ChromaFormat::k444, 8});
        fill(f, level);
        s.apply(f.view(), f.view());
        std::vector<int> g;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) g.push_back(sample(f, 0, y, x) - level);
        return g;
    };
    auto mean_abs_diff = [](const std::vector<int>& a, const std::vector<int>& b) {
        double d = 0;
        for (size_t i = 0; i < a.size(); ++i) d += std::abs(a[i] - b[i]);
        return d / double(a.size());
    };
    const double jump_off = mean_abs_diff(grain_at(false, 127), grain_at(false, 128));
    const double jump_on = mean_abs_diff(grain_at(true, 127), grain_at(true, 128));
    EXPECT_GT(jump_off, 3.0);
    EXPECT_LT(jump_on, jump_off / 4);
    // Far from the boundary interpolation changes nothing.
    EXPECT_EQ(grain_at(true, 60), grain_at(false, 60));
    EXPECT_EQ(grain_at(true, 200), grain_at(false, 200));
}

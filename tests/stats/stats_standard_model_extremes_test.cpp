// The standard models at their extremes, checked with the grain statistics: the largest AR
// gains, saturating scaling functions, 16-bit FGC, single-pixel pictures and sizes that are
// not multiples of the block size. Each case asserts output inside the sample range and the
// grain statistics the model implies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "av1/av1_picture_synthesis.hpp"
#include "core/float_plane.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/vfgs.hpp"
#include "stats/grain_statistics.hpp"

using namespace filmgrain;

namespace {

FrameBuffer flat(int w, int h, int bit_depth, int luma) {
    FrameBuffer f(w, h, PixelFormat{ChromaFormat::k420, bit_depth});
    FrameView v = f.view();
    for (int c = 0; c < 3; c++)
        for (int y = 0; y < v.planes[c].height; y++)
            for (int x = 0; x < v.planes[c].width; x++) {
                const int s = c ? 1 << (bit_depth - 1) : luma;
                if (bit_depth > 8)
                    v.planes[c].row<uint16_t>(y)[x] = uint16_t(s);
                else
                    v.planes[c].row<uint8_t>(y)[x] = uint8_t(s);
            }
    return f;
}

FloatPlane luma(FrameBuffer& f) { return float_plane_from(f.view().planes[0], f.format().bit_depth); }

Av1FilmGrainParams av1_base(int scaling) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 1234;
    p.num_y_points = 2;
    p.point_y_value[0] = 0;
    p.point_y_value[1] = 255;
    p.point_y_scaling[0] = p.point_y_scaling[1] = scaling;
    p.grain_scaling_minus_8 = 0;
    return p;
}

FgcParams fgc_base(int scale, int cutoff, int bit_depth_minus8 = 0) {
    FgcParams p;
    p.log2_scale_factor = 5;
    p.film_grain_bit_depth_luma_minus8 = bit_depth_minus8;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 2;
    FgcIntensityInterval iv;
    iv.intensity_interval_lower_bound = 0;
    iv.intensity_interval_upper_bound = 255;
    iv.comp_model_value = {scale, cutoff, cutoff, 0, 0, 0};
    p.comp[0].intervals = {iv};
    return p;
}

TEST(StandardModelExtremes, Av1LargestArGainsSaturateInsideTheGrainRange) {
    // Every lag-3 coefficient at +127 with the smallest shift (2^6): the AR recursion would
    // diverge; the template clamps each sample to [-128, 127] (8-bit), so the noise is at most
    // round2(255 * 128, 8) = 128 code values and the output stays in [0, 255].
    for (int coeff : {255, 0}) {
        Av1FilmGrainParams p = av1_base(255);
        p.ar_coeff_lag = 3;
        p.ar_coeff_shift_minus_6 = 0;
        std::fill(p.ar_coeffs_y_plus_128.begin(), p.ar_coeffs_y_plus_128.end(), coeff);
        FrameBuffer src = flat(96, 80, 8, 128), dst = src;
        av1::apply_film_grain(p, src.view(), dst.view(), 1);
        const FloatPlane g = stats::grain_of(luma(src), luma(dst));
        double maxabs = 0;
        for (float v : g.v) maxabs = std::max(maxabs, double(std::abs(v)));
        EXPECT_LE(maxabs * 255, 128.0 + 1e-3);
        // Saturated grain is strongly correlated and far from zero variance.
        const stats::Autocovariance c = stats::autocovariance(g, 1);
        EXPECT_GT(c.at(0, 0), 1e-3);
        if (coeff == 255) EXPECT_GT(c.at(1, 0) / c.at(0, 0), 0.5);
    }
}

TEST(StandardModelExtremes, SaturatingScalingClipsToTheRange) {
    for (int restricted : {0, 1}) {
        Av1FilmGrainParams p = av1_base(255);
        p.clip_to_restricted_range = restricted;
        for (int level : {0, 255}) {
            FrameBuffer src = flat(64, 64, 8, level), dst = src;
            av1::apply_film_grain(p, src.view(), dst.view(), 1);
            const FrameView v = dst.view();
            const int lo = restricted ? 16 : 0, hi = restricted ? 235 : 255;
            int at_limit = 0;
            for (int y = 0; y < 64; y++)
                for (int x = 0; x < 64; x++) {
                    const int s = v.planes[0].row<uint8_t>(y)[x];
                    ASSERT_GE(s, lo);
                    ASSERT_LE(s, hi);
                    at_limit += (s == lo || s == hi);
                }
            // Half of the symmetric grain pushes past the limit the content sits on.
            EXPECT_GT(at_limit, 64 * 64 / 4) << "restricted " << restricted << " level " << level;
        }
    }
    // FGC with the largest scale at both ends of the range: clipped, never wrapped.
    for (int level : {0, 255}) {
        FgcStreamSynthesis s(FgcOptions{});
        s.receive_sei(fgc_base(255, 14));
        FrameBuffer src = flat(64, 64, 8, level), dst = src;
        s.apply(src.view(), dst.view(), FgcPictureIds{0, 0});
        const FloatPlane g = stats::grain_of(luma(src), luma(dst));
        double m = 0;
        for (float v : g.v) m += v;
        m /= g.v.size();
        // clipping at the bottom (top) makes the grain's mean positive (negative)
        EXPECT_TRUE(level == 0 ? m > 0 : m < 0) << level;
    }
}

TEST(StandardModelExtremes, Fgc16BitScalesTheGrainWithTheBitDepth) {
    // The same SEI on 8-bit and on 16-bit content: grain in units of full scale has the
    // same standard deviation (RDD 5 scales by 2^(bitDepth - 8)) within 10%.
    double sd[2];
    int i = 0;
    for (int bd : {8, 16}) {
        FgcOptions o;
        FgcStreamSynthesis s(o);
        FgcParams p = fgc_base(100, 8);
        s.receive_sei(p);
        FrameBuffer src = flat(128, 128, bd, 128 << (bd - 8)), dst = src;
        s.apply(src.view(), dst.view(), FgcPictureIds{0, 0});
        const FloatPlane g = stats::grain_of(luma(src), luma(dst));
        for (float v : g.v) ASSERT_TRUE(std::isfinite(v));
        sd[i++] = std::sqrt(stats::autocovariance(g, 0).at(0, 0));
    }
    EXPECT_GT(sd[0], 0);
    EXPECT_NEAR(sd[1] / sd[0], 1.0, 0.1);
}

TEST(StandardModelExtremes, SinglePixelPictures) {
    {
        FgcStreamSynthesis s(FgcOptions{});
        s.receive_sei(fgc_base(255, 8));
        FrameBuffer src = flat(1, 1, 8, 128), dst = src;
        s.apply(src.view(), dst.view(), FgcPictureIds{0, 0});
        const int v = dst.view().planes[0].row<uint8_t>(0)[0];
        // The lone sample gets the grain the top-left sample of a larger flat picture gets: the
        // same block offsets and seed, an 8x8 average of the same grey, no deblocking at the
        // picture's edge.
        FgcStreamSynthesis big(FgcOptions{});
        big.receive_sei(fgc_base(255, 8));
        FrameBuffer src_big = flat(32, 32, 8, 128), dst_big = src_big;
        big.apply(src_big.view(), dst_big.view(), FgcPictureIds{0, 0});
        EXPECT_EQ(v, int(dst_big.view().planes[0].row<uint8_t>(0)[0]));
        // (and that picture does get grain: the comparison is not of two untouched samples)
        int changed = 0;
        for (int y = 0; y < 32; y++)
            for (int x = 0; x < 32; x++) changed += dst_big.view().planes[0].row<uint8_t>(y)[x] != 128;
        EXPECT_GT(changed, 512);
        // The vtm flavour follows HM's picture-size limits: a clear error naming them.
        FgcOptions o;
        o.flavour = FgcFlavour::kVtm;
        FgcStreamSynthesis t(o);
        t.receive_sei(fgc_base(255, 8));
        EXPECT_THROW(t.apply(src.view(), dst.view(), FgcPictureIds{0, 0}), Error);
    }
    FrameBuffer src = flat(1, 1, 8, 128), dst = src;
    av1::apply_film_grain(av1_base(255), src.view(), dst.view(), 1);
    // AV1: the same grain as the top-left sample of a larger picture (same block offsets, no
    // overlap at the picture's corner)
    FrameBuffer src_big = flat(64, 64, 8, 128), dst_big = src_big;
    av1::apply_film_grain(av1_base(255), src_big.view(), dst_big.view(), 1);
    EXPECT_EQ(int(dst.view().planes[0].row<uint8_t>(0)[0]), int(dst_big.view().planes[0].row<uint8_t>(0)[0]));
    EXPECT_NE(int(dst.view().planes[0].row<uint8_t>(0)[0]), 128);
    // VFGS documents a minimum size: a clear error, never an abort.
    vfgs::Synthesizer vs(vfgs::Options{});
    vs.set_params(fgc_base(100, 8));
    EXPECT_THROW(vs.apply(src.view(), dst.view()), Error);
}

TEST(StandardModelExtremes, PartialBlocksCarryGrainLikeFullOnes) {
    // Sizes that are no multiple of 8, 16 or 32 (vtm: HM needs multiples of 4 and >= 128):
    // the last partial blocks get grain with the same variance as the full ones (ratio
    // within [0.6, 1.6]; each region holds >= 200 samples).
    auto check = [&](FrameBuffer& src, FrameBuffer& dst, int w, int h, int fx, int fy, const char* what) {
        const FloatPlane g = stats::grain_of(luma(src), luma(dst));
        double in = 0, edge = 0;
        int nin = 0, nedge = 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const double v = double(g.at(x, y)) * g.at(x, y);
                if (x >= fx || y >= fy) edge += v, nedge++;
                else in += v, nin++;
            }
        ASSERT_GT(in, 0) << what;
        const double ratio = (edge / nedge) / (in / nin);
        EXPECT_GT(ratio, 0.6) << what;
        EXPECT_LT(ratio, 1.6) << what;
    };
    for (FgcFlavour f : {FgcFlavour::kRdd5, FgcFlavour::kVtm}) {
        FgcOptions o;
        o.flavour = f;
        FgcStreamSynthesis s(o);
        s.receive_sei(fgc_base(150, 10));
        const int w = f == FgcFlavour::kRdd5 ? 75 : 180, h = f == FgcFlavour::kRdd5 ? 45 : 132;
        FrameBuffer src = flat(w, h, 8, 128), dst = src;
        s.apply(src.view(), dst.view(), FgcPictureIds{0, 0});
        check(src, dst, w, h, w / 32 * 32, h / 32 * 32, f == FgcFlavour::kRdd5 ? "rdd5" : "vtm");
    }
    const int w = 75, h = 45;
    FrameBuffer src = flat(w, h, 8, 128), dst = src;
    av1::apply_film_grain(av1_base(120), src.view(), dst.view(), 1);
    check(src, dst, w, h, 64, 32, "av1");
}

}  // namespace

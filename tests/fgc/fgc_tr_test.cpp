// The tr flavour and single-line blocks (src/fgc/reference_stripe, colour_correlation, ar_template_generation,
// multiplicative_blending): equal to rdd5 / vtm where those accept the SEI, and statistical
// tests of what no reference implements: the auto-regressive model (autocorrelation at lag
// 1 and 2 against the coefficients, variance against intensity, colour correlation),
// multiplicative blending (grain proportional to the signal) and the film grain bit depth.
// Every tolerance is stated where it is checked; the pictures are fixed, so the results are
// deterministic, and the tolerances cover the estimators' spread over other seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "fgc/ar_template_generation.hpp"
#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;

namespace {

FgcIntensityInterval interval(int lo, int hi, std::array<int, 6> v) { return FgcIntensityInterval{lo, hi, v}; }

// Model 1 parameters for one component with the given values ([0] = sigma).
FgcParams ar_params(std::array<int, 6> v, int nmv = 6, int log2_scale = 5) {
    FgcParams p;
    p.film_grain_model_id = 1;
    p.log2_scale_factor = log2_scale;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = nmv - 1;
    p.comp[0].intervals = {interval(0, 255, v)};
    return p;
}

FgcParams ff_params(int scale, int log2_scale = 5) {
    FgcParams p;
    p.log2_scale_factor = log2_scale;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {interval(0, 255, {scale, 8, 8})};
    }
    return p;
}

int get(const FrameBuffer& b, int plane, int x, int y) {
    FrameView v = const_cast<FrameBuffer&>(b).view();
    return b.format().bit_depth > 8 ? v.planes[plane].row<uint16_t>(y)[x] : v.planes[plane].row<uint8_t>(y)[x];
}

void set(FrameBuffer& b, int plane, int x, int y, int value) {
    FrameView v = b.view();
    if (b.format().bit_depth > 8) v.planes[plane].row<uint16_t>(y)[x] = uint16_t(value);
    else v.planes[plane].row<uint8_t>(y)[x] = uint8_t(value);
}

FrameBuffer picture(int w, int h, PixelFormat f, const std::function<int(int, int, int)>& value) {
    FrameBuffer b(w, h, f);
    FrameView v = b.view();
    for (int c = 0; c < v.plane_count(); c++)
        for (int y = 0; y < v.planes[c].height; y++)
            for (int x = 0; x < v.planes[c].width; x++) set(b, c, x, y, value(c, x, y));
    return b;
}

FrameBuffer flat(int w, int h, PixelFormat f, int value) {
    return picture(w, h, f, [&](int, int, int) { return value; });
}

FrameBuffer synthesize(const FgcOptions& o, const FgcParams& p, const FrameBuffer& in, int poc = 0) {
    FgcStreamSynthesis s(o);
    s.receive_sei(p);
    FrameBuffer out(in.width(), in.height(), in.format());
    s.apply(const_cast<FrameBuffer&>(in).view(), out.view(), {poc, 0});
    return out;
}

FgcOptions tr_options(int block_size = 0) {
    FgcOptions o;
    o.flavour = FgcFlavour::kTr;
    o.block_size = block_size;
    return o;
}

// Grain of one plane: out - in.
std::vector<double> grain(const FrameBuffer& in, const FrameBuffer& out, int plane) {
    FrameView v = const_cast<FrameBuffer&>(in).view();
    std::vector<double> g;
    for (int y = 0; y < v.planes[plane].height; y++)
        for (int x = 0; x < v.planes[plane].width; x++) g.push_back(get(out, plane, x, y) - get(in, plane, x, y));
    return g;
}

double sd(const std::vector<double>& g) {
    double s = 0, s2 = 0;
    for (double x : g) s += x, s2 += x * x;
    const double n = double(g.size());
    return std::sqrt(s2 / n - (s / n) * (s / n));
}

// Autocorrelation at (dx, dy) over the pairs that `use` accepts (both samples inside one
// randomization block and away from the deblocked columns).
double autocorrelation(const std::vector<double>& g, int w, int h, int dx, int dy,
                       const std::function<bool(int, int)>& use) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
    for (int y = 0; y + dy < h; y++)
        for (int x = 0; x + dx < w; x++) {
            if (!use(x, y)) continue;
            const double a = g[std::size_t(y) * w + x], b = g[std::size_t(y + dy) * w + x + dx];
            sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, n++;
        }
    const double cov = sab / n - (sa / n) * (sb / n);
    return cov / std::sqrt((saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n)));
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Same as the references where they accept the SEI.

TEST(FgcTr, EqualsRdd5ForEverythingRdd5Accepts) {
    std::mt19937 rng(7);
    for (PixelFormat f : {PixelFormat{ChromaFormat::k420, 8}, PixelFormat{ChromaFormat::k420, 10},
                          PixelFormat{ChromaFormat::k422, 12}, PixelFormat{ChromaFormat::k444, 8},
                          PixelFormat{ChromaFormat::k400, 16}}) {
        for (int bs : {0, 16, 32}) {
            FrameBuffer in = picture(197, 131, f, [&](int, int, int) { return int(rng() % (1u << f.bit_depth)); });
            FgcParams p = ff_params(200);
            p.comp[0].intervals = {interval(0, 90, {150, 4, 10}), interval(100, 255, {255 << (f.bit_depth - 8), 12, 6})};
            FgcOptions rdd5;
            rdd5.block_size = bs;
            EXPECT_EQ(md5_hex(synthesize(rdd5, p, in, 5).bytes(), in.byte_size()),
                      md5_hex(synthesize(tr_options(bs), p, in, 5).bytes(), in.byte_size()))
                << pix_fmt_name(f) << " block " << bs;
        }
    }
}

TEST(FgcTr, ReferenceStripeEqualsTheOptimizedOneForEveryFlavourItServes) {
    // One scalar reference serves rdd5, vtm and tr (and single-line blocks, model 1 and
    // multiplicative blending, which only it runs); where the optimized stripes also run,
    // on model 0 with additive blending and square blocks, both give the same bytes.
    std::mt19937 rng(3);
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kTr})
        for (int bs : {8, 16, 32}) {
            const PixelFormat f{ChromaFormat::k420, 10};
            FrameBuffer in = picture(260, 140, f, [&](int, int, int) { return int(rng() % 1024); });
            const FgcParams p = ff_params(300);
            fgc::ResolvedFgc r = fgc::resolve_fgc_params(p, flavour, {f.chroma, 10, 260, 140});
            FrameBuffer a(260, 140, f), b(260, 140, f);
            fgc::FgcPictureSynthesis(flavour, bs, 1, fgc::Kernels::kOptimized).apply(r, in.view(), a.view(), 9);
            fgc::FgcPictureSynthesis(flavour, bs, 2, fgc::Kernels::kReference).apply(r, in.view(), b.view(), 9);
            EXPECT_EQ(std::memcmp(a.bytes(), b.bytes(), a.byte_size()), 0)
                << fgc_flavour_name(flavour) << " block " << bs;
        }
}

TEST(FgcTr, ModelOneAndSingleLineOutputsDoNotDependOnTheThreadCount) {
    // The colour term makes Cb wait for luma's finished grain and Cr for Cb's; every
    // component's stripes still run in parallel.
    std::mt19937 rng(5);
    const PixelFormat f{ChromaFormat::k420, 8};
    FrameBuffer in = picture(198, 133, f, [&](int, int, int) { return int(rng() % 256); });
    FgcParams p = ar_params({120, 9, 0, 4, 32, -3});
    p.comp[1] = p.comp[0];
    p.comp[1].intervals[0].comp_model_value = {90, 6, 12, 2, 32, 0};  // p1 = 12: colour term
    p.comp[2] = p.comp[1];
    p.blending_mode_id = 1;
    for (int single_line : {0, 16}) {
        const fgc::ResolvedFgc r = fgc::resolve_fgc_params(p, FgcFlavour::kTr, {f.chroma, 8, 198, 133});
        const int bs = single_line ? single_line : 8;
        FrameBuffer a(198, 133, f), b(198, 133, f);
        fgc::FgcPictureSynthesis(FgcFlavour::kTr, bs, 1, fgc::Kernels::kOptimized, single_line)
            .apply(r, in.view(), a.view(), 4);
        fgc::FgcPictureSynthesis(FgcFlavour::kTr, bs, 3, fgc::Kernels::kOptimized, single_line)
            .apply(r, in.view(), b.view(), 4);
        EXPECT_EQ(std::memcmp(a.bytes(), b.bytes(), a.byte_size()), 0) << "single-line " << single_line;
        EXPECT_NE(std::memcmp(a.bytes(), in.bytes(), a.byte_size()), 0) << "grain was added";
    }
}

// ---------------------------------------------------------------------------------------
// The auto-regressive model.

TEST(FgcTrAr, DefaultsAndWeightsFollowFigure18) {
    // Unsent values: p = 0, A = 1 (1 << L).
    EXPECT_EQ(fgc::complete_ar_model_values({90, 7, 7, 7, 7, 7}, 1, 5), (std::array<int, 6>{90, 0, 0, 0, 32, 0}));
    EXPECT_EQ(fgc::complete_ar_model_values({90, 7, 3, 2, 7, 7}, 4, 5), (std::array<int, 6>{90, 7, 3, 2, 32, 0}));
    // p0 = 8, p2 = 4, A = 48 (1.5), p3 = -4 in 1/32.
    const fgc::ArWeights w = fgc::ar_weights({0, 8, 99, 4, 48, -4}, 5);
    EXPECT_EQ(w.left, 8);
    EXPECT_EQ(w.top, 12);    // p0 * A
    EXPECT_EQ(w.diag, 6);    // p2 * A
    EXPECT_EQ(w.left2, -4);  // p3
    EXPECT_EQ(w.top2, -9);   // p3 * A * A (floor)
}

TEST(FgcTrAr, SharedFilterIsTheVfgsOneWithTheVfgsNoise) {
    // vfgs' bit-exact model-1 template runs the shared filter; fed the same values, the tr
    // template differs only by its random source, so it has the same statistics.
    const std::array<int, 6> v{0, 12, 0, 3, 32, -2};
    const vfgs::GrainTemplate a = vfgs::make_ar_template_luma(v, 5);
    const fgc::GrainTemplate b = fgc::make_ar_template_rdd5_noise(v, 5, 0);
    auto stats = [](const auto& t) {
        std::vector<double> g;
        for (const auto& row : t)
            for (int8_t x : row) g.push_back(x);
        return std::make_pair(sd(g), autocorrelation(g, 64, 64, 1, 0, [](int, int) { return true; }));
    };
    const auto [sa, ra] = stats(a);
    const auto [sb, rb] = stats(b);
    EXPECT_NEAR(sb / sa, 1.0, 0.15);  // two 64x64 draws: +-15 %
    EXPECT_NEAR(rb, ra, 0.1);
    EXPECT_NE(std::memcmp(a.data(), b.data(), sizeof a), 0);
}

namespace {
// Within one 16x16 randomization block (block size 8: same offset in its four sub-blocks)
// and clear of the deblocked columns 8k-1 and 8k.
bool horizontal_pair(int x, int dx) { return x % 8 >= 1 && x % 8 + dx <= 6; }
bool vertical_pair(int y, int dy) { return y % 16 + dy <= 15; }
}  // namespace

TEST(FgcTrAr, HorizontalAutocorrelationMatchesTheCoefficients) {
    // A = 0: no vertical terms, so each row is the 1-D AR(2) process
    // G[x] = n + a1 G[x-1] + a2 G[x-2] with a1 = p0, a2 = p3, whose autocorrelations are
    // rho1 = a1 / (1 - a2) and rho2 = a1 rho1 + a2 (Yule-Walker); vertically uncorrelated.
    // Tolerance 0.04: the estimate over ~60k pairs spreads by ~0.01, and the template's
    // +-127 clip and the rounding of the filter and of the scaling bias it slightly.
    struct Case { int p0, p3; };
    for (Case k : {Case{16, 0}, Case{22, 0}, Case{12, 8}, Case{-12, 0}}) {
        const double a1 = k.p0 / 32.0, a2 = k.p3 / 32.0;
        const double rho1 = a1 / (1 - a2), rho2 = a1 * rho1 + a2;
        const FrameBuffer in = flat(512, 512, {ChromaFormat::k400, 8}, 128);
        const FrameBuffer out = synthesize(tr_options(8), ar_params({255, k.p0, 0, 0, 0, k.p3}), in);
        const std::vector<double> g = grain(in, out, 0);
        const double r1 = autocorrelation(g, 512, 512, 1, 0, [](int x, int) { return horizontal_pair(x, 1); });
        const double r2 = autocorrelation(g, 512, 512, 2, 0, [](int x, int) { return horizontal_pair(x, 2); });
        const double v1 = autocorrelation(g, 512, 512, 0, 1, [](int, int y) { return vertical_pair(y, 1); });
        EXPECT_NEAR(r1, rho1, 0.04) << "p0 " << k.p0 << " p3 " << k.p3;
        EXPECT_NEAR(r2, rho2, 0.04) << "p0 " << k.p0 << " p3 " << k.p3;
        EXPECT_NEAR(v1, 0.0, 0.04) << "p0 " << k.p0 << " p3 " << k.p3;
    }
}

TEST(FgcTrAr, TwoDimensionalAutocorrelationMatchesTheModelEquation) {
    // With the aspect ratio, top and diagonal terms the autocorrelation has no short closed
    // form: it is computed from the model equation itself, in floating point with unit
    // Gaussian noise, on a 1024x1024 field (after a 64-sample start-up), and compared at
    // lags 1 and 2 in both directions. Tolerance 0.05 (estimates spread by ~0.01; the
    // integer filter rounds its weights to 1/32).
    const std::array<int, 6> v{255, 10, 0, 3, 40, -3};  // p0 = 0.3125, p2 = 0.094, A = 1.25, p3 = -0.094
    const fgc::ArWeights w = fgc::ar_weights(v, 5);
    const double L = 32.0;
    const int n = 1024 + 64;
    std::vector<double> f(std::size_t(n) * n, 0.0);
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    auto at = [&](int y, int x) { return (x < 0 || y < 0 || x >= n) ? 0.0 : f[std::size_t(y) * n + x]; };
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++)
            f[std::size_t(y) * n + x] = normal(rng) + (w.left * at(y, x - 1) + w.top * at(y - 1, x) +
                                                       w.diag * (at(y - 1, x - 1) + at(y - 1, x + 1)) +
                                                       w.left2 * at(y, x - 2) + w.top2 * at(y - 2, x)) / L;
    std::vector<double> model;
    for (int y = 64; y < n; y++)
        for (int x = 64; x < n - 64 + 64 && x < n; x++) model.push_back(f[std::size_t(y) * n + x]);
    const int mw = n - 64;
    auto all = [](int, int) { return true; };

    const FrameBuffer in = flat(512, 512, {ChromaFormat::k400, 8}, 128);
    const std::vector<double> g = grain(in, synthesize(tr_options(8), ar_params(v), in), 0);
    for (int lag : {1, 2}) {
        EXPECT_NEAR(autocorrelation(g, 512, 512, lag, 0, [&](int x, int) { return horizontal_pair(x, lag); }),
                    autocorrelation(model, mw, mw, lag, 0, all), 0.05)
            << "horizontal lag " << lag;
        EXPECT_NEAR(autocorrelation(g, 512, 512, 0, lag, [&](int, int y) { return vertical_pair(y, lag); }),
                    autocorrelation(model, mw, mw, 0, lag, all), 0.05)
            << "vertical lag " << lag;
    }
}

TEST(FgcTrAr, VarianceFollowsTheIntervalScale) {
    // Two intervals with the same coefficients and sigma 60 and 180 (x3): the grain of a flat
    // picture in each has a standard deviation in the ratio 3 (+-5 %), and it is what the
    // template and the scaling give: sigma * sd(template) / 2^(L + 5) (+-5 %).
    FgcParams p = ar_params({60, 12, 0, 2, 32, 0});
    p.comp[0].intervals = {interval(0, 127, {60, 12, 0, 2, 32, 0}), interval(128, 255, {180, 12, 0, 2, 32, 0})};
    const FrameBuffer dark = flat(512, 256, {ChromaFormat::k400, 8}, 70);
    const FrameBuffer bright = flat(512, 256, {ChromaFormat::k400, 8}, 190);
    const double s_dark = sd(grain(dark, synthesize(tr_options(), p, dark), 0));
    const double s_bright = sd(grain(bright, synthesize(tr_options(), p, bright), 0));
    EXPECT_NEAR(s_bright / s_dark, 3.0, 0.15);
    std::vector<double> t;
    for (const auto& row : fgc::make_ar_template_rdd5_noise(p.comp[0].intervals[0].comp_model_value, 5, 0))
        for (int8_t x : row) t.push_back(x);
    EXPECT_NEAR(s_bright, 180 * sd(t) / 1024.0, 0.05 * s_bright);
}

TEST(FgcTrAr, ColourCorrelationCarriesThePreviousComponentsGrain) {
    // Cb signals sigma 0 and p1 = 0.5: its grain is p1 times the luma grain under it
    // (2x2 mean in 4:2:0). Slope within 0.02 of p1 and correlation above 0.95 (the rounding
    // of the 8-bit grain is the only other term). Cr with its own sigma and p1 = -0.25 on Cb
    // keeps a negative correlation; without p1 the components are uncorrelated (|r| < 0.05).
    for (ChromaFormat cf : {ChromaFormat::k444, ChromaFormat::k420}) {
        FgcParams p = ar_params({255, 12, 0, 0, 32, 0});
        p.comp[1] = p.comp[0];
        p.comp[1].intervals = {interval(0, 255, {0, 12, 16, 0, 32, 0})};
        p.comp[2] = p.comp[0];
        p.comp[2].intervals = {interval(0, 255, {120, 12, -8, 0, 32, 0})};
        const FrameBuffer in = flat(256, 256, {cf, 8}, 128);
        const FrameBuffer out = synthesize(tr_options(), p, in);
        const auto gy = grain(in, out, 0), gcb = grain(in, out, 1), gcr = grain(in, out, 2);
        const int cw = cf == ChromaFormat::k420 ? 128 : 256;
        std::vector<double> under;  // luma grain under each chroma sample
        for (int y = 0; y < cw; y++)
            for (int x = 0; x < cw; x++) {
                if (cf == ChromaFormat::k444) under.push_back(gy[std::size_t(y) * 256 + x]);
                else
                    under.push_back((gy[std::size_t(2 * y) * 256 + 2 * x] + gy[std::size_t(2 * y) * 256 + 2 * x + 1] +
                                     gy[std::size_t(2 * y + 1) * 256 + 2 * x] +
                                     gy[std::size_t(2 * y + 1) * 256 + 2 * x + 1]) / 4);
            }
        double sxy = 0, sxx = 0, syy = 0;
        for (std::size_t i = 0; i < under.size(); i++)
            sxy += under[i] * gcb[i], sxx += under[i] * under[i], syy += gcb[i] * gcb[i];
        EXPECT_NEAR(sxy / sxx, 0.5, 0.02);
        EXPECT_GT(sxy / std::sqrt(sxx * syy), 0.95);
        double cbcr = 0, cc = 0, rr = 0;
        for (std::size_t i = 0; i < gcb.size(); i++) cbcr += gcb[i] * gcr[i], cc += gcb[i] * gcb[i], rr += gcr[i] * gcr[i];
        EXPECT_LT(cbcr / std::sqrt(cc * rr), -0.05);

        // Without p1 (the luma grain is unchanged, so `under` still holds it).
        p.comp[1].intervals = {interval(0, 255, {200, 12, 0, 0, 32, 0})};
        const auto g1 = grain(in, synthesize(tr_options(), p, in), 1);
        double a = 0, aa = 0, bb = 0;
        for (std::size_t i = 0; i < under.size(); i++) a += under[i] * g1[i], aa += under[i] * under[i], bb += g1[i] * g1[i];
        EXPECT_NEAR(a / std::sqrt(aa * bb), 0.0, 0.05);
    }
}

// ---------------------------------------------------------------------------------------
// Multiplicative blending.

TEST(FgcTrBlending, MultiplicativeGrainIsProportionalToTheSignal) {
    // The same grain pattern (same picture offset) on flat pictures at 48, 96 and 144:
    // multiplicative grain is exactly (I * g8 + 128) >> 8 of the 8-bit scale additive grain
    // g8 (taken at 128, where nothing clips; at 10 bits the additive grain is g8 << 2), so its standard deviation is in the ratio 1:2:3 (+-2 %:
    // the rounding to whole code values is the only spread) and I/256 of the additive one.
    for (int bd : {8, 10}) {
        FgcParams p = ff_params(200, /*log2_scale=*/2);
        const int levels[3] = {48, 96, 144};
        const FrameBuffer mid = flat(256, 256, {ChromaFormat::k420, bd}, 128 << (bd - 8));
        const std::vector<double> add = grain(mid, synthesize(tr_options(), p, mid), 0);
        p.blending_mode_id = 1;
        std::array<double, 3> mult{};
        for (int i = 0; i < 3; i++) {
            const int level = levels[i] << (bd - 8);
            const FrameBuffer in = flat(256, 256, {ChromaFormat::k420, bd}, level);
            const std::vector<double> g = grain(in, synthesize(tr_options(), p, in), 0);
            for (std::size_t k = 0; k < g.size(); k++)
                ASSERT_EQ(int(g[k]), (level * (int(add[k]) >> (bd - 8)) + 128) >> 8) << "bit depth " << bd << " sample " << k;
            mult[i] = sd(g);
        }
        EXPECT_NEAR(mult[1] / mult[0], 2.0, 0.04) << bd;
        EXPECT_NEAR(mult[2] / mult[0], 3.0, 0.06) << bd;
        EXPECT_NEAR(mult[1] / sd(add), 96.0 / 256, 0.0075) << bd;
    }
}

TEST(FgcTrBlending, MultiplicativeKeepsTheMeanAndClips) {
    // The mean of the grain scales like the grain: at 150 it is 150/256 of the additive
    // grain's (within 0.05 code value); black stays black, and the top of the range clips.
    FgcParams p = ff_params(255);
    const FrameBuffer mid = flat(256, 256, {ChromaFormat::k420, 8}, 150);
    auto mean = [](const std::vector<double>& g) {
        double m = 0;
        for (double x : g) m += x;
        return m / double(g.size());
    };
    const double add_mean = mean(grain(mid, synthesize(tr_options(), p, mid), 0));
    p.blending_mode_id = 1;
    EXPECT_NEAR(mean(grain(mid, synthesize(tr_options(), p, mid), 0)), add_mean * 150 / 256, 0.05);
    const FrameBuffer black = flat(256, 256, {ChromaFormat::k420, 8}, 0);
    EXPECT_EQ(sd(grain(black, synthesize(tr_options(), p, black), 0)), 0.0);
    const FrameBuffer white = flat(256, 256, {ChromaFormat::k420, 10}, 255 << 2);
    const FrameBuffer out = synthesize(tr_options(), p, white);
    int top = 0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            EXPECT_LE(get(out, 0, x, y), 1023);
            top += get(out, 0, x, y) == 1023;
        }
    EXPECT_GT(top, 0);
}

// ---------------------------------------------------------------------------------------
// The film grain bit depth (separate_colour_description_present_flag).

TEST(FgcTrBitDepth, GrainScalesWithThePictureBitDepthNotTheGrainBitDepth) {
    // The SEI describes grain for Bg bits; carried to the picture's B bits it is scaled by
    // 2^(B - Bg). Same content at 8 and at 10 bits (x4): the grain of a Bg = 10 SEI has 4x
    // the standard deviation at 10 bits (+-1 %); a 10-bit picture gets the same grain from
    // Bg = 8, 10 and 12 (identical output), and the 8-bit one the same from Bg = 8 and 10.
    FgcParams p = ff_params(180);
    p.separate_colour_description_present_flag = true;
    const FrameBuffer in8 = picture(256, 256, {ChromaFormat::k420, 8}, [](int, int x, int y) { return 40 + (x + y) % 170; });
    FrameBuffer in10(256, 256, {ChromaFormat::k420, 10});
    {
        FrameView v = in10.view();
        for (int c = 0; c < 3; c++)
            for (int y = 0; y < v.planes[c].height; y++)
                for (int x = 0; x < v.planes[c].width; x++) set(in10, c, x, y, get(in8, c, x, y) << 2);
    }
    std::array<std::string, 3> md5_10;
    std::array<double, 3> sd8{};
    for (int bg : {8, 10, 12}) {
        p.film_grain_bit_depth_luma_minus8 = p.film_grain_bit_depth_chroma_minus8 = bg - 8;
        const FrameBuffer o10 = synthesize(tr_options(), p, in10), o8 = synthesize(tr_options(), p, in8);
        md5_10[(bg - 8) / 2] = md5_hex(o10.bytes(), o10.byte_size());
        sd8[(bg - 8) / 2] = sd(grain(in8, o8, 0));
        if (bg == 10) EXPECT_NEAR(sd(grain(in10, o10, 0)) / sd8[1], 4.0, 0.04);
    }
    EXPECT_EQ(md5_10[0], md5_10[1]);
    EXPECT_EQ(md5_10[1], md5_10[2]);
    EXPECT_NEAR(sd8[0] / sd8[1], 1.0, 0.01);
    EXPECT_NEAR(sd8[2] / sd8[1], 1.0, 0.01);
}

TEST(FgcTrBitDepth, ScaleRangeFollowsTheGrainBitDepth) {
    // comp_model_value[0] may reach 255 << (Bg - 8): 800 is valid for Bg = 10 on an 8-bit
    // picture and then gives 800/200 = 4x the grain of 200 (+-5 %: the smaller grain's
    // rounding to whole code values), but not for Bg = 8.
    const FrameBuffer in = flat(256, 256, {ChromaFormat::k420, 8}, 128);
    FgcParams p = ff_params(800);
    p.separate_colour_description_present_flag = true;
    p.film_grain_bit_depth_luma_minus8 = p.film_grain_bit_depth_chroma_minus8 = 0;
    try {
        synthesize(tr_options(), p, in);
        FAIL() << "scale 800 accepted with an 8-bit film grain bit depth";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = 800 is out of range (allowed 0..255)"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("filmGrainBitDepth[0] = 8 from film_grain_bit_depth_luma_minus8 + 8"),
                  std::string::npos)
            << e.what();
    }
    // 1021..1023 are valid SEI values at Bg = 10 but above what the references take
    p.film_grain_bit_depth_luma_minus8 = p.film_grain_bit_depth_chroma_minus8 = 2;
    p.comp[0].intervals[0].comp_model_value[0] = 1023;
    try {
        synthesize(tr_options(), p, in);
        FAIL() << "scale 1023 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = 1023 is out of range (allowed 0..1020)"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("255 << (film grain bit depth - 8)"), std::string::npos) << e.what();
    }
    p.comp[0].intervals[0].comp_model_value[0] = 800;
    const double big = sd(grain(in, synthesize(tr_options(), p, in), 0));
    FgcParams q = p;
    for (auto& c : q.comp) c.intervals[0].comp_model_value[0] = 200;
    EXPECT_NEAR(big / sd(grain(in, synthesize(tr_options(), q, in), 0)), 4.0, 0.2);
}

// ---------------------------------------------------------------------------------------
// Single-line blocks (TR 23002-9 7.3.2.3).

TEST(FgcSingleLine, EachRowSegmentPicksItsOwnScale) {
    // Rows alternate between intensities 60 and 200, whose intervals have scales 100 and
    // 250. Square blocks average the two and use one scale; Nx1 segments see each row's own
    // intensity, so the grain of the bright rows is 2.5x that of the dark ones (+-5 %).
    for (FgcFlavour flavour : {FgcFlavour::kVtm, FgcFlavour::kTr})
        for (int n : {8, 16, 32}) {
            FgcParams p = ff_params(100);
            p.comp[0].intervals = {interval(0, 127, {100, 8, 8}), interval(128, 255, {250, 8, 8})};
            const FrameBuffer in =
                picture(256, 256, {ChromaFormat::k420, 8}, [](int c, int, int y) { return c ? 128 : (y % 2 ? 200 : 60); });
            FgcOptions o;
            o.flavour = flavour;
            o.single_line_blocks = n;
            const auto g = grain(in, synthesize(o, p, in), 0);
            std::vector<double> dark, bright;
            for (int y = 0; y < 256; y++)
                for (int x = 0; x < 256; x++) (y % 2 ? bright : dark).push_back(g[std::size_t(y) * 256 + x]);
            EXPECT_NEAR(sd(bright) / sd(dark), 2.5, 0.125) << int(flavour) << " " << n;
            o.single_line_blocks = 0;
            o.block_size = n;
            const auto sq = grain(in, synthesize(o, p, in), 0);
            dark.clear(), bright.clear();
            for (int y = 0; y < 256; y++)
                for (int x = 0; x < 256; x++) (y % 2 ? bright : dark).push_back(sq[std::size_t(y) * 256 + x]);
            EXPECT_NEAR(sd(bright) / sd(dark), 1.0, 0.1) << int(flavour) << " " << n;
        }
}

TEST(FgcSingleLine, OneTemplatePerPicture) {
    // The second interval's cut-offs are not used: the picture takes the first interval's
    // template everywhere, so changing them changes nothing.
    const FrameBuffer in = picture(256, 192, {ChromaFormat::k420, 8}, [](int, int x, int y) { return (x * 3 + y) % 256; });
    FgcParams a = ff_params(120), b = a;
    a.comp[0].intervals = {interval(0, 127, {120, 4, 4}), interval(128, 255, {220, 12, 12})};
    b.comp[0].intervals = {interval(0, 127, {120, 4, 4}), interval(128, 255, {220, 4, 4})};
    FgcOptions o;
    o.flavour = FgcFlavour::kVtm;
    o.single_line_blocks = 16;
    FgcStreamSynthesis s(o);
    s.receive_sei(a);
    EXPECT_EQ(md5_hex(synthesize(o, a, in).bytes(), in.byte_size()), md5_hex(synthesize(o, b, in).bytes(), in.byte_size()));
    o.single_line_blocks = 0;
    o.block_size = 16;
    EXPECT_NE(md5_hex(synthesize(o, a, in).bytes(), in.byte_size()), md5_hex(synthesize(o, b, in).bytes(), in.byte_size()));
}

TEST(FgcSingleLine, OptionChecks) {
    auto code = [](FgcOptions o) {
        try {
            FgcStreamSynthesis s(o);
        } catch (const Error& e) {
            return e.code();
        }
        return ErrorCode::kOk;
    };
    FgcOptions o;
    o.single_line_blocks = 8;
    EXPECT_EQ(code(o), ErrorCode::kInvalidArgument);  // rdd5 fixes 8x8 blocks
    o.flavour = FgcFlavour::kVtm;
    EXPECT_EQ(code(o), ErrorCode::kOk);
    o.single_line_blocks = 12;
    EXPECT_EQ(code(o), ErrorCode::kInvalidArgument);
    o.single_line_blocks = 16;
    o.block_size = 32;
    EXPECT_EQ(code(o), ErrorCode::kInvalidArgument);
    o.flavour = FgcFlavour::kTr;
    o.block_size = 16;
    EXPECT_EQ(code(o), ErrorCode::kOk);
}

// ---------------------------------------------------------------------------------------
// What rdd5 and vtm reject, tr accepts; what tr still rejects.

TEST(FgcTr, AcceptsWhatTheReferencesRejectAndNamesTheRest) {
    const fgc::PictureFormat f{ChromaFormat::k420, 8, 352, 288};
    FgcParams ar = ar_params({100, 10, 0, 0, 32, 0});
    FgcParams mult = ff_params(100);
    mult.blending_mode_id = 1;
    FgcParams sep = ff_params(100);
    sep.separate_colour_description_present_flag = true;
    for (const FgcParams& p : {ar, mult, sep}) {
        EXPECT_NO_THROW(fgc::resolve_fgc_params(p, FgcFlavour::kTr, f));
        for (FgcFlavour ref : {FgcFlavour::kRdd5, FgcFlavour::kVtm}) {
            try {
                fgc::resolve_fgc_params(p, ref, f);
                ADD_FAILURE() << "accepted by the reference flavour";
            } catch (const Error& e) {
                EXPECT_EQ(e.code(), ErrorCode::kUnsupported);
                EXPECT_NE(std::string(e.what()).find("--flavour tr"), std::string::npos) << e.what();
            }
        }
    }
    auto message = [&](const FgcParams& p) {
        try {
            fgc::resolve_fgc_params(p, FgcFlavour::kTr, f);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    FgcParams bad = ar;
    bad.log2_scale_factor = 2;
    EXPECT_NE(message(bad).find("log2_scale_factor = 2"), std::string::npos);
    EXPECT_NE(message(bad).find("allowed 3..8"), std::string::npos);
    bad = ar;
    bad.comp[0].intervals[0].comp_model_value[1] = 40;
    EXPECT_NE(message(bad).find("comp_model_value[0][0][1] = 40"), std::string::npos);
    bad = ar;
    bad.comp[0].intervals[0].comp_model_value[4] = -1;
    EXPECT_NE(message(bad).find("comp_model_value[0][0][4] = -1"), std::string::npos);
    bad = mult;
    bad.blending_mode_id = 2;
    EXPECT_NE(message(bad).find("reserved"), std::string::npos);
    bad = ar;
    bad.film_grain_model_id = 3;
    EXPECT_NE(message(bad).find("reserved"), std::string::npos);
}

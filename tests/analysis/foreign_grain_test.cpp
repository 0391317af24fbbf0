// Estimation on grain the estimator did not make: Gaussian noise, white or blurred, drawn
// here and added to the test pictures (content the comparison of docs/ANALYSIS.md does not
// use). What must hold, with the figures of issue 22's acceptance:
//  - FGC cut-offs that give the true autocorrelation (mean |r_est - r_true| over lags
//    (1,0), (0,1), (1,1), (2,0) <= 0.06): a step fit chose them 1-2 steps too coarse;
//  - strong coarse FGC grain at its level (within 5 %): it saturated at comp_model_value 255;
//  - strong coarse FGC chroma grain at its level (within 10 %): out of reach at its cut-offs;
//  - AV1 chroma at its level (within 10 %) when moving coloured texture crosses the picture,
//    and none (re-synthesized chroma std <= 0.3) when the grain is luma only;
//  - AV1 chroma scaling indexed by the luma when the chroma grain follows the luma.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "analysis/grain_analyzer.hpp"
#include "analysis/plane_image.hpp"
#include "av1/av1_picture_synthesis.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "synthetic_content.hpp"

namespace filmgrain {
namespace {

using analysis::GrainAnalyzer;
using analysis::GrainModel;
using analysis::plane_to_float;

constexpr int kWidth = 384, kHeight = 256, kFrames = 8;

struct NoiseSpec {
    double luma_std = 0, chroma_std = 0, blur = 0;  // blur: Gaussian sigma in samples, 0 = white
};

// Gaussian noise of the given std (after blurring) for one plane, sample units.
cv::Mat noise_plane(cv::Size size, double std, double blur, unsigned seed) {
    cv::Mat n(size, CV_32F);
    cv::RNG rng(seed);
    rng.fill(n, cv::RNG::NORMAL, 0.0, 1.0);
    if (blur > 0) cv::GaussianBlur(n, n, cv::Size(0, 0), blur, blur, cv::BORDER_REFLECT);
    cv::Scalar mean, sd;
    cv::meanStdDev(n, mean, sd);
    return (n - mean[0]) * (std / sd[0]);
}

// The test pictures with a textured, coloured disc moving 5 samples per picture over them.
FrameBuffer moving_content(PixelFormat fmt, int k) {
    FrameBuffer fb = analysis_test::make_clean_picture(kWidth, kHeight, fmt);
    FrameView v = fb.view();
    const int scale = 1 << (fmt.bit_depth - 8);
    for (int p = 0; p < v.plane_count(); p++) {
        cv::Mat m = plane_to_float(v, p);
        const int sx = p ? 1 : 0;
        const double cx = (60 + 5 * k) >> sx, cy = 128 >> sx, r = 50 >> sx;
        for (int y = 0; y < m.rows; y++)
            for (int x = 0; x < m.cols; x++) {
                const double d = std::hypot(x - cx, y - cy);
                if (d > r) continue;
                const double u = (x << sx) - 5.0 * k, w = y << sx;  // texture moves with the disc
                const double tex = std::sin(u * 0.31) * std::cos(w * 0.23) + 0.5 * std::sin((u + w) * 0.11);
                m.at<float>(y, x) = float((p == 0 ? 120 + 20 * tex : p == 1 ? 150 + 3 * tex : 100 - 3 * tex) * scale);
            }
        analysis::float_to_plane(m, v, p);
    }
    return fb;
}

FrameBuffer add_noise(const FrameBuffer& clean, const NoiseSpec& n, unsigned seed) {
    FrameBuffer g = clean;
    FrameView v = g.view();
    const int scale = 1 << (clean.format().bit_depth - 8);
    for (int p = 0; p < v.plane_count(); p++) {
        const double std = (p == 0 ? n.luma_std : n.chroma_std) * scale;
        if (std <= 0) continue;
        cv::Mat m = plane_to_float(v, p);
        m += noise_plane(m.size(), std, p == 0 ? n.blur : n.blur / 2, seed * 3 + p);
        analysis::float_to_plane(m, v, p);
    }
    return g;
}

// Normalized autocorrelation of grain at lags (1,0), (0,1), (1,1), (2,0).
std::array<double, 4> acf(const std::vector<cv::Mat>& grains) {
    const int lags[4][2] = {{1, 0}, {0, 1}, {1, 1}, {2, 0}};
    std::array<double, 4> r{};
    double r0 = 0;
    for (const cv::Mat& g0 : grains) {
        cv::Mat g = g0 - cv::mean(g0)[0];
        r0 += g.dot(g) / double(g.total());
        for (int i = 0; i < 4; i++) {
            const int dx = lags[i][0], dy = lags[i][1];
            const cv::Rect a(0, 0, g.cols - dx, g.rows - dy), b(dx, dy, g.cols - dx, g.rows - dy);
            r[i] += g(a).dot(g(b)) / double(a.area());
        }
    }
    for (double& x : r) x /= r0;
    return r;
}

double plane_std(const std::vector<cv::Mat>& grains) {
    double ss = 0, n = 0;
    for (const cv::Mat& g : grains) ss += g.dot(g), n += double(g.total());
    return std::sqrt(ss / n);
}

struct Clip {
    std::vector<FrameBuffer> clean, grainy;
};

Clip make_clip(PixelFormat fmt, const NoiseSpec& n, bool moving) {
    Clip c;
    for (int k = 0; k < kFrames; k++) {
        c.clean.push_back(moving ? moving_content(fmt, k) : analysis_test::make_clean_picture(kWidth, kHeight, fmt));
        c.grainy.push_back(add_noise(c.clean.back(), n, 101 + k));
    }
    return c;
}

std::vector<cv::Mat> grain_of(const std::vector<FrameBuffer>& grainy, const std::vector<FrameBuffer>& clean, int p,
                              cv::Rect inner = {}) {
    std::vector<cv::Mat> out;
    for (std::size_t k = 0; k < grainy.size(); k++) {
        cv::Mat g = plane_to_float(const_cast<FrameBuffer&>(grainy[k]).view(), p) -
                    plane_to_float(const_cast<FrameBuffer&>(clean[k]).view(), p);
        out.push_back(inner.area() ? g(inner).clone() : g);
    }
    return out;
}

std::vector<FrameBuffer> resynthesize_fgc(const FgcParams& p, const std::vector<FrameBuffer>& clean) {
    FgcStreamSynthesis s(FgcOptions{});
    std::vector<FrameBuffer> out;
    for (std::size_t k = 0; k < clean.size(); k++) {
        FrameBuffer g = clean[k];
        s.receive_sei(p);
        s.apply(const_cast<FrameBuffer&>(clean[k]).view(), g.view(), FgcPictureIds{int(k), 0});
        out.push_back(std::move(g));
    }
    return out;
}

std::vector<FrameBuffer> resynthesize_av1(const Av1FilmGrainParams& p, const std::vector<FrameBuffer>& clean) {
    std::vector<FrameBuffer> out;
    for (std::size_t k = 0; k < clean.size(); k++) {
        FrameBuffer g = clean[k];
        Av1FilmGrainParams q = p;
        q.grain_seed = (p.grain_seed + 977 * int(k)) & 0xFFFF;
        if (p.apply_grain) av1::apply_film_grain(q, const_cast<FrameBuffer&>(clean[k]).view(), g.view(), 2);
        out.push_back(std::move(g));
    }
    return out;
}

template <class Estimate>
Estimate analyse(const Clip& c, GrainModel model, bool supply_clean) {
    analysis::AnalysisOptions o;
    o.model = model;
    GrainAnalyzer a(o, c.grainy[0].format(), kWidth, kHeight);
    for (std::size_t k = 0; k < c.grainy.size(); k++) a.add_frame(c.grainy[k], supply_clean ? &c.clean[k] : nullptr);
    a.finish();
    if constexpr (std::is_same_v<Estimate, analysis::FgcEstimate>) return a.estimate_fgc();
    else return a.estimate_av1();
}

// Luma grain std where the clean luma is in lo..hi, averaged over the pictures.
double mean_luma_band_std(const std::vector<FrameBuffer>& grainy, const std::vector<FrameBuffer>& clean, int lo, int hi) {
    double s = 0;
    for (std::size_t k = 0; k < grainy.size(); k++) s += analysis_test::grain_std_in_band(grainy[k], clean[k], 0, lo, hi);
    return s / double(grainy.size());
}

// Luma grain in the middle intensities (clear of clipping), 8-bit scale.
const cv::Rect kInnerLuma(16, 16, kWidth - 32, kHeight - 32);

TEST(ForeignGrain, FgcCutoffsGiveTheTrueAutocorrelation) {
    for (double blur : {0.6, 0.9, 1.3}) {
        const Clip c = make_clip({ChromaFormat::k420, 8}, {4.0, 0.0, blur}, false);
        const auto est = analyse<analysis::FgcEstimate>(c, GrainModel::kFgc, true);
        ASSERT_TRUE(est.params.comp[0].comp_model_present_flag);
        const auto resynth = resynthesize_fgc(est.params, c.clean);
        const auto rt = acf(grain_of(c.grainy, c.clean, 0, kInnerLuma)), re = acf(grain_of(resynth, c.clean, 0, kInnerLuma));
        double err = 0;
        for (int i = 0; i < 4; i++) err += std::fabs(re[i] - rt[i]) / 4;
        const auto& iv = est.params.comp[0].intervals[0];
        std::printf("[ measured ] blur %.1f: cut-offs (%d, %d), r (1,0) (0,1) (1,1) (2,0) true %.3f %.3f %.3f %.3f, "
                    "estimate %.3f %.3f %.3f %.3f, ACF error %.3f\n",
                    blur, iv.comp_model_value[1], iv.comp_model_value[2], rt[0], rt[1], rt[2], rt[3], re[0], re[1], re[2],
                    re[3], err);
        EXPECT_LE(err, 0.06) << "blur " << blur;
        const double st = plane_std(grain_of(c.grainy, c.clean, 0, kInnerLuma)),
                     se = plane_std(grain_of(resynth, c.clean, 0, kInnerLuma));
        EXPECT_NEAR(se / st, 1.0, 0.05) << "blur " << blur;
    }
}

TEST(ForeignGrain, FgcStrongCoarseGrainReachesItsLevel) {
    const Clip c = make_clip({ChromaFormat::k420, 8}, {9.0, 0.0, 1.6}, false);
    const auto est = analyse<analysis::FgcEstimate>(c, GrainModel::kFgc, true);
    ASSERT_TRUE(est.params.comp[0].comp_model_present_flag);
    for (const auto& iv : est.params.comp[0].intervals) EXPECT_LT(iv.comp_model_value[0], 255) << "saturated";
    const auto resynth = resynthesize_fgc(est.params, c.clean);
    // middle bands: clipping at 0/255 does not reach them
    for (int lo : {64, 128}) {
        const double so = analysis_test::grain_std_in_band(c.grainy[3], c.clean[3], 0, lo, lo + 63);
        const double sr = analysis_test::grain_std_in_band(resynth[3], c.clean[3], 0, lo, lo + 63);
        std::printf("[ measured ] band %d..%d: true %.2f, re-synthesized %.2f (log2_scale_factor %d)\n", lo, lo + 63, so, sr,
                    est.params.log2_scale_factor);
        EXPECT_NEAR(sr / so, 1.0, 0.05) << "band " << lo;
    }
}

// Strong coarse chroma grain: at the cut-offs its correlation matches, the level needs a
// comp_model_value beyond 255 even at RDD 5's smallest log2_scale_factor (2), and the grain
// came out 40 % weak. The estimate takes finer cut-offs that reach the level, and says so.
TEST(ForeignGrain, FgcStrongCoarseChromaGrainReachesItsLevel) {
    const Clip c = make_clip({ChromaFormat::k420, 8}, {4.0, 14.0, 3.0}, false);
    const auto est = analyse<analysis::FgcEstimate>(c, GrainModel::kFgc, true);
    const auto resynth = resynthesize_fgc(est.params, c.clean);
    for (int p = 1; p < 3; p++) {
        ASSERT_TRUE(est.params.comp[p].comp_model_present_flag) << "plane " << p;
        const auto& iv = est.params.comp[p].intervals[0];
        const double st = plane_std(grain_of(c.grainy, c.clean, p)), se = plane_std(grain_of(resynth, c.clean, p));
        std::printf("[ measured ] plane %d: true std %.2f, re-synthesized %.2f; value %d, cut-offs (%d,%d), "
                    "log2_scale_factor %d; %s\n",
                    p, st, se, iv.comp_model_value[0], iv.comp_model_value[1], iv.comp_model_value[2],
                    est.params.log2_scale_factor, est.components[p].note.c_str());
        EXPECT_NEAR(se / st, 1.0, 0.10) << "plane " << p;
        EXPECT_NE(est.components[p].note.find("cut-offs raised"), std::string::npos) << "plane " << p;
    }
}

TEST(ForeignGrain, Av1ChromaAtItsLevelUnderMovingColouredTexture) {
    const Clip c = make_clip({ChromaFormat::k420, 8}, {4.0, 1.5, 0.0}, true);
    const auto est = analyse<analysis::Av1Estimate>(c, GrainModel::kAv1, false);
    ASSERT_EQ(est.params.apply_grain, 1);
    const auto resynth = resynthesize_av1(est.params, c.clean);
    for (int p = 1; p < 3; p++) {
        const double st = plane_std(grain_of(c.grainy, c.clean, p)), se = plane_std(grain_of(resynth, c.clean, p));
        std::printf("[ measured ] plane %d: true std %.3f, re-synthesized %.3f\n", p, st, se);
        EXPECT_NEAR(se / st, 1.0, 0.10) << "plane " << p;
    }
}

TEST(ForeignGrain, LumaOnlyGrainGivesNoChromaGrain) {
    for (int bd : {8, 10}) {
        const Clip c = make_clip({ChromaFormat::k420, bd}, {4.0, 0.0, 0.0}, true);
        const auto est = analyse<analysis::Av1Estimate>(c, GrainModel::kAv1, false);
        ASSERT_EQ(est.params.apply_grain, 1);
        const auto resynth = resynthesize_av1(est.params, c.clean);
        for (int p = 1; p < 3; p++) {
            const auto& r = est.components[p];
            double peak = 0;
            for (const auto& pt : r.points) peak = std::max(peak, pt.level);
            std::printf("[ measured ] %d-bit plane %d: %s%s (largest level %.3f)\n", bd, p, r.present ? "grain" : "no grain; ",
                        r.note.c_str(), peak);
            const double se = plane_std(grain_of(resynth, c.clean, p)) / (1 << (bd - 8));
            std::printf("[ measured ] %d-bit plane %d: re-synthesized chroma std %.3f (8-bit scale)\n", bd, p, se);
            EXPECT_LE(se, 0.3) << bd << "-bit plane " << p;
        }
    }
}

// Grain clipped to the studio range (camera pipelines clip R'G'B'; libaom's test vectors set
// clip_to_restricted_range): the estimate must clip alike, or the re-synthesized grain near
// black is too strong (+18-24 % in docs/ANALYSIS.md's darkest band). Unclipped grain that
// crosses the bounds must not be clipped.
TEST(ForeignGrain, Av1GrainClippedToTheStudioRangeIsClippedAlike) {
    for (bool clip : {true, false}) {
        Clip c;
        const PixelFormat fmt{ChromaFormat::k420, 8};
        for (int k = 0; k < kFrames; k++) {
            c.clean.push_back(analysis_test::make_clean_picture(kWidth, kHeight, fmt, 19, 230));
            FrameBuffer g = add_noise(c.clean.back(), {4.0, 2.0, 0.0}, 301 + k);
            FrameView v = g.view();
            for (int p = 0; clip && p < 3; p++) {
                cv::Mat m = plane_to_float(v, p);
                cv::min(cv::max(m, 16.0), p == 0 ? 235.0 : 240.0, m);
                analysis::float_to_plane(m, v, p);
            }
            c.grainy.push_back(std::move(g));
        }
        const auto est = analyse<analysis::Av1Estimate>(c, GrainModel::kAv1, false);
        ASSERT_EQ(est.params.apply_grain, 1);
        std::printf("[ measured ] %s grain: clip_to_restricted_range %d, %.3f %% of the samples on the bounds\n",
                    clip ? "clipped" : "unclipped", est.params.clip_to_restricted_range, 100 * est.on_legal_bound);
        EXPECT_EQ(est.params.clip_to_restricted_range, clip ? 1 : 0);
        if (!clip) continue;
        const auto resynth = resynthesize_av1(est.params, c.clean);
        const double st = mean_luma_band_std(c.grainy, c.clean, 16, 31), se = mean_luma_band_std(resynth, c.clean, 16, 31);
        std::printf("[ measured ] band 16..31: true %.2f, re-synthesized %.2f\n", st, se);
        EXPECT_NEAR(se / st, 1.0, 0.06);
    }
}

// A dark patch 48 samples wide: 32x32 level blocks do not fit beside the flat mask's margins,
// so the darkest band had no observation and took the level of the next one (re-synthesized
// at half its level). The AV1 estimate observes it and gets its level.
TEST(ForeignGrain, Av1ObservesNarrowDarkPatches) {
    constexpr int kPatchWidth = 48;  // 32x32 blocks need 64 beside the mask's margins
    Clip c;
    const PixelFormat fmt{ChromaFormat::k420, 8};
    for (int k = 0; k < kFrames; k++) {
        FrameBuffer clean = analysis_test::make_clean_picture(kWidth, kHeight, fmt, 100, 200);
        FrameView v = clean.view();
        cv::Mat y = plane_to_float(v, 0);
        y(cv::Rect(40, 40, kPatchWidth, 176)).setTo(40.0);
        analysis::float_to_plane(y, v, 0);
        FrameBuffer g = add_noise(clean, {4.0, 0.0, 0.0}, 401 + k);
        // Twice the grain on the patch: its level differs from the rest of the curve.
        FrameView gv = g.view();
        cv::Mat gy = plane_to_float(gv, 0);
        gy(cv::Rect(40, 40, kPatchWidth, 176)) = gy(cv::Rect(40, 40, kPatchWidth, 176)) * 2.0 - 40.0;
        analysis::float_to_plane(gy, gv, 0);
        c.clean.push_back(std::move(clean));
        c.grainy.push_back(std::move(g));
    }
    const auto est = analyse<analysis::Av1Estimate>(c, GrainModel::kAv1, false);
    ASSERT_EQ(est.params.apply_grain, 1);
    const auto& curve = est.components[0].curve;
    std::printf("[ measured ] observed luma %d..%d\n", curve.observed_low, curve.observed_high);
    EXPECT_LE(curve.observed_low, 40);
    const auto resynth = resynthesize_av1(est.params, c.clean);
    const double st = mean_luma_band_std(c.grainy, c.clean, 32, 47), se = mean_luma_band_std(resynth, c.clean, 32, 47);
    std::printf("[ measured ] the patch (band 32..47): true %.2f, re-synthesized %.2f\n", st, se);
    EXPECT_NEAR(se / st, 1.0, 0.10);
}

// Chroma grain std over the chroma samples whose co-located clean luma (4:2:0) or own clean
// chroma value lies in lo..hi, over the pictures.
double chroma_std_where(const std::vector<FrameBuffer>& grainy, const std::vector<FrameBuffer>& clean, int p, bool by_luma,
                        int lo, int hi) {
    double ss = 0;
    long long n = 0;
    for (std::size_t k = 0; k < grainy.size(); k++) {
        const cv::Mat g = plane_to_float(const_cast<FrameBuffer&>(grainy[k]).view(), p) -
                          plane_to_float(const_cast<FrameBuffer&>(clean[k]).view(), p);
        const cv::Mat index = by_luma ? plane_to_float(const_cast<FrameBuffer&>(clean[k]).view(), 0)
                                      : plane_to_float(const_cast<FrameBuffer&>(clean[k]).view(), p);
        const int s = by_luma ? 1 : 0;
        for (int y = 0; y < g.rows; y++)
            for (int x = 0; x < g.cols; x++) {
                const float v = index.at<float>(y << s, x << s);
                if (v < lo || v > hi) continue;
                ss += double(g.at<float>(y, x)) * g.at<float>(y, x);
                n++;
            }
    }
    return n ? std::sqrt(ss / double(n)) : 0.0;
}

// Chroma grain whose level follows the luma (camera noise; libaom's test grain indexes chroma
// by the luma average): indexed by the chroma value alone, the curve averaged over the luma
// and the darkest luma patch got twice its chroma grain. The estimate indexes chroma by the
// luma (cb_luma_mult) and gets each luma band's level; grain that follows the chroma value
// keeps the chroma index.
TEST(ForeignGrain, Av1ChromaGrainIndexedByWhatItFollows) {
    const PixelFormat fmt{ChromaFormat::k420, 8};
    for (bool follows_luma : {true, false}) {
        Clip c;
        for (int k = 0; k < kFrames; k++) {
            c.clean.push_back(analysis_test::make_clean_picture(kWidth, kHeight, fmt));
            FrameBuffer g = add_noise(c.clean.back(), {3.0, 0.0, 0.0}, 501 + k);
            FrameView v = g.view();
            const cv::Mat luma = plane_to_float(c.clean.back().view(), 0);
            for (int p = 1; p < 3; p++) {
                cv::Mat m = plane_to_float(v, p);
                const cv::Mat own = m.clone();
                const cv::Mat n = noise_plane(m.size(), 1.0, 0.0, 601 + 7 * k + p);
                for (int y = 0; y < m.rows; y++)
                    for (int x = 0; x < m.cols; x++) {
                        const double t = follows_luma ? (luma.at<float>(2 * y, 2 * x) - 24) / 208.0
                                                      : (own.at<float>(y, x) - 64) / 128.0;
                        m.at<float>(y, x) += float((0.5 + 3.0 * t) * n.at<float>(y, x));
                    }
                analysis::float_to_plane(m, v, p);
            }
            c.grainy.push_back(std::move(g));
        }
        const auto est = analyse<analysis::Av1Estimate>(c, GrainModel::kAv1, false);
        ASSERT_EQ(est.params.apply_grain, 1);
        const auto resynth = resynthesize_av1(est.params, c.clean);
        for (int p = 1; p < 3; p++) {
            const auto& r = est.components[p];
            ASSERT_TRUE(r.present) << "plane " << p;
            std::printf("[ measured ] grain following the %s, plane %d: luma share %d/4 (spread by share:", follows_luma ? "luma" : "chroma", p,
                        r.luma_quarters);
            for (double x : r.spread_by_luma_quarters) std::printf(" %.3f", x);
            std::printf(")\n");
            EXPECT_EQ(r.luma_quarters, follows_luma ? 4 : 0) << "plane " << p;
            // the two ends of what the grain follows (luma patches 24..70 and 186..232; chroma 64..96 and 160..192)
            const int bands[2][2] = {{follows_luma ? 24 : 64, follows_luma ? 70 : 96}, {follows_luma ? 186 : 160, follows_luma ? 232 : 192}};
            for (const auto& b : bands) {
                const double st = chroma_std_where(c.grainy, c.clean, p, follows_luma, b[0], b[1]),
                             se = chroma_std_where(resynth, c.clean, p, follows_luma, b[0], b[1]);
                std::printf("[ measured ]   %s %d..%d: true %.3f, re-synthesized %.3f\n", follows_luma ? "luma" : "chroma", b[0], b[1], st, se);
                EXPECT_NEAR(se / st, 1.0, 0.10) << "plane " << p << " band " << b[0];
            }
        }
    }
}

}  // namespace
}  // namespace filmgrain

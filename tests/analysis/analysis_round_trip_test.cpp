// Round trips: grain synthesized with known parameters onto clean pictures, analysed, and
// re-synthesized with the estimate. What must hold (the acceptance of issue 8):
//  - the re-synthesized grain's standard deviation per intensity band is within 10% of the
//    original's (bands inside the original's intervals / between its points);
//  - FGC: estimated cut-offs within +-1 of the true ones;
//  - AV1: the estimated AR filter's power spectrum within kSpectrumTolerance (mean relative
//    deviation of the normalized spectra) of the true filter's;
//  - grain-free content yields parameters that disable synthesis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/av1_estimation.hpp"
#include "analysis/grain_analyzer.hpp"
#include "av1/av1_picture_synthesis.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "synthetic_content.hpp"

namespace filmgrain {
namespace {

using analysis::GrainAnalyzer;
using analysis::GrainModel;
using analysis_test::grain_std_in_band;
using analysis_test::make_clean_picture;

constexpr double kLevelTolerance = 0.10;     // relative, per intensity band
constexpr int kCutoffTolerance = 1;          // FGC cut-off units
constexpr double kSpectrumTolerance = 0.15;  // mean |S_est - S_true| / mean S_true
constexpr int kWidth = 384, kHeight = 256;

struct Band {
    int plane, lo, hi;
};

FgcIntensityInterval interval(int lo, int hi, int value, int h, int v) {
    FgcIntensityInterval iv;
    iv.intensity_interval_lower_bound = lo;
    iv.intensity_interval_upper_bound = hi;
    iv.comp_model_value = {value, h, v, 0, 0, 0};
    return iv;
}

std::vector<FrameBuffer> synthesize_fgc(const FgcParams& p, const FrameBuffer& clean, int frames) {
    FgcOptions o;
    FgcStreamSynthesis s(o);
    std::vector<FrameBuffer> out;
    for (int k = 0; k < frames; k++) {
        FrameBuffer g = clean;
        s.receive_sei(p);
        s.apply(const_cast<FrameBuffer&>(clean).view(), g.view(), FgcPictureIds{k, 0});
        out.push_back(std::move(g));
    }
    return out;
}

std::vector<FrameBuffer> synthesize_av1(const Av1FilmGrainParams& p, const FrameBuffer& clean, int frames) {
    std::vector<FrameBuffer> out;
    for (int k = 0; k < frames; k++) {
        FrameBuffer g = clean;
        Av1FilmGrainParams q = p;
        q.grain_seed = (p.grain_seed + 1237 * k) & 0xFFFF;
        av1::apply_film_grain(q, const_cast<FrameBuffer&>(clean).view(), g.view(), 2);
        out.push_back(std::move(g));
    }
    return out;
}

// Pooled standard deviation of the grain in a band over all pictures.
double band_std(const std::vector<FrameBuffer>& grainy, const FrameBuffer& clean, const Band& b) {
    double ss = 0;
    for (const auto& g : grainy) {
        const double s = grain_std_in_band(g, clean, b.plane, b.lo, b.hi);
        ss += s * s;
    }
    return std::sqrt(ss / grainy.size());
}


void expect_levels(const std::vector<FrameBuffer>& original, const std::vector<FrameBuffer>& resynth,
                   const FrameBuffer& clean, const std::vector<Band>& bands, const std::string& what) {
    for (const auto& b : bands) {
        const double so = band_std(original, clean, b), sr = band_std(resynth, clean, b);
        ASSERT_GT(so, 0.0);
        const double rel = sr / so - 1.0;
        std::printf("[ measured ] %s plane %d band %d..%d: original std %.3f, re-synthesized %.3f, error %+.1f%%\n",
                    what.c_str(), b.plane, b.lo, b.hi, so, sr, 100 * rel);
        EXPECT_LE(std::fabs(rel), kLevelTolerance) << what << " plane " << b.plane << " band " << b.lo << ".." << b.hi;
    }
}

struct FgcCase {
    std::string name;
    int bit_depth;
    FgcParams params;
    std::vector<Band> bands;
    bool supply_clean = true;
    int frames = 6;
};

void run_fgc_case(const FgcCase& c) {
    const PixelFormat fmt{ChromaFormat::k420, c.bit_depth};
    const FrameBuffer clean = make_clean_picture(kWidth, kHeight, fmt);
    const auto grainy = synthesize_fgc(c.params, clean, c.frames);
    analysis::AnalysisOptions o;
    o.model = GrainModel::kFgc;
    GrainAnalyzer a(o, fmt, kWidth, kHeight);
    for (const auto& g : grainy) a.add_frame(g, c.supply_clean ? &clean : nullptr);
    a.finish();
    const auto est = a.estimate_fgc();
    for (int comp = 0; comp < 3; comp++)
        std::printf("[ measured ] %s component %d: %zu level observations, %d DCT blocks\n", c.name.c_str(), comp,
                    a.observations()[comp].blocks.size(), a.observations()[comp].total_dct_blocks());
    ASSERT_FALSE(est.params.film_grain_characteristics_cancel_flag) << c.name << ": grain not found";
    for (int comp = 0; comp < 3; comp++) {
        const auto& truth = c.params.comp[comp];
        const auto& got = est.params.comp[comp];
        ASSERT_EQ(truth.comp_model_present_flag, got.comp_model_present_flag) << c.name << " component " << comp;
        if (!truth.comp_model_present_flag) continue;
        const int th = truth.intervals[0].comp_model_value[1], tv = truth.intervals[0].comp_model_value[2];
        for (const auto& iv : got.intervals) {
            const int gh = got.num_model_values_minus1 >= 1 ? iv.comp_model_value[1] : 8;
            const int gv = got.num_model_values_minus1 >= 2 ? iv.comp_model_value[2] : gh;
            std::printf("[ measured ] %s component %d interval %d..%d: cut-offs (%d, %d), true (%d, %d)\n", c.name.c_str(),
                        comp, iv.intensity_interval_lower_bound, iv.intensity_interval_upper_bound, gh, gv, th, tv);
            EXPECT_LE(std::abs(gh - th), kCutoffTolerance) << c.name << " component " << comp << " horizontal";
            EXPECT_LE(std::abs(gv - tv), kCutoffTolerance) << c.name << " component " << comp << " vertical";
        }
    }
    const auto resynth = synthesize_fgc(est.params, clean, c.frames);
    expect_levels(grainy, resynth, clean, c.bands, c.name);
}

TEST(AnalysisRoundTrip, FgcTwoIntervals8Bit) {
    FgcCase c{"fgc-8bit-2-intervals", 8, {}, {{0, 40, 112}, {0, 144, 220}, {1, 90, 170}}};
    c.params.log2_scale_factor = 5;
    c.params.comp[0] = {true, 2, {interval(0, 127, 110, 8, 8), interval(128, 255, 180, 8, 8)}};
    c.params.comp[1] = {true, 2, {interval(0, 255, 120, 6, 6)}};
    run_fgc_case(c);
}

TEST(AnalysisRoundTrip, FgcStrongAnisotropic10Bit) {
    FgcCase c{"fgc-10bit-strong-12x6", 10, {}, {{0, 40, 220}}};
    c.params.log2_scale_factor = 6;
    c.params.comp[0] = {true, 2, {interval(0, 255, 700, 12, 6)}};
    run_fgc_case(c);
}

TEST(AnalysisRoundTrip, FgcWeakCoarse8Bit) {
    FgcCase c{"fgc-8bit-weak-4x10", 8, {}, {{0, 40, 220}}};
    c.params.log2_scale_factor = 5;
    c.params.comp[0] = {true, 2, {interval(0, 255, 60, 4, 10)}};
    run_fgc_case(c);
}

TEST(AnalysisRoundTrip, FgcTemporalDenoiser8Bit) {
    FgcCase c{"fgc-8bit-temporal-denoiser", 8, {}, {{0, 40, 112}, {0, 144, 220}}};
    c.params.log2_scale_factor = 5;
    c.params.comp[0] = {true, 2, {interval(0, 127, 110, 10, 10), interval(128, 255, 180, 10, 10)}};
    c.supply_clean = false;
    c.frames = 9;
    run_fgc_case(c);
}

struct Av1Case {
    std::string name;
    int bit_depth;
    Av1FilmGrainParams params;
    std::vector<Band> bands;
    bool supply_clean = true;
    int frames = 6;
};

void set_points(int* values, int* scalings, int* count, std::vector<std::pair<int, int>> pts) {
    *count = int(pts.size());
    for (std::size_t i = 0; i < pts.size(); i++) values[i] = pts[i].first, scalings[i] = pts[i].second;
}

void run_av1_case(const Av1Case& c) {
    const PixelFormat fmt{ChromaFormat::k420, c.bit_depth};
    const FrameBuffer clean = make_clean_picture(kWidth, kHeight, fmt);
    const auto grainy = synthesize_av1(c.params, clean, c.frames);
    analysis::AnalysisOptions o;
    o.model = GrainModel::kAv1;
    GrainAnalyzer a(o, fmt, kWidth, kHeight);
    for (const auto& g : grainy) a.add_frame(g, c.supply_clean ? &clean : nullptr);
    a.finish();
    const auto est = a.estimate_av1();
    ASSERT_EQ(est.params.apply_grain, 1) << c.name << ": grain not found";
    // The AR filters compared through their spectra (what the viewer sees), not coefficient by
    // coefficient: different filters can shape grain alike.
    auto real_coeffs = [](const Av1FilmGrainParams& p) {
        std::vector<double> v;
        for (int i = 0; i < p.num_pos_luma(); i++)
            v.push_back((p.ar_coeffs_y_plus_128[i] - 128) / std::ldexp(1.0, p.ar_coeff_shift_minus_6 + 6));
        return v;
    };
    const auto st = analysis::ar_power_spectrum(real_coeffs(c.params), c.params.ar_coeff_lag, 32);
    const auto se = analysis::ar_power_spectrum(real_coeffs(est.params), est.params.ar_coeff_lag, 32);
    double dev = 0;
    for (std::size_t i = 0; i < st.size(); i++) dev += std::fabs(se[i] - st[i]);
    dev /= double(st.size());  // spectra have mean 1
    std::string by_lag;
    for (double d : est.components[0].spectrum_error_by_lag) by_lag += " " + std::to_string(d).substr(0, 5);
    std::printf("[ measured ] %s: true lag %d, estimated lag %d, spectrum deviation %.3f (lag selection:%s)\n",
                c.name.c_str(), c.params.ar_coeff_lag, est.params.ar_coeff_lag, dev, by_lag.c_str());
    EXPECT_LE(dev, kSpectrumTolerance) << c.name;
    const auto resynth = synthesize_av1(est.params, clean, c.frames);
    expect_levels(grainy, resynth, clean, c.bands, c.name);
}

Av1FilmGrainParams av1_base() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 1234;
    p.overlap_flag = 1;
    p.cb_mult = p.cr_mult = 192;
    p.cb_luma_mult = p.cr_luma_mult = 128;
    return p;
}

TEST(AnalysisRoundTrip, Av1WhiteLag0With8BitChroma) {
    Av1Case c{"av1-8bit-lag0", 8, av1_base(), {{0, 30, 100}, {0, 120, 220}, {1, 90, 170}}};
    set_points(c.params.point_y_value.data(), c.params.point_y_scaling.data(), &c.params.num_y_points,
               {{0, 30}, {128, 60}, {255, 40}});
    set_points(c.params.point_cb_value.data(), c.params.point_cb_scaling.data(), &c.params.num_cb_points,
               {{0, 40}, {255, 40}});
    set_points(c.params.point_cr_value.data(), c.params.point_cr_scaling.data(), &c.params.num_cr_points,
               {{0, 20}, {255, 50}});
    run_av1_case(c);
}

TEST(AnalysisRoundTrip, Av1Lag2At10Bit) {
    Av1Case c{"av1-10bit-lag2", 10, av1_base(), {{0, 30, 100}, {0, 120, 220}}};
    c.params.grain_scaling_minus_8 = 1;
    c.params.ar_coeff_lag = 2;
    c.params.ar_coeff_shift_minus_6 = 2;  // shift 8: coefficient sum 0.62, a stable filter
    const int coeffs[12] = {4, -6, 10, -6, 4, 8, 20, 30, 20, 8, 36, 30};
    for (int i = 0; i < 12; i++) c.params.ar_coeffs_y_plus_128[i] = 128 + coeffs[i];
    set_points(c.params.point_y_value.data(), c.params.point_y_scaling.data(), &c.params.num_y_points,
               {{0, 120}, {255, 120}});
    run_av1_case(c);
}

TEST(AnalysisRoundTrip, Av1Lag3Strong8Bit) {
    Av1Case c{"av1-8bit-lag3", 8, av1_base(), {{0, 30, 100}, {0, 120, 220}}};
    c.params.ar_coeff_lag = 3;
    c.params.ar_coeff_shift_minus_6 = 3;  // shift 9: coefficient sum 0.59
    const int coeffs[24] = {2, 4, 6, 8, 6, 4, 2, 4, 8, 12, 16, 12, 8, 4, 6, 12, 24, 32, 24, 12, 6, 12, 30, 50};
    for (int i = 0; i < 24; i++) c.params.ar_coeffs_y_plus_128[i] = 128 + coeffs[i];
    set_points(c.params.point_y_value.data(), c.params.point_y_scaling.data(), &c.params.num_y_points,
               {{0, 40}, {100, 80}, {200, 50}});
    run_av1_case(c);
}

TEST(AnalysisRoundTrip, Av1TemporalDenoiser8Bit) {
    Av1Case c{"av1-8bit-temporal-denoiser", 8, av1_base(), {{0, 30, 100}, {0, 120, 220}}};
    c.params.ar_coeff_lag = 1;
    c.params.ar_coeff_shift_minus_6 = 1;
    const int coeffs[4] = {10, 24, 10, 30};
    for (int i = 0; i < 4; i++) c.params.ar_coeffs_y_plus_128[i] = 128 + coeffs[i];
    set_points(c.params.point_y_value.data(), c.params.point_y_scaling.data(), &c.params.num_y_points,
               {{0, 50}, {255, 90}});
    c.supply_clean = false;
    c.frames = 9;
    run_av1_case(c);
}

// Grain-free content: parameters that disable synthesis, through the supplied-denoised path
// (exactly zero grain) and through the temporal denoiser.
TEST(AnalysisRoundTrip, NoGrainDisablesSynthesis) {
    for (int bd : {8, 10})
        for (bool supply : {true, false}) {
            const PixelFormat fmt{ChromaFormat::k420, bd};
            const FrameBuffer clean = make_clean_picture(kWidth, kHeight, fmt);
            for (GrainModel m : {GrainModel::kFgc, GrainModel::kAv1}) {
                analysis::AnalysisOptions o;
                o.model = m;
                GrainAnalyzer a(o, fmt, kWidth, kHeight);
                for (int k = 0; k < 5; k++) a.add_frame(clean, supply ? &clean : nullptr);
                a.finish();
                if (m == GrainModel::kFgc) {
                    EXPECT_TRUE(a.estimate_fgc().params.film_grain_characteristics_cancel_flag) << bd << " " << supply;
                } else {
                    EXPECT_EQ(a.estimate_av1().params.apply_grain, 0) << bd << " " << supply;
                }
            }
        }
}

}  // namespace
}  // namespace filmgrain

#include "analysis/av1_estimation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "analysis/grain_level.hpp"
#include "av1/av1_picture_synthesis.hpp"
#include "av1/grain_template_generation.hpp"
#include "core/frame_buffer.hpp"

namespace filmgrain::analysis {
namespace {

constexpr int kCalibrationSize = 256;
constexpr int kCalibrationSeeds = 6;  // templates are random: average over realizations
constexpr double kMinArEquations = 500;
// The chroma index takes a luma share only when it explains the blocks' levels clearly
// better: their spread around its curve at least this much smaller than around the chroma
// sample's own (the blocks are the same, so the comparison's noise is far below this).
constexpr double kLumaShareMinGain = 0.05;

std::vector<int> lag_indices(int lag, bool with_luma) {
    std::vector<int> idx;
    const auto& offs = ar_offsets_lag3();
    for (int i = 0; i < kMaxArTerms - 1; i++)
        if (std::abs(offs[i].dy) <= lag && std::abs(offs[i].dx) <= lag) idx.push_back(i);
    if (with_luma) idx.push_back(kMaxArTerms - 1);
    return idx;
}

double template_std(const av1::GrainTemplate& t) {
    double s = 0, ss = 0;
    int n = 0;
    for (int y = av1::kArPadding; y < t.height; y++)
        for (int x = av1::kArPadding; x < t.width - av1::kArPadding; x++) {
            s += t.at(y, x);
            ss += double(t.at(y, x)) * t.at(y, x);
            n++;
        }
    const double m = s / n;
    return std::sqrt(std::max(0.0, ss / n - m * m));
}

// Quantizes real coefficients with the finest shift (6..9) that keeps them in -128..127.
int choose_ar_shift(const std::array<std::vector<double>, 3>& coeffs) {
    double peak = 0;
    for (const auto& v : coeffs)
        for (double c : v) peak = std::max(peak, std::fabs(c));
    for (int s = 9; s >= 6; s--)
        if (peak * std::ldexp(1.0, s) <= 127.0) return s;
    return 6;
}

// Pooled standard deviation of the blocks' levels within the curve's sub-ranges: what the
// index leaves unexplained (one degree of freedom per sub-range, so finer indices gain
// nothing by spreading the blocks over more sub-ranges).
double within_sub_range_spread(const LevelCurve& curve) {
    double ss = 0, dof = 0;
    for (int s = 0; s < kSubRanges; s++)
        if (curve.sub_range_count[s] > 1) {
            ss += (curve.sub_range_count[s] - 1) * curve.sub_range_spread[s] * curve.sub_range_spread[s];
            dof += curve.sub_range_count[s] - 1;
        }
    return dof > 0 ? std::sqrt(ss / dof) : 0.0;
}

}  // namespace

std::vector<BlockSample> blocks_by_chroma_index(const std::vector<BlockSample>& blocks, int luma_quarters) {
    std::vector<BlockSample> out = blocks;
    for (BlockSample& b : out) b.intensity8 = ((4 - luma_quarters) * b.intensity8 + luma_quarters * b.luma8) / 4;
    return out;
}

std::vector<double> solve_ar(const ArEquations& eq, int lag, bool with_luma, double* residual) {
    const auto idx = lag_indices(lag, with_luma);
    const int k = int(idx.size());
    std::vector<double> a(k, 0.0);
    if (eq.n <= 0) {
        if (residual) *residual = 1.0;
        return a;
    }
    if (k == 0) {
        if (residual) *residual = eq.yty / eq.n;
        return a;
    }
    cv::Mat A(k, k, CV_64F), b(k, 1, CV_64F);
    for (int i = 0; i < k; i++) {
        b.at<double>(i) = eq.xty.at<double>(idx[i]);
        for (int j = 0; j < k; j++) A.at<double>(i, j) = eq.xtx.at<double>(idx[i], idx[j]);
        A.at<double>(i, i) += 1e-6 * eq.n;  // a whisper of ridge keeps degenerate data solvable
    }
    cv::Mat sol;
    cv::solve(A, b, sol, cv::DECOMP_CHOLESKY);
    for (int i = 0; i < k; i++) a[i] = sol.at<double>(i);
    double r = eq.yty;
    for (int i = 0; i < k; i++) {
        r -= 2 * a[i] * b.at<double>(i);
        for (int j = 0; j < k; j++) r += a[i] * a[j] * eq.xtx.at<double>(idx[i], idx[j]);
    }
    if (residual) *residual = std::max(0.0, r / eq.n);
    return a;
}

std::vector<double> ar_power_spectrum(const std::vector<double>& coefficients, int lag, int n) {
    const auto idx = lag_indices(lag, false);
    const auto& offs = ar_offsets_lag3();
    std::vector<double> s(std::size_t(n) * n);
    double sum = 0;
    for (int v = 0; v < n; v++)
        for (int u = 0; u < n; u++) {
            const double wy = 2 * M_PI * v / n, wx = 2 * M_PI * u / n;
            std::complex<double> d = 1.0;
            for (std::size_t i = 0; i < idx.size(); i++)
                d -= coefficients[i] * std::polar(1.0, -(wy * offs[idx[i]].dy + wx * offs[idx[i]].dx));
            s[std::size_t(v) * n + u] = 1.0 / std::norm(d);
            sum += s[std::size_t(v) * n + u];
        }
    for (double& x : s) x *= double(s.size()) / sum;
    return s;
}

Av1FilmGrainParams av1_params_from_levels(const std::array<std::vector<LevelPoint>, 3>& points, int lag,
                                          const std::array<std::vector<double>, 3>& coefficients,
                                          const Av1Target& target, const std::array<int, 3>& luma_quarters) {
    const int num_planes = target.chroma == ChromaFormat::k400 ? 1 : 3;
    Av1FilmGrainParams p;
    bool any = false;
    for (int c = 0; c < num_planes; c++) any |= !points[c].empty();
    if (!any) return p;  // apply_grain = 0
    p.apply_grain = 1;
    p.grain_seed = target.grain_seed & 0xFFFF;
    p.update_grain = 1;
    p.ar_coeff_lag = lag;
    p.overlap_flag = 1;
    // Chroma scaling index (AV1 7.18.3.5): (cb_mult - 128) weighs the chroma sample,
    // (cb_luma_mult - 128) the luma average, in 64ths; no offset.
    p.cb_mult = 192 - 16 * luma_quarters[1];
    p.cb_luma_mult = 128 + 16 * luma_quarters[1];
    p.cr_mult = 192 - 16 * luma_quarters[2];
    p.cr_luma_mult = 128 + 16 * luma_quarters[2];
    p.cb_offset = p.cr_offset = 256;
    const int shift = choose_ar_shift(coefficients);
    p.ar_coeff_shift_minus_6 = shift - 6;
    auto q = [&](double c) { return std::clamp(int(std::lround(c * std::ldexp(1.0, shift))), -128, 127) + 128; };
    const bool luma = !points[0].empty();
    // Placeholder constant scalings: the calibration below needs any non-zero function.
    p.num_y_points = luma ? 2 : 0;
    if (luma) {
        p.point_y_value[0] = 0, p.point_y_value[1] = 255;
        p.point_y_scaling[0] = p.point_y_scaling[1] = 64;
        for (std::size_t i = 0; i < coefficients[0].size() && i < 24; i++) p.ar_coeffs_y_plus_128[i] = q(coefficients[0][i]);
    }
    int* nps[3] = {&p.num_y_points, &p.num_cb_points, &p.num_cr_points};
    int* vals[3] = {p.point_y_value.data(), p.point_cb_value.data(), p.point_cr_value.data()};
    int* scal[3] = {p.point_y_scaling.data(), p.point_cb_scaling.data(), p.point_cr_scaling.data()};
    std::array<int, 25>* cc[3] = {nullptr, &p.ar_coeffs_cb_plus_128, &p.ar_coeffs_cr_plus_128};
    for (int c = 1; c < num_planes; c++) {
        if (points[c].empty()) continue;
        *nps[c] = 2;
        vals[c][0] = 0, vals[c][1] = 255;
        scal[c][0] = scal[c][1] = 64;
        const auto& co = coefficients[c];
        const int npos = p.num_pos_luma();
        for (int i = 0; i < npos && i < int(co.size()); i++) (*cc[c])[i] = q(co[i]);
        if (luma && int(co.size()) > npos) (*cc[c])[npos] = q(co[npos]);
    }
    // 4:2:0 signals both chroma functions or neither (AV1 5.9.30): a grain-free one gets a
    // single zero point, for the calibration and for the result.
    const auto pair_chroma_functions = [&] {
        if (target.chroma != ChromaFormat::k420 || (p.num_cb_points == 0) == (p.num_cr_points == 0)) return;
        const int c = p.num_cb_points == 0 ? 1 : 2;
        *nps[c] = 1;
        vals[c][0] = 128;
        scal[c][0] = 0;
    };
    pair_chroma_functions();
    // Grain level per unit of scaling at scaling_shift 8, per plane, over several seeds.
    FrameBuffer clean(kCalibrationSize, kCalibrationSize, {target.chroma, target.bit_depth}), grainy;
    fill_frame(clean.view(), 128 << (clean.format().bit_depth - 8));
    grainy = clean;
    std::array<double, 3> gain{};
    for (int s = 0; s < kCalibrationSeeds; s++) {
        Av1FilmGrainParams cp = p;
        cp.grain_seed = (p.grain_seed + 4099 * s) & 0xFFFF;
        av1::apply_film_grain(cp, clean.view(), grainy.view(), 2);
        for (int c = 0; c < num_planes; c++)
            if (*nps[c] > 0) gain[c] += measure_grain_level(grainy.view(), clean.view(), c, kAv1LevelBlock) / 64.0 / kCalibrationSeeds;
    }
    // scaling_shift: the finest (largest) for which every scaling value fits in 8 bits.
    double need = 0;
    for (int c = 0; c < num_planes; c++)
        for (const auto& pt : points[c])
            if (gain[c] > 0) need = std::max(need, pt.level / gain[c]);
    int scaling_shift = 8;
    for (int s = 11; s >= 8; s--)
        if (need * std::ldexp(1.0, s - 8) <= 255.0) {
            scaling_shift = s;
            break;
        }
    p.grain_scaling_minus_8 = scaling_shift - 8;
    for (int c = 0; c < num_planes; c++) {
        *nps[c] = 0;
        if (points[c].empty() || gain[c] <= 0) continue;
        int n = 0;
        for (const auto& pt : points[c]) {
            vals[c][n] = pt.value;
            scal[c][n] = std::clamp(int(std::lround(pt.level / gain[c] * std::ldexp(1.0, scaling_shift - 8))), 0, 255);
            n++;
        }
        bool nonzero = false;
        for (int i = 0; i < n; i++) nonzero |= scal[c][i] > 0;
        *nps[c] = nonzero ? n : 0;
    }
    pair_chroma_functions();
    if (p.num_y_points == 0) {
        // Without luma grain, chroma filters have no luma term and the luma filter is unused.
        for (int c = 1; c < 3; c++) (*cc[c])[p.num_pos_luma()] = 128;
    }
    if (p.num_y_points == 0 && p.num_cb_points == 0 && p.num_cr_points == 0) return Av1FilmGrainParams{};
    return p;
}

Av1Estimate estimate_av1(const std::array<PlaneObservations, 3>& obs, const Av1Target& target) {
    Av1Estimate e;
    const int num_planes = target.chroma == ChromaFormat::k400 ? 1 : 3;
    const int max_points[3] = {14, 10, 10};
    std::array<std::vector<LevelPoint>, 3> points;
    std::array<int, 3> luma_quarters{};
    for (int c = 0; c < num_planes; c++) {
        auto& rep = e.components[c];
        rep.note = fit_component_curve(obs[c].blocks, target.bit_depth, rep.curve, c > 0);
        if (!rep.note.empty()) continue;
        if (c > 0) {
            // Chroma grain often follows the luma (camera noise is set by the light, which
            // luma carries; libaom's test grain indexes chroma by luma alone): index by the
            // mix of chroma sample and luma average that explains the blocks' levels best.
            std::array<LevelCurve, 5> curves;
            curves[0] = rep.curve;
            int best = 0;
            for (int q = 0; q <= 4; q++) {
                if (q > 0) curves[q] = fit_level_curve(blocks_by_chroma_index(obs[c].blocks, q));
                rep.spread_by_luma_quarters.push_back(within_sub_range_spread(curves[q]));
                if (curves[q].valid() && rep.spread_by_luma_quarters[q] < rep.spread_by_luma_quarters[best]) best = q;
            }
            if (rep.spread_by_luma_quarters[best] < (1 - kLumaShareMinGain) * rep.spread_by_luma_quarters[0]) {
                rep.luma_quarters = luma_quarters[c] = best;
                rep.curve = curves[best];
            }
        }
        rep.points = fit_piecewise_linear(rep.curve, max_points[c], target.accuracy);
        rep.error = worst_band_error(rep.curve, evaluate_piecewise_linear(rep.points), &rep.worst_band);
        rep.accurate = rep.error <= target.accuracy;
        rep.present = true;
        points[c] = rep.points;
    }
    // The lag, shared by all planes.
    const bool luma = e.components[0].present;
    int lag = 0;
    for (int c = 0; c < num_planes; c++) {
        auto& rep = e.components[c];
        if (!rep.present || obs[c].ar.n < kMinArEquations) continue;
        const bool with_luma = c > 0 && luma;
        for (int l = 0; l <= kMaxArLag; l++) {
            double r;
            solve_ar(obs[c].ar, l, with_luma, &r);
            rep.residual_by_lag.push_back(r);
        }
        // The shortest lag whose filter shapes the grain like the longest one (the residual
        // variance alone misses spectral shape). "Like" means within what the data can tell:
        // the spectra of the longest lag fitted to two halves of the blocks differ by the
        // fit's own noise, and the tolerance is never below that.
        const int longest = std::min(target.max_lag, kMaxArLag);
        const auto spectrum_deviation = [](const std::vector<double>& a, const std::vector<double>& b) {
            double dev = 0;
            for (std::size_t i = 0; i < a.size(); i++) dev += std::fabs(a[i] - b[i]);
            return dev / double(a.size());
        };
        const auto full = ar_power_spectrum(solve_ar(obs[c].ar, longest, false, nullptr), longest, 32);
        double tolerance = target.lag_spectrum_tolerance;
        if (obs[c].ar_halves[0].n >= kMinArEquations && obs[c].ar_halves[1].n >= kMinArEquations)
            tolerance = std::max(tolerance, spectrum_deviation(ar_power_spectrum(solve_ar(obs[c].ar_halves[0], longest, false, nullptr), longest, 32),
                                                               ar_power_spectrum(solve_ar(obs[c].ar_halves[1], longest, false, nullptr), longest, 32)));
        rep.lag_tolerance = tolerance;
        for (int l = 0; l <= longest; l++) {
            const double dev = spectrum_deviation(ar_power_spectrum(solve_ar(obs[c].ar, l, false, nullptr), l, 32), full);
            rep.spectrum_error_by_lag.push_back(dev);
            if (dev <= tolerance) {
                rep.own_lag = l;
                break;
            }
        }
        // Luma decides when it has grain (its fit has four times the equations of 4:2:0 chroma).
        if (c == 0 || !luma) lag = std::max(lag, rep.own_lag);
    }
    e.chosen_lag = lag;
    std::array<std::vector<double>, 3> coeffs;
    std::array<double, 3> residual{1.0, 1.0, 1.0};
    for (int c = 0; c < num_planes; c++) {
        if (!e.components[c].present) continue;
        const bool with_luma = c > 0 && luma;
        coeffs[c] = obs[c].ar.n >= kMinArEquations ? solve_ar(obs[c].ar, lag, with_luma, &residual[c])
                                                   : std::vector<double>(lag_indices(lag, with_luma).size(), 0.0);
    }
    if (luma && num_planes > 1) {
        // The chroma fits see unit-level grain; the template's luma term multiplies the luma
        // template, whose level differs: rescale by (innovation level / sqrt(residual)) over
        // the luma template's level (see the derivation in the analysis notes of README).
        Av1FilmGrainParams lp;
        lp.num_y_points = 1;
        lp.ar_coeff_lag = lag;
        const int shift = choose_ar_shift(coeffs);
        lp.ar_coeff_shift_minus_6 = shift - 6;
        double sd_innov = 0, sd_luma = 0;
        for (int s = 0; s < kCalibrationSeeds; s++) {
            lp.grain_seed = (target.grain_seed + 4099 * s) & 0xFFFF;
            Av1FilmGrainParams white = lp;
            white.ar_coeff_lag = 0;
            sd_innov += template_std(av1::generate_luma_template(white, target.bit_depth)) / kCalibrationSeeds;
            for (std::size_t i = 0; i < coeffs[0].size(); i++)
                lp.ar_coeffs_y_plus_128[i] = std::clamp(int(std::lround(coeffs[0][i] * std::ldexp(1.0, shift))), -128, 127) + 128;
            sd_luma += template_std(av1::generate_luma_template(lp, target.bit_depth)) / kCalibrationSeeds;
        }
        for (int c = 1; c < num_planes; c++)
            if (!coeffs[c].empty() && sd_luma > 0 && residual[c] > 0)
                coeffs[c].back() *= sd_innov / (std::sqrt(residual[c]) * sd_luma);
    }
    for (int c = 0; c < num_planes; c++) e.components[c].coefficients = coeffs[c];
    e.params = av1_params_from_levels(points, lag, coeffs, target, luma_quarters);
    long long outside = 0, on_bound = 0, total = 0;
    for (int c = 0; c < num_planes; c++) {
        outside += obs[c].outside_legal;
        on_bound += obs[c].on_legal_bound;
        total += obs[c].total_samples;
    }
    if (total > 0) {
        e.on_legal_bound = double(on_bound) / double(total);
        // Not one sample in a million outside, and at least one in ten thousand on a bound:
        // without clipping, grain near black or white would cross the bounds.
        e.clipped_to_legal_range = outside * 1000000 <= total && on_bound * 10000 >= total;
    }
    if (e.params.apply_grain) e.params.clip_to_restricted_range = e.clipped_to_legal_range ? 1 : 0;
    return e;
}

}  // namespace filmgrain::analysis

#include "analysis/fgc_estimation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <tuple>

#include "analysis/grain_level.hpp"
#include "analysis/plane_image.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"

namespace filmgrain::analysis {
namespace {

constexpr int kCalibrationSize = 256;
constexpr int kModelPlaneSize = 256;  // each plane of a cut-off pair's model: 16 blocks of 64x64
constexpr int kMinDctBlocksPerInterval = 8;

// The target synthesis measured on flat mid-grey pictures: grain level per unit of
// comp_model_value[0] (for a component, cut-off pair, scale factor and value), and the
// grain's short-lag correlation per cut-off. Measured exactly as the observations are, so the
// measurement's biases cancel.
class FgcCalibration {
public:
    explicit FgcCalibration(const FgcTarget& t) : t_(t), clean_(kCalibrationSize, kCalibrationSize, {t.chroma, t.bit_depth}) {
        fill_frame(clean_.view(), 128 << (clean_.format().bit_depth - 8));
        grainy_ = FrameBuffer(kCalibrationSize, kCalibrationSize, {t.chroma, t.bit_depth});
    }
    double gain(int c, int h, int v, int lsf, int value) {
        const auto key = std::make_tuple(c, h, v, lsf, value);
        if (auto it = cache_.find(key); it != cache_.end()) return it->second;
        synthesize(clean_, grainy_, c, h, v, lsf, value);
        const double g = measure_grain_level(grainy_.view(), clean_.view(), c, kFgcLevelBlock) / value;
        cache_[key] = g;
        return g;
    }
    const CutoffModels& cutoff_models(int c) {
        if (models_[c]) return *models_[c];
        const int w = kModelPlaneSize << (c > 0 ? chroma_shift_x(t_.chroma) : 0);
        const int h = kModelPlaneSize << (c > 0 ? chroma_shift_y(t_.chroma) : 0);
        FrameBuffer clean(w, h, {t_.chroma, t_.bit_depth}), grainy(w, h, {t_.chroma, t_.bit_depth});
        fill_frame(clean.view(), 128 << (t_.bit_depth - 8));
        CutoffModels m;
        for (int hc = kMinCutoff; hc <= kMaxCutoff; hc++)
            for (int vc = kMinCutoff; vc <= kMaxCutoff; vc++) {
                // About 5 code values of grain: no clipping, rounding small beside it. The level per
                // unit of a pair lies near the geometric mean of its axes' square pairs (the
                // template is a product of its axes' band limits), close enough for that.
                const int probe = 32 << (t_.bit_depth - 8);
                const double per_value = std::sqrt(gain(c, hc, hc, 5, probe) * gain(c, vc, vc, 5, probe));
                const int value = std::clamp(int(std::lround(5.0 * (1 << (t_.bit_depth - 8)) / per_value)), 1,
                                             255 << (t_.bit_depth - 8));
                synthesize(clean, grainy, c, hc, vc, 5, value);
                const cv::Mat grain = plane_to_float(grainy.view(), c) - plane_to_float(clean.view(), c);
                for (int y = 0; y + kDctBlock <= grain.rows; y += kDctBlock)
                    for (int x = 0; x + kDctBlock <= grain.cols; x += kDctBlock)
                        accumulate_block_lags(grain(cv::Rect(x, y, kDctBlock, kDctBlock)), m.pairs[hc][vc]);
            }
        models_[c] = m;
        return *models_[c];
    }

private:
    void synthesize(FrameBuffer& clean, FrameBuffer& grainy, int c, int h, int v, int lsf, int value) const {
        FgcParams p;
        p.log2_scale_factor = lsf;
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        FgcIntensityInterval iv;
        iv.intensity_interval_lower_bound = 0;
        iv.intensity_interval_upper_bound = 255;
        iv.comp_model_value = {value, h, v, 0, 0, 0};
        p.comp[c].intervals = {iv};
        FgcOptions o;
        o.flavour = t_.flavour;
        FgcStreamSynthesis synth(o);
        synth.receive_sei(p);
        synth.apply(clean.view(), grainy.view(), FgcPictureIds{0, 0});
    }
    FgcTarget t_;
    FrameBuffer clean_, grainy_;
    std::map<std::tuple<int, int, int, int, int>, double> cache_;
    std::array<std::optional<CutoffModels>, 3> models_;
};

int distinct_pairs(const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::pair<int, int>> distinct;
    for (const auto& pr : pairs)
        if (std::find(distinct.begin(), distinct.end(), pr) == distinct.end()) distinct.push_back(pr);
    return int(distinct.size());
}

// What the parameters signal where it departs from the levels asked for.
struct SignalledCutoffs {
    std::array<std::vector<std::pair<int, int>>, 3> cutoffs;  // per component and interval
    std::array<std::string, 3> raised;                        // why a component's cut-offs were raised
};

FgcParams params_from_levels(const std::array<FgcComponentLevels, 3>& levels, const FgcTarget& target, FgcCalibration& cal,
                             SignalledCutoffs* signalled = nullptr) {
    const int max_scale = 255 << (target.bit_depth - 8);
    const int num_comp = target.chroma == ChromaFormat::k400 ? 1 : 3;
    struct Item {
        int c;
        std::size_t i;
        int h, v;
        double level;
    };
    std::vector<Item> items;
    for (int c = 0; c < num_comp; c++)
        for (std::size_t i = 0; i < levels[c].intervals.size(); i++) {
            const auto [h, v] = levels[c].cutoffs[i];
            items.push_back({c, i, std::clamp(h, kMinCutoff, kMaxCutoff), std::clamp(v, kMinCutoff, kMaxCutoff),
                             levels[c].intervals[i].level});
        }
    if (items.empty()) return fgc_no_grain();
    // The value that gives an item its level at a scale factor: first from a small probe,
    // then measured at about that value, so that the synthesis' own limits show (strong,
    // coarse grain stops growing with the value: at the probe's rate it fitted in 255 with
    // log2_scale_factor 3 and came out 43 % weak).
    const int probe = std::max(1, 32 << (target.bit_depth - 8));
    auto value_for = [&](const Item& it, int lsf) {
        const double first = it.level / (cal.gain(it.c, it.h, it.v, 5, probe) * std::ldexp(1.0, 5 - lsf));
        if (first > max_scale) return first;
        const int at = std::clamp(int(std::lround(first)), 1, max_scale);
        return it.level / cal.gain(it.c, it.h, it.v, lsf, at);
    };
    // log2_scale_factor: the largest (finest) at which every value fits its range.
    int lsf = 2;
    for (int l = 7; l >= 2; l--) {
        bool fits = true;
        for (const auto& it : items) fits &= value_for(it, l) <= max_scale + 0.5;
        if (fits) {
            lsf = l;
            break;
        }
    }
    // Strong coarse grain can be out of reach: RDD 5 holds log2_scale_factor to 2..7 and the
    // value to 255, and a coarse cut-off's template has little amplitude per unit (Boolean
    // grain 1.2 px wide on chroma came out at cut-offs (2,2) 41 % weak). Such an item takes
    // the coarsest finer cut-offs that reach its level: grain a little finer shows less than
    // grain 40 % weak.
    for (Item& it : items) {
        const int h0 = it.h, v0 = it.v;
        const double need = value_for(it, lsf);
        while (value_for(it, lsf) > max_scale + 0.5 && (it.h < kMaxCutoff || it.v < kMaxCutoff)) {
            it.h = std::min(it.h + 1, kMaxCutoff);
            it.v = std::min(it.v + 1, kMaxCutoff);
        }
        if (!signalled) continue;
        signalled->cutoffs[it.c].push_back({it.h, it.v});
        if ((it.h != h0 || it.v != v0) && signalled->raised[it.c].empty()) {
            char text[200];
            std::snprintf(text, sizeof text,
                          "cut-offs raised from (%d,%d) to (%d,%d): there the level %.2f needs comp_model_value %.0f, "
                          "beyond %d at log2_scale_factor %d",
                          h0, v0, it.h, it.v, it.level / double(1 << (target.bit_depth - 8)), need, max_scale, lsf);
            signalled->raised[it.c] = text;
        }
    }
    FgcParams p;
    p.log2_scale_factor = lsf;
    p.film_grain_characteristics_persistence_flag = true;
    for (int c = 0; c < num_comp; c++) {
        auto& m = p.comp[c];
        for (const auto& it : items) {
            if (it.c != c) continue;
            const int value = std::clamp(int(std::lround(value_for(it, lsf))), 0, max_scale);
            if (value == 0) continue;
            FgcIntensityInterval iv;
            iv.intensity_interval_lower_bound = levels[c].intervals[it.i].lower;
            iv.intensity_interval_upper_bound = levels[c].intervals[it.i].upper;
            iv.comp_model_value = {value, it.h, it.v, 0, 0, 0};
            // Neighbours that quantize to the same model merge into one interval.
            if (!m.intervals.empty()) {
                auto& last = m.intervals.back();
                if (last.intensity_interval_upper_bound + 1 == iv.intensity_interval_lower_bound &&
                    last.comp_model_value == iv.comp_model_value) {
                    last.intensity_interval_upper_bound = iv.intensity_interval_upper_bound;
                    continue;
                }
            }
            m.intervals.push_back(iv);
        }
        if (m.intervals.empty()) continue;
        m.comp_model_present_flag = true;
        bool all_default = true, all_square = true;
        for (const auto& iv : m.intervals) {
            all_default &= iv.comp_model_value[1] == 8 && iv.comp_model_value[2] == 8;
            all_square &= iv.comp_model_value[1] == iv.comp_model_value[2];
        }
        // Only the model values that differ from their inferred defaults are sent.
        m.num_model_values_minus1 = all_default ? 0 : all_square ? 1 : 2;
    }
    bool any = false;
    for (int c = 0; c < num_comp; c++) any |= p.comp[c].comp_model_present_flag;
    return any ? p : fgc_no_grain();
}

}  // namespace

FgcParams fgc_no_grain() {
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = true;
    return p;
}

FgcParams fgc_params_from_levels(const std::array<FgcComponentLevels, 3>& levels, const FgcTarget& target) {
    FgcCalibration cal(target);
    return params_from_levels(levels, target, cal);
}

void choose_intervals(const LevelCurve& curve, const FgcTarget& target, FgcComponentReport& rep) {
    rep.error_by_order.clear();
    for (int k = 1; k <= target.max_intervals; k++) {
        auto iv = segment_levels(curve, k);
        std::vector<double> approx(256);
        for (const auto& s : iv)
            for (int i = s.lower; i <= s.upper; i++) approx[i] = s.level;
        int band = -1;
        const double err = worst_band_error(curve, approx, &band);
        rep.error_by_order.push_back(err);
        rep.worst_band = band;
        rep.intervals = iv;
        rep.chosen_order = k;
        rep.error = err;
        if (err <= target.accuracy) break;
    }
    rep.accurate = rep.error <= target.accuracy;
}

FgcEstimate estimate_fgc(const std::array<PlaneObservations, 3>& obs, const FgcTarget& target) {
    FgcEstimate e;
    FgcCalibration cal(target);
    const int num_comp = target.chroma == ChromaFormat::k400 ? 1 : 3;
    const double min_level = kMinGrainLevel8 * double(1 << (target.bit_depth - 8));
    std::array<FgcComponentLevels, 3> levels;
    for (int c = 0; c < num_comp; c++) {
        auto& rep = e.components[c];
        rep.note = fit_component_curve(obs[c].blocks, target.bit_depth, rep.curve, c > 0);
        if (!rep.note.empty()) continue;
        choose_intervals(rep.curve, target, rep);
        // Intervals too weak to show are left out: no interval, no grain there.
        std::vector<LevelInterval> kept;
        for (const auto& s : rep.intervals)
            if (s.level >= min_level) kept.push_back(s);
        rep.intervals = kept;
        if (obs[c].total_dct_blocks() > 0) {
            rep.pooled = match_cutoffs(lag_sums_in(obs[c], 0, 255), cal.cutoff_models(c));
        } else {
            rep.note = "no flat 64x64 block: default cut-offs 8";
        }
        // One cut-off pair for the component unless an interval's own observations, where there
        // are enough of them, call for another.
        rep.cutoffs.clear();
        for (const auto& s : rep.intervals)
            rep.cutoffs.push_back(dct_blocks_in(obs[c], s.lower, s.upper) >= kMinDctBlocksPerInterval
                                      ? interval_cutoffs(lag_sums_in(obs[c], s.lower, s.upper), rep.pooled, cal.cutoff_models(c))
                                      : std::pair<int, int>{rep.pooled.horizontal, rep.pooled.vertical});
        rep.cutoff_pairs = distinct_pairs(rep.cutoffs);
        rep.present = !rep.intervals.empty();
        levels[c].intervals = rep.intervals;
        levels[c].cutoffs = rep.cutoffs;
    }
    SignalledCutoffs signalled;
    e.params = params_from_levels(levels, target, cal, &signalled);
    for (int c = 0; c < num_comp; c++) {
        auto& rep = e.components[c];
        if (signalled.raised[c].empty()) continue;
        rep.cutoffs = signalled.cutoffs[c];
        rep.cutoff_pairs = distinct_pairs(rep.cutoffs);
        rep.note += (rep.note.empty() ? "" : "; ") + signalled.raised[c];
    }
    return e;
}

}  // namespace filmgrain::analysis

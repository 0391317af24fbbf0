#include "analysis/fgc_estimation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "analysis/grain_level.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"

namespace filmgrain::analysis {
namespace {

constexpr int kCalibrationSize = 256;
constexpr int kMinDctBlocksPerInterval = 8;

// Grain level per unit of comp_model_value[0] for one component, cut-off pair and scale
// factor, measured on a flat mid-grey picture synthesized by the target flavour.
class FgcCalibration {
public:
    explicit FgcCalibration(const FgcTarget& t) : t_(t), clean_(kCalibrationSize, kCalibrationSize, {t.chroma, t.bit_depth}) {
        fill_frame(clean_.view(), 128 << (clean_.format().bit_depth - 8));
        grainy_ = FrameBuffer(kCalibrationSize, kCalibrationSize, {t.chroma, t.bit_depth});
    }
    double gain(int c, int h, int v, int lsf, int value) {
        const auto key = std::make_tuple(c, h, v, lsf, value);
        if (auto it = cache_.find(key); it != cache_.end()) return it->second;
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
        synth.apply(clean_.view(), grainy_.view(), FgcPictureIds{0, 0});
        const double g = measure_grain_level(grainy_.view(), clean_.view(), c) / value;
        cache_[key] = g;
        return g;
    }

private:
    FgcTarget t_;
    FrameBuffer clean_, grainy_;
    std::map<std::tuple<int, int, int, int, int>, double> cache_;
};

// Signalled cut-off for a plane-resolution one: chroma of 4:2:0 (both axes) and 4:2:2
// (horizontal) is described at luma resolution and doubled by the decoder (7.3.1).
int signalled_cutoff(int plane_cutoff, bool doubled) {
    if (!doubled) return std::clamp(plane_cutoff, 2, 14);
    int best = 2;
    for (int c = 2; c <= 14; c++)
        if (std::abs(std::clamp(2 * c, 2, 14) - plane_cutoff) < std::abs(std::clamp(2 * best, 2, 14) - plane_cutoff))
            best = c;
    return best;
}

}  // namespace

FgcParams fgc_no_grain() {
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = true;
    return p;
}

FgcParams fgc_params_from_levels(const std::array<FgcComponentLevels, 3>& levels, const FgcTarget& target) {
    FgcCalibration cal(target);
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
            const bool dx = c > 0 && target.chroma != ChromaFormat::k444;
            const bool dy = c > 0 && target.chroma == ChromaFormat::k420;
            const auto [ph, pv] = levels[c].plane_cutoffs[i];
            items.push_back({c, i, signalled_cutoff(ph, dx), signalled_cutoff(pv, dy), levels[c].intervals[i].level});
        }
    if (items.empty()) return fgc_no_grain();
    // log2_scale_factor: the largest (finest) that still fits every value in its range.
    const int probe = std::max(1, 32 << (target.bit_depth - 8));
    int lsf = 2;
    for (int l = 7; l >= 2; l--) {
        bool fits = true;
        for (const auto& it : items) {
            const double g = cal.gain(it.c, it.h, it.v, 5, probe) * std::ldexp(1.0, 5 - l);
            if (it.level / g > max_scale) fits = false;
        }
        if (fits) {
            lsf = l;
            break;
        }
    }
    FgcParams p;
    p.log2_scale_factor = lsf;
    p.film_grain_characteristics_persistence_flag = true;
    for (int c = 0; c < num_comp; c++) {
        auto& m = p.comp[c];
        for (const auto& it : items) {
            if (it.c != c) continue;
            // Calibrate at about the value used, so that the synthesis' rounding is included.
            int value = std::clamp(int(std::lround(it.level / (cal.gain(c, it.h, it.v, 5, probe) * std::ldexp(1.0, 5 - lsf)))),
                                   1, max_scale);
            value = std::clamp(int(std::lround(it.level / cal.gain(c, it.h, it.v, lsf, value))), 0, max_scale);
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

FgcEstimate estimate_fgc(const std::array<PlaneObservations, 3>& obs, const FgcTarget& target) {
    FgcEstimate e;
    const int num_comp = target.chroma == ChromaFormat::k400 ? 1 : 3;
    const double min_level = kMinGrainLevel8 * double(1 << (target.bit_depth - 8));
    std::array<FgcComponentLevels, 3> levels;
    for (int c = 0; c < num_comp; c++) {
        auto& rep = e.components[c];
        rep.note = fit_component_curve(obs[c].blocks, target.bit_depth, rep.curve);
        if (!rep.note.empty()) continue;
        // The smallest number of intervals that meets the accuracy target.
        for (int k = 1; k <= target.max_intervals; k++) {
            auto iv = segment_levels(rep.curve, k);
            std::vector<double> approx(256);
            for (const auto& s : iv)
                for (int i = s.lower; i <= s.upper; i++) approx[i] = s.level;
            const double err = rms_relative_error(rep.curve, approx);
            rep.error_by_order.push_back(err);
            rep.intervals = iv;
            rep.chosen_order = k;
            rep.error = err;
            if (err <= target.accuracy) break;
        }
        // Intervals too weak to show are left out: no interval, no grain there.
        std::vector<LevelInterval> kept;
        for (const auto& s : rep.intervals)
            if (s.level >= min_level) kept.push_back(s);
        rep.intervals = kept;
        const cv::Mat pooled_power = mean_power(obs[c], 0, 255);
        if (obs[c].total_dct_blocks() > 0) {
            rep.pooled = estimate_cutoffs(pooled_power);
        } else {
            rep.note = "no flat 64x64 block: default cut-offs 8";
        }
        // One cut-off pair for the component unless an interval's own spectrum says otherwise.
        std::vector<std::pair<int, int>> own;
        bool differs = false;
        for (const auto& s : rep.intervals) {
            int n = 0;
            for (int b = 0; b < kPowerBins; b++) {
                const int lo = b * (256 / kPowerBins);
                if (lo + 256 / kPowerBins - 1 >= s.lower && lo <= s.upper) n += obs[c].dct_blocks[b];
            }
            std::pair<int, int> pair{rep.pooled.horizontal, rep.pooled.vertical};
            if (n >= kMinDctBlocksPerInterval) {
                const auto ce = estimate_cutoffs(mean_power(obs[c], s.lower, s.upper));
                pair = {ce.horizontal, ce.vertical};
                differs |= std::abs(pair.first - rep.pooled.horizontal) > 1 || std::abs(pair.second - rep.pooled.vertical) > 1;
            }
            own.push_back(pair);
        }
        rep.plane_cutoffs = differs ? own : std::vector<std::pair<int, int>>(rep.intervals.size(),
                                                                             {rep.pooled.horizontal, rep.pooled.vertical});
        std::vector<std::pair<int, int>> distinct;
        for (const auto& pr : rep.plane_cutoffs)
            if (std::find(distinct.begin(), distinct.end(), pr) == distinct.end()) distinct.push_back(pr);
        rep.cutoff_pairs = int(distinct.size());
        rep.present = !rep.intervals.empty();
        levels[c].intervals = rep.intervals;
        levels[c].plane_cutoffs = rep.plane_cutoffs;
    }
    e.params = fgc_params_from_levels(levels, target);
    return e;
}

}  // namespace filmgrain::analysis

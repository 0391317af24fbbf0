// Parameter set-up of the VFGS flavour: see vfgs_parameters.hpp.
#include "fgc/vfgs/vfgs_parameters.hpp"

#include <algorithm>
#include <string>

#include "core/field_names.hpp"
#include "fgc/ar_template_generation.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::vfgs {

namespace {

std::string value_field(int c, int i, int m) { return fgc::comp_model_value_name(c, i, m); }

[[noreturn]] void fail(ErrorCode code, const std::string& msg) { throw Error(code, "vfgs: " + msg); }

void check_range(const std::string& field, long long v, long long lo, long long hi,
                 ErrorCode code = ErrorCode::kInvalidParams, const std::string& why = "") {
    if (v < lo || v > hi) fail(code, out_of_range_message(field, v, lo, hi) + why);
}

// The ranges every flavour checks (fgc::check_fgc_syntax_ranges: each syntax element, and
// comp_model_value[c][i][j] against what the SEI semantics let it carry at the picture's
// bit depth, 0 = not known yet), with this flavour's "vfgs: " prefix.
void check_syntax_ranges(const FgcParams& p, int picture_bit_depth) {
    try {
        fgc::check_fgc_syntax_ranges(p, picture_bit_depth);
    } catch (const Error& e) {
        fail(e.code(), e.what());
    }
}

}  // namespace

std::array<int, 6> complete_model_values(const std::array<int, 6>& signalled, int num_values, int model_id,
                                         int log2_scale_factor) {
    // Model 1: the FGC auto-regressive defaults (p = 0, A = 1 << L with L as signalled,
    // before --gain), shared with the tr flavour.
    if (model_id == 1) return fgc::complete_ar_model_values(signalled, num_values, log2_scale_factor);
    std::array<int, 6> v = signalled;
    if (num_values < 2) v[1] = 8;     // horizontal high cut-off
    if (num_values < 3) v[2] = v[1];  // vertical high cut-off
    if (num_values < 4) v[3] = 0;     // horizontal low cut-off
    if (num_values < 5) v[4] = 0;     // vertical low cut-off (model_id << L for model 0)
    if (num_values < 6) v[5] = 0;     // (unused)
    return v;
}

int reduce_gain(int gain_percent, int& log2_scale_factor) {
    int g = gain_percent;
    if (g == 100) return g;
    for (; g > 100; g /= 2) --log2_scale_factor;
    for (; g != 0 && g < 50; g *= 2) ++log2_scale_factor;
    return g;
}

void validate_params(const FgcParams& p, int gain_percent) {
    if (gain_percent < 0) fail(ErrorCode::kInvalidArgument, "gain = " + std::to_string(gain_percent) +
                                                                " percent is negative (allowed 0 and above)");
    if (p.film_grain_characteristics_cancel_flag) return;  // nothing else is read
    check_range("film_grain_model_id", p.film_grain_model_id, 0, 1, ErrorCode::kUnsupported,
                " (VFGS implements frequency filtering (0) and auto-regression (1))");
    check_range("blending_mode_id", p.blending_mode_id, 0, 0, ErrorCode::kUnsupported,
                " (VFGS always blends additively)");
    const int model = p.film_grain_model_id;
    check_syntax_ranges(p, 0);

    // VFGS requires 2 <= L - model_id <= 7 for the value it ends up using,
    // i.e. after --gain: 2..7 for model 0, 3..8 for model 1.
    int L = p.log2_scale_factor;
    reduce_gain(gain_percent, L);
    if (L - model < 2 || L - model > 7) {
        std::string msg = out_of_range_message("log2_scale_factor", p.log2_scale_factor, 2 + model, 7 + model);
        if (L != p.log2_scale_factor)
            msg += " after --gain " + std::to_string(gain_percent) + " changed it to " + std::to_string(L);
        fail(ErrorCode::kInvalidParams, msg + " (film_grain_model_id " + std::to_string(model) + ")");
    }
    if (p.comp[1].comp_model_present_flag || p.comp[2].comp_model_present_flag) {
        if (model != 0)
            fail(ErrorCode::kUnsupported,
                 "comp_model_present_flag[1..2] = 1 with film_grain_model_id = 1: VFGS has no chroma grain in "
                 "auto-regression mode (allowed: luma only)");
    }

    for (int c = 0; c < 3; ++c) {
        const FgcComponentModel& cm = p.comp[c];
        if (!cm.comp_model_present_flag) continue;
        check_range(indexed("num_model_values_minus1", c), cm.num_model_values_minus1, 0, 5);
        check_range(indexed("num_intensity_intervals_minus1", c),
                    static_cast<long long>(cm.intervals.size()) - 1, 0, 255);
        for (int i = 0; i < static_cast<int>(cm.intervals.size()); ++i) {
            const FgcIntensityInterval& iv = cm.intervals[static_cast<size_t>(i)];
            check_range(indexed("intensity_interval_lower_bound", c, i), iv.intensity_interval_lower_bound, 0, 255);
            check_range(indexed("intensity_interval_upper_bound", c, i), iv.intensity_interval_upper_bound,
                        iv.intensity_interval_lower_bound, 255, ErrorCode::kInvalidParams,
                        " (the upper bound may not be below the lower bound)");
            const auto v = complete_model_values(iv.comp_model_value, cm.num_model_values_minus1 + 1, model,
                                                 p.log2_scale_factor);
            // Scale: never negative (check_syntax_ranges); VFGS stores it in 8 bits, see
            // validate_params_for_format for > 255.
            if (model == 0) {
                // VFGS checks the horizontal cut-off 2..14 and the vertical one
                // <= 14 only; negative cut-offs are rejected here as meaningless.
                check_range(value_field(c, i, 1), v[1], 2, 14, ErrorCode::kInvalidParams,
                            cm.num_model_values_minus1 < 1 ? " (inferred)" : "");
                check_range(value_field(c, i, 2), v[2], 0, 14, ErrorCode::kInvalidParams,
                            cm.num_model_values_minus1 < 2 ? " (inferred)" : "");
            }
        }
    }
}

void validate_params_for_format(const FgcParams& p, ChromaFormat format, int bit_depth) {
    if (p.film_grain_characteristics_cancel_flag) return;
    check_syntax_ranges(p, bit_depth);
    const int rng = 1 << bit_depth;
    if (format != ChromaFormat::k420 && (p.comp[1].comp_model_present_flag || p.comp[2].comp_model_present_flag))
        fail(ErrorCode::kUnsupported,
             "comp_model_present_flag[1..2] = 1 on a non-4:2:0 picture: VFGS has chroma grain in 4:2:0 only "
             "(4:2:2 and 4:4:4 take luma grain only)");
    for (int c = 0; c < 3; ++c) {
        const FgcComponentModel& cm = p.comp[c];
        if (!cm.comp_model_present_flag) continue;
        for (int i = 0; i < static_cast<int>(cm.intervals.size()); ++i) {
            const auto v = complete_model_values(cm.intervals[static_cast<size_t>(i)].comp_model_value,
                                                 cm.num_model_values_minus1 + 1, p.film_grain_model_id,
                                                 p.log2_scale_factor);
            check_range(value_field(c, i, 0), v[0], 0, rng - 1);
            // VFGS accepts scales up to 2^bitdepth - 1 but keeps only their low
            // 8 bits; rather than reproduce that silently, refuse it.
            check_range(value_field(c, i, 0), v[0], 0, 255, ErrorCode::kUnsupported,
                        " (VFGS truncates scale factors to 8 bits)");
            if (p.film_grain_model_id == 1)
                for (int m : {1, 3, 5}) check_range(value_field(c, i, m), v[static_cast<size_t>(m)], -rng / 2, rng / 2 - 1);
        }
    }
}

ResolvedParams resolve_params(const FgcParams& p, ChromaFormat format, int gain_percent) {
    ResolvedParams r;
    r.model_id = p.film_grain_model_id;
    r.signalled_log2_scale_factor = p.log2_scale_factor;
    r.log2_scale_factor = p.log2_scale_factor;
    for (int c = 0; c < 3; ++c) {
        const FgcComponentModel& cm = p.comp[c];
        ResolvedComponent& rc = r.comp[c];
        rc.present = cm.comp_model_present_flag && (c == 0 || format != ChromaFormat::k400);
        if (!rc.present) continue;
        for (const FgcIntensityInterval& iv : cm.intervals) {
            ResolvedInterval ri;
            ri.lower = iv.intensity_interval_lower_bound;
            ri.upper = iv.intensity_interval_upper_bound;
            ri.value = complete_model_values(iv.comp_model_value, cm.num_model_values_minus1 + 1, r.model_id,
                                             p.log2_scale_factor);
            // 4:2:0 chroma conversion (TR 23002-9 clause 7.5): the chroma template is
            // half the size, so the same spatial cut-off is twice the index
            // (clipped to 2..14), and the scale is halved.
            if (c > 0 && r.model_id == 0 && format == ChromaFormat::k420) {
                ri.value[1] = std::clamp(ri.value[1] * 2, 2, 14);
                ri.value[2] = std::clamp(ri.value[2] * 2, 2, 14);
                ri.value[0] >>= 1;
            }
            rc.intervals.push_back(ri);
        }
    }
    // --gain comes after the chroma conversion.
    if (gain_percent != 100) {
        const int g = reduce_gain(gain_percent, r.log2_scale_factor);
        for (auto& rc : r.comp)
            for (auto& ri : rc.intervals) ri.value[0] = static_cast<int16_t>(ri.value[0] * g / 100);
    }
    return r;
}

std::array<ComponentLuts, 3> build_luts(const ResolvedParams& r, const TemplatePools& pools) {
    std::array<ComponentLuts, 3> luts{};
    constexpr int kUnset = 255;
    std::array<uint8_t, 256> scale{};
    for (int c = 0; c < 3; ++c) {
        // VFGS clears the scale buffer for Y and for Cb only; Cr is written
        // over Cb's scale values.
        if (c < 2) scale.fill(0);
        std::array<int, 256> tmpl;
        const ResolvedComponent& rc = r.comp[c];
        if (rc.present) {
            tmpl.fill(kUnset);
            for (int k = 0; k < static_cast<int>(rc.intervals.size()); ++k) {
                const ResolvedInterval& iv = rc.intervals[static_cast<size_t>(k)];
                const int slot = find_template_slot(pools, r, c, k);
                for (int l = iv.lower; l <= iv.upper; ++l) {
                    scale[static_cast<size_t>(l)] = static_cast<uint8_t>(iv.value[0]);
                    if (slot >= 0) tmpl[static_cast<size_t>(l)] = slot;
                }
            }
            // Holes take the template of the nearest lower intensity.
            int last = 0;
            for (int& t : tmpl) {
                if (t == kUnset) t = last;
                else last = t;
            }
        } else {
            tmpl.fill(0);
        }
        luts[c].scale = scale;
        for (int l = 0; l < 256; ++l) luts[c].tmpl[static_cast<size_t>(l)] = static_cast<uint8_t>(tmpl[static_cast<size_t>(l)]);
    }
    return luts;
}

void add_interpolation_ramps(const ResolvedParams& r, std::array<ComponentLuts, 3>& luts) {
    constexpr int kMaxHalfWidth = 8;  // 16 blend steps of 1/16
    for (int c = 0; c < 3; ++c) {
        ComponentLuts& lut = luts[c];
        lut.tmpl_next = lut.tmpl;
        lut.frac.fill(0);
        if (!r.comp[c].present) continue;
        // Boundaries between two adjacent intervals whose templates differ.
        for (const ResolvedInterval& a : r.comp[c].intervals) {
            for (const ResolvedInterval& b : r.comp[c].intervals) {
                if (b.lower != a.upper + 1) continue;
                const int e = b.lower;
                const int t0 = luts[c].tmpl[static_cast<size_t>(e - 1)];
                const int t1 = luts[c].tmpl[static_cast<size_t>(e)];
                if (t0 == t1) continue;
                // Half-width: at most 8, and at most half of either interval,
                // so that ramps of neighbouring boundaries never overlap.
                const int w = std::min({kMaxHalfWidth, (a.upper - a.lower + 1) / 2, (b.upper - b.lower + 1) / 2});
                if (w < 1) continue;
                // Intensities e-w .. e+w-1 blend t0 -> t1 with weight
                // f/16 = (i - e + w + 1/2) / (2w) of t1, rounded, which runs
                // from ~0 to ~16 and is 8 at the boundary itself.
                for (int i = e - w; i < e + w; ++i) {
                    const int f = (16 * (i - e + w) + w) / (2 * w);
                    lut.tmpl[static_cast<size_t>(i)] = static_cast<uint8_t>(t0);
                    lut.tmpl_next[static_cast<size_t>(i)] = static_cast<uint8_t>(t1);
                    lut.frac[static_cast<size_t>(i)] = static_cast<uint8_t>(f);
                }
            }
        }
    }
}

int scale_shift(const ResolvedParams& r, int bit_depth) {
    return r.log2_scale_factor - r.model_id + 6 - (bit_depth - 8);
}

}  // namespace filmgrain::vfgs

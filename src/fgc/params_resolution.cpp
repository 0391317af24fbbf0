#include "fgc/params_resolution.hpp"

#include <algorithm>
#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::fgc {
namespace {

[[noreturn]] void invalid(const std::string& msg) { throw Error(ErrorCode::kInvalidParams, msg); }

std::string cmv(int c, int i, int j) {
    return "comp_model_value[" + std::to_string(c) + "][" + std::to_string(i) + "][" + std::to_string(j) + "]";
}

// HM (both generations) counts at most 10 distinct cut-off pairs over all components,
// after the chroma conversion (RDD 5 limits the template database to 10 entries).
constexpr int kMaxCutoffPairs = 10;

}  // namespace

void check_fgc_syntax_ranges(const FgcParams& p) {
    if (p.film_grain_characteristics_cancel_flag) return;
    if (p.film_grain_model_id < 0 || p.film_grain_model_id > 3)
        invalid(out_of_range_message("film_grain_model_id", p.film_grain_model_id, 0, 3));
    if (p.blending_mode_id < 0 || p.blending_mode_id > 3)
        invalid(out_of_range_message("blending_mode_id", p.blending_mode_id, 0, 3));
    if (p.log2_scale_factor < 0 || p.log2_scale_factor > 15)
        invalid(out_of_range_message("log2_scale_factor", p.log2_scale_factor, 0, 15));
    if (p.separate_colour_description_present_flag) {
        if (p.film_grain_bit_depth_luma_minus8 < 0 || p.film_grain_bit_depth_luma_minus8 > 7)
            invalid(out_of_range_message("film_grain_bit_depth_luma_minus8", p.film_grain_bit_depth_luma_minus8, 0, 7));
        if (p.film_grain_bit_depth_chroma_minus8 < 0 || p.film_grain_bit_depth_chroma_minus8 > 7)
            invalid(out_of_range_message("film_grain_bit_depth_chroma_minus8", p.film_grain_bit_depth_chroma_minus8, 0, 7));
        for (auto [name, v] : {std::pair<const char*, int>{"film_grain_colour_primaries", p.film_grain_colour_primaries},
                               {"film_grain_transfer_characteristics", p.film_grain_transfer_characteristics},
                               {"film_grain_matrix_coeffs", p.film_grain_matrix_coeffs}})
            if (v < 0 || v > 255) invalid(out_of_range_message(name, v, 0, 255));
    }
    for (int c = 0; c < 3; c++) {
        const auto& m = p.comp[c];
        if (!m.comp_model_present_flag) continue;
        if (m.intervals.empty() || m.intervals.size() > 256)
            invalid(out_of_range_message("num_intensity_intervals_minus1[" + std::to_string(c) + "]",
                                         (long long)m.intervals.size() - 1, 0, 255));
        if (m.num_model_values_minus1 < 0 || m.num_model_values_minus1 > 5)
            invalid(out_of_range_message("num_model_values_minus1[" + std::to_string(c) + "]",
                                         m.num_model_values_minus1, 0, 5));
        for (std::size_t i = 0; i < m.intervals.size(); i++) {
            const auto& iv = m.intervals[i];
            std::string idx = "[" + std::to_string(c) + "][" + std::to_string(i) + "]";
            if (iv.intensity_interval_lower_bound < 0 || iv.intensity_interval_lower_bound > 255)
                invalid(out_of_range_message("intensity_interval_lower_bound" + idx, iv.intensity_interval_lower_bound, 0, 255));
            if (iv.intensity_interval_upper_bound < 0 || iv.intensity_interval_upper_bound > 255)
                invalid(out_of_range_message("intensity_interval_upper_bound" + idx, iv.intensity_interval_upper_bound, 0, 255));
        }
    }
    if (p.film_grain_characteristics_repetition_period < 0 || p.film_grain_characteristics_repetition_period > 16384)
        invalid(out_of_range_message("film_grain_characteristics_repetition_period",
                                     p.film_grain_characteristics_repetition_period, 0, 16384));
}

ResolvedFgc resolve_fgc_params(const FgcParams& p, FgcFlavour flavour, const PictureFormat& fmt) {
    ResolvedFgc r;
    if (fmt.bit_depth < 8 || fmt.bit_depth > 16)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("bit_depth", fmt.bit_depth, 8, 16));
    if (flavour == FgcFlavour::kVtm) {
        // HM/VTM refuse these picture sizes (FG_MIN/MAX_WIDTH/HEIGHT, multiple of 4).
        if (fmt.width < 128 || fmt.width > 7680 || fmt.width % 4)
            throw Error(ErrorCode::kUnsupported, out_of_range_message("picture width", fmt.width, 128, 7680) +
                                                     " or not a multiple of 4 (the vtm flavour follows HM's limits)");
        if (fmt.height < 128 || fmt.height > 4320 || fmt.height % 4)
            throw Error(ErrorCode::kUnsupported, out_of_range_message("picture height", fmt.height, 128, 4320) +
                                                     " or not a multiple of 4 (the vtm flavour follows HM's limits)");
    }
    if (p.film_grain_characteristics_cancel_flag) {
        r.cancelled = true;
        return r;
    }
    check_fgc_syntax_ranges(p);
    if (p.film_grain_model_id != 0)
        throw Error(ErrorCode::kUnsupported,
                    "film_grain_model_id = " + std::to_string(p.film_grain_model_id) +
                        " is not supported by this flavour (allowed 0..0: frequency filtering; use --flavour vfgs for 1)");
    if (p.separate_colour_description_present_flag)
        throw Error(ErrorCode::kUnsupported,
                    "separate_colour_description_present_flag = 1 is not supported by this flavour (allowed 0..0)");
    if (p.blending_mode_id != 0)
        throw Error(ErrorCode::kUnsupported, "blending_mode_id = " + std::to_string(p.blending_mode_id) +
                                                 " is not supported by this flavour (allowed 0..0: additive)");

    const int num_comp = fmt.chroma == ChromaFormat::k400 ? 1 : 3;
    bool any_present = false;
    for (int c = 0; c < num_comp; c++) any_present |= p.comp[c].comp_model_present_flag;
    // HM-2020 checks the scale factor always; HM master only when some component has grain.
    if (flavour == FgcFlavour::kRdd5 || any_present)
        if (p.log2_scale_factor < 2 || p.log2_scale_factor > 7)
            invalid(out_of_range_message("log2_scale_factor", p.log2_scale_factor, 2, 7));
    r.log2_scale_factor = p.log2_scale_factor;

    for (int c = 0; c < num_comp; c++) {
        const auto& m = p.comp[c];
        if (m.comp_model_present_flag && m.num_model_values_minus1 + 1 > 3)
            throw Error(ErrorCode::kUnsupported,
                        out_of_range_message("num_model_values_minus1[" + std::to_string(c) + "]",
                                             m.num_model_values_minus1, 0, 2) +
                            " (the frequency-filtering flavours use at most 3 model values)");
    }

    const long long max_scale = 255LL << (fmt.bit_depth - 8);
    for (int c = 0; c < num_comp; c++) {
        const auto& m = p.comp[c];
        auto& rc = r.comp[c];
        rc.interval_of_intensity.fill(-1);
        if (!m.comp_model_present_flag) continue;
        rc.present = true;
        const int nmv = m.num_model_values_minus1 + 1;
        for (std::size_t i = 0; i < m.intervals.size(); i++) {
            const auto& iv = m.intervals[i];
            const std::string idx = "[" + std::to_string(c) + "][" + std::to_string(i) + "]";
            if (iv.intensity_interval_lower_bound > iv.intensity_interval_upper_bound)
                invalid("intensity_interval_lower_bound" + idx + " = " + std::to_string(iv.intensity_interval_lower_bound) +
                        " exceeds intensity_interval_upper_bound" + idx + " = " +
                        std::to_string(iv.intensity_interval_upper_bound) + " (allowed lower <= upper)");
            for (int v = iv.intensity_interval_lower_bound; v <= iv.intensity_interval_upper_bound; v++) {
                if (rc.interval_of_intensity[v] >= 0)
                    invalid("intensity interval " + std::to_string(i) + " of component " + std::to_string(c) + " [" +
                            std::to_string(iv.intensity_interval_lower_bound) + ", " +
                            std::to_string(iv.intensity_interval_upper_bound) + "] overlaps interval " +
                            std::to_string(rc.interval_of_intensity[v]) + " at intensity " + std::to_string(v) +
                            " (allowed: intervals that do not overlap)");
                rc.interval_of_intensity[v] = int16_t(i);
            }
            ResolvedInterval ri;
            ri.scale = iv.comp_model_value[0];
            // TR 23002-9 7.3.1 defaults: horizontal cut-off 8, vertical = horizontal.
            ri.cutoff_h = nmv >= 2 ? iv.comp_model_value[1] : 8;
            ri.cutoff_v = nmv >= 3 ? iv.comp_model_value[2] : ri.cutoff_h;
            if (ri.scale > max_scale)
                invalid(cmv(c, int(i), 0) + " = " + std::to_string(ri.scale) + " is out of range (allowed ..." +
                        std::to_string(max_scale) + " = 255 << (bit_depth - 8))");
            if (ri.cutoff_h < 2 || ri.cutoff_h > 14)
                invalid(out_of_range_message(nmv >= 2 ? cmv(c, int(i), 1) : "default horizontal cut-off", ri.cutoff_h, 2, 14));
            if (ri.cutoff_v < 2 || ri.cutoff_v > 14)
                invalid(out_of_range_message(nmv >= 3 ? cmv(c, int(i), 2) : "inferred vertical cut-off (= comp_model_value[" +
                                                                                 std::to_string(c) + "][" + std::to_string(i) + "][1])",
                                             ri.cutoff_v, 2, 14));
            // The references' chroma conversion: the model describes grain at luma resolution.
            if (c > 0 && fmt.chroma == ChromaFormat::k420) {
                ri.scale >>= 1;
                ri.cutoff_h = std::clamp(ri.cutoff_h << 1, 2, 14);
                ri.cutoff_v = std::clamp(ri.cutoff_v << 1, 2, 14);
            } else if (c > 0 && fmt.chroma == ChromaFormat::k422) {
                ri.scale = (ri.scale * 181) >> 8;  // 1/sqrt(2) in Q8
                ri.cutoff_h = std::clamp(ri.cutoff_h << 1, 2, 14);
            }
            auto pair = std::make_pair(ri.cutoff_h, ri.cutoff_v);
            if (std::find(r.cutoff_pairs.begin(), r.cutoff_pairs.end(), pair) == r.cutoff_pairs.end()) {
                r.cutoff_pairs.push_back(pair);
                if (int(r.cutoff_pairs.size()) > kMaxCutoffPairs)
                    invalid("the parameter set uses " + std::to_string(r.cutoff_pairs.size()) +
                            " distinct (horizontal, vertical) cut-off pairs after chroma conversion, first excess at " +
                            cmv(c, int(i), 1) + " (allowed at most 10)");
            }
            rc.intervals.push_back(ri);
        }
    }
    return r;
}

}  // namespace filmgrain::fgc

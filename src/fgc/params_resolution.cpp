#include "fgc/params_resolution.hpp"

#include <algorithm>
#include <string>

#include "core/field_names.hpp"
#include "fgc/ar_template_generation.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::fgc {
namespace {

[[noreturn]] void invalid(const std::string& msg) { throw Error(ErrorCode::kInvalidParams, msg); }

// HM (both generations) counts at most 10 distinct cut-off pairs over all components,
// after the chroma conversion (RDD 5 limits the template database to 10 entries).
constexpr int kMaxCutoffPairs = 10;

}  // namespace

std::string comp_model_value_name(int c, int i, int j) {
    return "comp_model_value[" + std::to_string(c) + "][" + std::to_string(i) + "][" + std::to_string(j) + "]";
}

int film_grain_bit_depth(const FgcParams& p, int c, int picture_bit_depth) {
    if (p.separate_colour_description_present_flag)
        return (c == 0 ? p.film_grain_bit_depth_luma_minus8 : p.film_grain_bit_depth_chroma_minus8) + 8;
    return picture_bit_depth > 0 ? picture_bit_depth : 16;
}

ValueRange comp_model_value_range(int model_id, int j, int bit_depth) {
    if (model_id == 0 || (model_id == 1 && j == 0)) return {0, (1LL << bit_depth) - 1};
    if (model_id == 1) return {-(1LL << (bit_depth - 1)), (1LL << (bit_depth - 1)) - 1};
    return {-((1LL << 31) - 1), (1LL << 31) - 1};  // reserved model: what se(v) of 32 bits carries
}

void check_fgc_syntax_ranges(const FgcParams& p, int picture_bit_depth) {
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
            const std::string idx = indexed("", c, i);
            if (iv.intensity_interval_lower_bound < 0 || iv.intensity_interval_lower_bound > 255)
                invalid(out_of_range_message("intensity_interval_lower_bound" + idx, iv.intensity_interval_lower_bound, 0, 255));
            if (iv.intensity_interval_upper_bound < 0 || iv.intensity_interval_upper_bound > 255)
                invalid(out_of_range_message("intensity_interval_upper_bound" + idx, iv.intensity_interval_upper_bound, 0, 255));
            if (p.film_grain_model_id > 1) continue;  // reserved: no range defined (the flavours refuse it)
            const int bd = film_grain_bit_depth(p, c, picture_bit_depth);
            for (int j = 0; j <= m.num_model_values_minus1; j++) {
                const int v = iv.comp_model_value[std::size_t(j)];
                const ValueRange r = comp_model_value_range(p.film_grain_model_id, j, bd);
                if (v >= r.lo && v <= r.hi) continue;
                const std::string depth =
                    p.separate_colour_description_present_flag
                        ? std::string(c == 0 ? "film_grain_bit_depth_luma_minus8" : "film_grain_bit_depth_chroma_minus8") +
                              " + 8"
                    : picture_bit_depth > 0 ? "the picture's bit depth"
                                            : "the deepest picture, 16 bits; the picture's bit depth narrows it";
                const bool scale = p.film_grain_model_id == 0 || j == 0;
                invalid(out_of_range_message(comp_model_value_name(c, int(i), j), v, r.lo, r.hi) + " (film_grain_model_id " +
                        std::to_string(p.film_grain_model_id) + ": " +
                        (scale ? "0..2^filmGrainBitDepth - 1" : "-2^(filmGrainBitDepth - 1)..2^(filmGrainBitDepth - 1) - 1") +
                        ", filmGrainBitDepth[" + std::to_string(c) + "] = " + std::to_string(bd) + " from " + depth + ")");
            }
        }
    }
    if (p.film_grain_characteristics_repetition_period < 0 || p.film_grain_characteristics_repetition_period > 16384)
        invalid(out_of_range_message("film_grain_characteristics_repetition_period",
                                     p.film_grain_characteristics_repetition_period, 0, 16384));
}

}  // namespace filmgrain::fgc

namespace filmgrain {

const char* fgc_flavour_name(FgcFlavour flavour) {
    switch (flavour) {
        case FgcFlavour::kRdd5: return "rdd5";
        case FgcFlavour::kVtm: return "vtm";
        case FgcFlavour::kVfgs: return "vfgs";
        case FgcFlavour::kTr: return "tr";
        case FgcFlavour::kFfmpeg: return "ffmpeg";
    }
    return "?";
}

}  // namespace filmgrain

namespace filmgrain::fgc {

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
    check_fgc_syntax_ranges(p, fmt.bit_depth);
    const bool tr = flavour == FgcFlavour::kTr;
    // FFmpeg's h274.c (7.1) checks only film_grain_model_id; it synthesizes every other
    // signalling with the additive model at the picture's bit depth, as players then show it.
    const bool ffmpeg = flavour == FgcFlavour::kFfmpeg;
    if (ffmpeg) {
        if (p.film_grain_model_id != 0)
            throw Error(ErrorCode::kUnsupported,
                        "film_grain_model_id = " + std::to_string(p.film_grain_model_id) +
                            " is not supported by the ffmpeg flavour (allowed 0..0: FFmpeg outputs the picture "
                            "without grain)");
    } else if (!tr) {
        const std::string name = fgc_flavour_name(flavour);
        if (p.film_grain_model_id != 0)
            throw Error(ErrorCode::kUnsupported,
                        "film_grain_model_id = " + std::to_string(p.film_grain_model_id) + " is not supported by the " +
                            name +
                            " flavour (allowed 0..0: frequency filtering; --flavour tr synthesizes the "
                            "auto-regressive model 1, --flavour vfgs its luma)");
        if (p.separate_colour_description_present_flag)
            throw Error(ErrorCode::kUnsupported, "separate_colour_description_present_flag = 1 is not supported by the " +
                                                     name + " flavour (allowed 0..0; --flavour tr supports 1)");
        if (p.blending_mode_id != 0)
            throw Error(ErrorCode::kUnsupported,
                        "blending_mode_id = " + std::to_string(p.blending_mode_id) + " is not supported by the " + name +
                            " flavour (allowed 0..0: additive; --flavour tr supports 1, multiplicative)");
    } else {
        if (p.film_grain_model_id > 1)
            throw Error(ErrorCode::kUnsupported, out_of_range_message("film_grain_model_id", p.film_grain_model_id, 0, 1) +
                                                     " (2 and 3 are reserved)");
        if (p.blending_mode_id > 1)
            throw Error(ErrorCode::kUnsupported,
                        out_of_range_message("blending_mode_id", p.blending_mode_id, 0, 1) + " (2 and 3 are reserved)");
    }
    const int model = p.film_grain_model_id;
    r.model_id = model;
    r.blending_mode_id = ffmpeg ? 0 : p.blending_mode_id;
    for (int c = 0; c < 3; c++)
        r.grain_bit_depth[c] = ffmpeg || !p.separate_colour_description_present_flag ? fmt.bit_depth
                               : c == 0 ? p.film_grain_bit_depth_luma_minus8 + 8
                                        : p.film_grain_bit_depth_chroma_minus8 + 8;

    const int num_comp = fmt.chroma == ChromaFormat::k400 ? 1 : 3;
    bool any_present = false;
    for (int c = 0; c < num_comp; c++) any_present |= p.comp[c].comp_model_present_flag;
    // HM-2020 checks the scale factor always; HM master only when some component has grain.
    // tr: the synthesis shift is log2_scale_factor + 6 - model_id (auto-regressive templates
    // carry one bit more, as in VFGS), and both models keep it in 8..13.
    // ffmpeg: FFmpeg takes any log2_scale_factor, but below 2 its int8 grain wraps (an
    // overflow, not a behaviour to reproduce), so the flavour keeps RDD 5's range.
    if (flavour == FgcFlavour::kRdd5 || ffmpeg || tr || any_present)
        if (p.log2_scale_factor < 2 + model || p.log2_scale_factor > 7 + model)
            invalid(out_of_range_message("log2_scale_factor", p.log2_scale_factor, 2 + model, 7 + model) +
                    (model ? " (film_grain_model_id 1)" : ""));
    r.log2_scale_factor = p.log2_scale_factor;

    for (int c = 0; c < num_comp; c++) {
        const auto& m = p.comp[c];
        if (model == 0 && !ffmpeg && m.comp_model_present_flag && m.num_model_values_minus1 + 1 > 3)
            throw Error(ErrorCode::kUnsupported,
                        out_of_range_message("num_model_values_minus1[" + std::to_string(c) + "]",
                                             m.num_model_values_minus1, 0, 2) +
                            " (the frequency-filtering flavours use at most 3 model values)");
    }

    for (int c = 0; c < num_comp; c++) {
        const auto& m = p.comp[c];
        auto& rc = r.comp[c];
        rc.interval_of_intensity.fill(-1);
        if (!m.comp_model_present_flag) continue;
        rc.present = true;
        const int nmv = m.num_model_values_minus1 + 1;
        // comp_model_value[c][i][0] up to 2^bitDepth - 1 as HM checks it, 255 << (bitDepth - 8),
        // with the film grain bit depth when the SEI gives one (tr).
        const long long max_scale = 255LL << (r.grain_bit_depth[c] - 8);
        const char* max_scale_why = p.separate_colour_description_present_flag
                                        ? " = 255 << (film grain bit depth - 8))"
                                        : " = 255 << (bit_depth - 8))";
        for (std::size_t i = 0; i < m.intervals.size(); i++) {
            const auto& iv = m.intervals[i];
            const std::string idx = indexed("", c, i);
            // ffmpeg: FFmpeg takes the first signalled interval that holds the block average,
            // so an empty interval (lower > upper) holds none and an overlap goes to the earlier.
            if (iv.intensity_interval_lower_bound > iv.intensity_interval_upper_bound && !ffmpeg)
                invalid("intensity_interval_lower_bound" + idx + " = " + std::to_string(iv.intensity_interval_lower_bound) +
                        " exceeds intensity_interval_upper_bound" + idx + " = " +
                        std::to_string(iv.intensity_interval_upper_bound) + " (allowed lower <= upper)");
            for (int v = iv.intensity_interval_lower_bound; v <= iv.intensity_interval_upper_bound; v++) {
                if (rc.interval_of_intensity[v] >= 0) {
                    if (ffmpeg) continue;
                    invalid("intensity interval " + std::to_string(i) + " of component " + std::to_string(c) + " [" +
                            std::to_string(iv.intensity_interval_lower_bound) + ", " +
                            std::to_string(iv.intensity_interval_upper_bound) + "] overlaps interval " +
                            std::to_string(rc.interval_of_intensity[v]) + " at intensity " + std::to_string(v) +
                            " (allowed: intervals that do not overlap)");
                }
                rc.interval_of_intensity[v] = int16_t(i);
            }
            ResolvedInterval ri;
            ri.scale = iv.comp_model_value[0];
            // Negative values never get here (check_fgc_syntax_ranges): the scale factor and
            // sigma are 0 or more, so the products of synthesis stay within int32.
            if (ri.scale > max_scale)
                invalid(out_of_range_message(comp_model_value_name(c, int(i), 0), ri.scale, 0, max_scale) + " (" +
                        std::to_string(max_scale) + max_scale_why);
            if (model == 1) {
                // Auto-regressive model (tr). No chroma conversion is defined for it: the
                // coefficients are correlations between neighbouring samples of the component
                // itself, so the values are used as signalled.
                ri.ar = complete_ar_model_values(iv.comp_model_value, nmv, p.log2_scale_factor);
                const int one = 1 << p.log2_scale_factor;
                for (int j : {1, 2, 3, 5})
                    if (ri.ar[j] < -one || ri.ar[j] > one)
                        invalid(out_of_range_message(comp_model_value_name(c, int(i), j), ri.ar[j], -one, one) +
                                " (a correlation from -1 to 1 in units of 2^-log2_scale_factor)");
                if (ri.ar[4] < 0 || ri.ar[4] > 4 * one)
                    invalid(out_of_range_message(comp_model_value_name(c, int(i), 4), ri.ar[4], 0, 4 * one) +
                            " (an aspect ratio from 0 to 4 in units of 2^-log2_scale_factor)");
                rc.intervals.push_back(ri);
                continue;
            }
            // TR 23002-9 7.3.1 defaults: horizontal cut-off 8, vertical = horizontal. FFmpeg
            // (ffmpeg) infers none: what is not signalled stays 0, and it clips where RDD 5
            // refuses values outside 2..14 (the clip below).
            int h = nmv >= 2 ? iv.comp_model_value[1] : ffmpeg ? 0 : 8;
            int v = nmv >= 3 ? iv.comp_model_value[2] : ffmpeg ? 0 : h;
            if (!ffmpeg && (h < 2 || h > 14))
                invalid(out_of_range_message(nmv >= 2 ? comp_model_value_name(c, int(i), 1) : "default horizontal cut-off", h, 2, 14));
            if (!ffmpeg && (v < 2 || v > 14))
                invalid(out_of_range_message(nmv >= 3 ? comp_model_value_name(c, int(i), 2) : "inferred vertical cut-off (= comp_model_value[" +
                                                                                 std::to_string(c) + "][" + std::to_string(i) + "][1])",
                                             v, 2, 14));
            // The references' chroma conversion: the model describes grain at luma resolution.
            if (c > 0 && fmt.chroma == ChromaFormat::k420) {
                ri.scale >>= 1;
                h <<= 1;
                v <<= 1;
            } else if (c > 0 && fmt.chroma == ChromaFormat::k422) {
                ri.scale = (ri.scale * 181) >> 8;  // 1/sqrt(2) in Q8
                h <<= 1;
            }
            ri.cutoff_h = std::clamp(h, 2, 14);
            ri.cutoff_v = std::clamp(v, 2, 14);
            auto pair = std::make_pair(ri.cutoff_h, ri.cutoff_v);
            if (std::find(r.cutoff_pairs.begin(), r.cutoff_pairs.end(), pair) == r.cutoff_pairs.end()) {
                r.cutoff_pairs.push_back(pair);
                // ffmpeg: FFmpeg builds any of the 13 x 13 templates a set asks for
                if (!ffmpeg && int(r.cutoff_pairs.size()) > kMaxCutoffPairs)
                    invalid("the parameter set uses " + std::to_string(r.cutoff_pairs.size()) +
                            " distinct (horizontal, vertical) cut-off pairs after chroma conversion, first excess at " +
                            comp_model_value_name(c, int(i), 1) + " (allowed at most 10)");
            }
            rc.intervals.push_back(ri);
        }
    }
    return r;
}

}  // namespace filmgrain::fgc

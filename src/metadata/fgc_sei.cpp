#include "metadata/fgc_sei.hpp"

#include <string>

#include "filmgrain/error.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain {

FgcCodec parse_fgc_codec(const std::string& n) {
    if (n == "avc" || n == "h264") return FgcCodec::kAvc;
    if (n == "hevc" || n == "h265") return FgcCodec::kHevc;
    if (n == "vvc" || n == "h266") return FgcCodec::kVvc;
    throw Error(ErrorCode::kInvalidArgument, "SEI codec '" + n + "' is not known (allowed avc, hevc, vvc)");
}

FgcParams parse_fgc_sei_payload(const uint8_t* data, std::size_t size, FgcCodec codec) {
    BitReader br(data, size);
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = br.flag("film_grain_characteristics_cancel_flag");
    if (p.film_grain_characteristics_cancel_flag) return p;
    p.film_grain_model_id = int(br.u(2, "film_grain_model_id"));
    p.separate_colour_description_present_flag = br.flag("separate_colour_description_present_flag");
    if (p.separate_colour_description_present_flag) {
        p.film_grain_bit_depth_luma_minus8 = int(br.u(3, "film_grain_bit_depth_luma_minus8"));
        p.film_grain_bit_depth_chroma_minus8 = int(br.u(3, "film_grain_bit_depth_chroma_minus8"));
        p.film_grain_full_range_flag = br.flag("film_grain_full_range_flag");
        p.film_grain_colour_primaries = int(br.u(8, "film_grain_colour_primaries"));
        p.film_grain_transfer_characteristics = int(br.u(8, "film_grain_transfer_characteristics"));
        p.film_grain_matrix_coeffs = int(br.u(8, "film_grain_matrix_coeffs"));
    }
    p.blending_mode_id = int(br.u(2, "blending_mode_id"));
    p.log2_scale_factor = int(br.u(4, "log2_scale_factor"));
    for (int c = 0; c < 3; c++) p.comp[c].comp_model_present_flag = br.flag("comp_model_present_flag");
    for (int c = 0; c < 3; c++) {
        auto& m = p.comp[c];
        if (!m.comp_model_present_flag) continue;
        const int n = int(br.u(8, "num_intensity_intervals_minus1")) + 1;
        m.num_model_values_minus1 = int(br.u(3, "num_model_values_minus1"));
        if (m.num_model_values_minus1 > 5)
            throw Error(ErrorCode::kMalformedPayload,
                        out_of_range_message("num_model_values_minus1[" + std::to_string(c) + "]",
                                             m.num_model_values_minus1, 0, 5));
        m.intervals.resize(n);
        for (auto& iv : m.intervals) {
            iv.intensity_interval_lower_bound = int(br.u(8, "intensity_interval_lower_bound"));
            iv.intensity_interval_upper_bound = int(br.u(8, "intensity_interval_upper_bound"));
            for (int j = 0; j <= m.num_model_values_minus1; j++) iv.comp_model_value[j] = br.se("comp_model_value");
        }
    }
    if (codec == FgcCodec::kAvc) {
        uint32_t rp = br.ue("film_grain_characteristics_repetition_period");
        if (rp > 16384)
            throw Error(ErrorCode::kMalformedPayload,
                        out_of_range_message("film_grain_characteristics_repetition_period", rp, 0, 16384));
        p.film_grain_characteristics_repetition_period = int(rp);
        p.film_grain_characteristics_persistence_flag = rp != 0;
    } else {
        p.film_grain_characteristics_persistence_flag = br.flag("film_grain_characteristics_persistence_flag");
        p.film_grain_characteristics_repetition_period = p.film_grain_characteristics_persistence_flag ? 1 : 0;
    }
    if (!br.only_trailing_bits_left())
        throw Error(ErrorCode::kMalformedPayload,
                    "film_grain_characteristics payload has " + std::to_string(br.bits_left()) +
                        " unexpected bits after film_grain_characteristics_" +
                        (codec == FgcCodec::kAvc ? "repetition_period" : "persistence_flag") +
                        " (wrong --sei-codec?)");
    return p;
}

std::vector<uint8_t> write_fgc_sei_payload(const FgcParams& p, FgcCodec codec) {
    BitWriter bw;
    bw.flag(p.film_grain_characteristics_cancel_flag);
    if (!p.film_grain_characteristics_cancel_flag) {
        auto check = [](const std::string& f, long long v, long long lo, long long hi) {
            if (v < lo || v > hi) throw Error(ErrorCode::kInvalidParams, out_of_range_message(f, v, lo, hi));
        };
        check("film_grain_model_id", p.film_grain_model_id, 0, 3);
        bw.u(2, p.film_grain_model_id);
        bw.flag(p.separate_colour_description_present_flag);
        if (p.separate_colour_description_present_flag) {
            check("film_grain_bit_depth_luma_minus8", p.film_grain_bit_depth_luma_minus8, 0, 7);
            check("film_grain_bit_depth_chroma_minus8", p.film_grain_bit_depth_chroma_minus8, 0, 7);
            bw.u(3, p.film_grain_bit_depth_luma_minus8);
            bw.u(3, p.film_grain_bit_depth_chroma_minus8);
            bw.flag(p.film_grain_full_range_flag);
            bw.u(8, uint32_t(p.film_grain_colour_primaries) & 0xFF);
            bw.u(8, uint32_t(p.film_grain_transfer_characteristics) & 0xFF);
            bw.u(8, uint32_t(p.film_grain_matrix_coeffs) & 0xFF);
        }
        check("blending_mode_id", p.blending_mode_id, 0, 3);
        check("log2_scale_factor", p.log2_scale_factor, 0, 15);
        bw.u(2, p.blending_mode_id);
        bw.u(4, p.log2_scale_factor);
        for (int c = 0; c < 3; c++) bw.flag(p.comp[c].comp_model_present_flag);
        for (int c = 0; c < 3; c++) {
            const auto& m = p.comp[c];
            if (!m.comp_model_present_flag) continue;
            check("num_intensity_intervals_minus1[" + std::to_string(c) + "]", (long long)m.intervals.size() - 1, 0, 255);
            check("num_model_values_minus1[" + std::to_string(c) + "]", m.num_model_values_minus1, 0, 5);
            bw.u(8, uint32_t(m.intervals.size() - 1));
            bw.u(3, m.num_model_values_minus1);
            for (const auto& iv : m.intervals) {
                check("intensity_interval_lower_bound", iv.intensity_interval_lower_bound, 0, 255);
                check("intensity_interval_upper_bound", iv.intensity_interval_upper_bound, 0, 255);
                bw.u(8, iv.intensity_interval_lower_bound);
                bw.u(8, iv.intensity_interval_upper_bound);
                for (int j = 0; j <= m.num_model_values_minus1; j++) bw.se(iv.comp_model_value[j]);
            }
        }
        if (codec == FgcCodec::kAvc)
            bw.ue(uint32_t(p.film_grain_characteristics_repetition_period));
        else
            bw.flag(p.film_grain_characteristics_persistence_flag);
    }
    bw.byte_align_with_stop_bit();
    return bw.bytes();
}

}  // namespace filmgrain

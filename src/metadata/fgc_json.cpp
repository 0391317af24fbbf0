#include "metadata/fgc_json.hpp"

#include <string>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"
#include "metadata/json_access.hpp"

namespace filmgrain {

using nlohmann::json;

FgcParams fgc_params_from_json(const json& j) {
    JsonObject o(j, "fgc");
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = o.get_int("film_grain_characteristics_cancel_flag", 0, 0, 1);
    p.film_grain_model_id = o.get_int("film_grain_model_id", 0, 0, 3);
    p.separate_colour_description_present_flag = o.get_int("separate_colour_description_present_flag", 0, 0, 1);
    p.film_grain_bit_depth_luma_minus8 = o.get_int("film_grain_bit_depth_luma_minus8", 0, 0, 7);
    p.film_grain_bit_depth_chroma_minus8 = o.get_int("film_grain_bit_depth_chroma_minus8", 0, 0, 7);
    p.film_grain_full_range_flag = o.get_int("film_grain_full_range_flag", 0, 0, 1);
    p.film_grain_colour_primaries = o.get_int("film_grain_colour_primaries", 2, 0, 255);
    p.film_grain_transfer_characteristics = o.get_int("film_grain_transfer_characteristics", 2, 0, 255);
    p.film_grain_matrix_coeffs = o.get_int("film_grain_matrix_coeffs", 2, 0, 255);
    p.blending_mode_id = o.get_int("blending_mode_id", 0, 0, 3);
    p.log2_scale_factor = o.get_int("log2_scale_factor", 0, 0, 15);
    p.film_grain_characteristics_persistence_flag = o.get_int("film_grain_characteristics_persistence_flag", 1, 0, 1);
    p.film_grain_characteristics_repetition_period =
        o.get_int("film_grain_characteristics_repetition_period", p.film_grain_characteristics_persistence_flag ? 1 : 0,
                  0, 16384);
    if (o.has("film_grain_characteristics_repetition_period") && !o.has("film_grain_characteristics_persistence_flag"))
        p.film_grain_characteristics_persistence_flag = p.film_grain_characteristics_repetition_period != 0;
    if (p.film_grain_characteristics_cancel_flag) return p;

    auto present = o.get_int_array("comp_model_present_flag", 3, 0, 1);
    auto nint = o.get_int_array("num_intensity_intervals_minus1", 3, 0, 255, /*required=*/false);
    auto nmv = o.get_int_array("num_model_values_minus1", 3, 0, 5, /*required=*/false);
    const json* lower = o.array("intensity_interval_lower_bound");
    const json* upper = o.array("intensity_interval_upper_bound");
    const json* values = o.array("comp_model_value");
    for (int c = 0; c < 3; c++) {
        auto& m = p.comp[c];
        m.comp_model_present_flag = present[c] != 0;
        if (!m.comp_model_present_flag) continue;
        const std::string cs = indexed("", c);
        if (nint.empty() || nmv.empty() || !lower || !upper || !values)
            throw Error(ErrorCode::kInvalidParams,
                        "fgc: comp_model_present_flag" + cs +
                            " = 1 needs num_intensity_intervals_minus1, num_model_values_minus1, "
                            "intensity_interval_lower_bound, intensity_interval_upper_bound and comp_model_value");
        m.num_model_values_minus1 = nmv[c];
        const int n = nint[c] + 1;
        auto lo = JsonObject::int_array_at(*lower, c, n, 0, 255, "intensity_interval_lower_bound" + cs);
        auto hi = JsonObject::int_array_at(*upper, c, n, 0, 255, "intensity_interval_upper_bound" + cs);
        if (!values->is_array() || values->size() <= std::size_t(c) || !(*values)[c].is_array() ||
            (*values)[c].size() != std::size_t(n))
            throw Error(ErrorCode::kInvalidParams, "fgc: comp_model_value" + cs + " must be an array of " +
                                                       std::to_string(n) + " intervals");
        m.intervals.resize(n);
        for (int i = 0; i < n; i++) {
            const std::string is = indexed("", c, i);
            auto v = JsonObject::int_array_at((*values)[c], i, m.num_model_values_minus1 + 1, -(1 << 30), 1 << 30,
                                              "comp_model_value" + is);
            m.intervals[i].intensity_interval_lower_bound = lo[i];
            m.intervals[i].intensity_interval_upper_bound = hi[i];
            for (int k = 0; k <= m.num_model_values_minus1; k++) m.intervals[i].comp_model_value[k] = v[k];
        }
    }
    return p;
}

json fgc_params_to_json(const FgcParams& p) {
    json j;
    j["film_grain_characteristics_cancel_flag"] = int(p.film_grain_characteristics_cancel_flag);
    j["film_grain_model_id"] = p.film_grain_model_id;
    j["separate_colour_description_present_flag"] = int(p.separate_colour_description_present_flag);
    if (p.separate_colour_description_present_flag) {
        j["film_grain_bit_depth_luma_minus8"] = p.film_grain_bit_depth_luma_minus8;
        j["film_grain_bit_depth_chroma_minus8"] = p.film_grain_bit_depth_chroma_minus8;
        j["film_grain_full_range_flag"] = int(p.film_grain_full_range_flag);
        j["film_grain_colour_primaries"] = p.film_grain_colour_primaries;
        j["film_grain_transfer_characteristics"] = p.film_grain_transfer_characteristics;
        j["film_grain_matrix_coeffs"] = p.film_grain_matrix_coeffs;
    }
    j["blending_mode_id"] = p.blending_mode_id;
    j["log2_scale_factor"] = p.log2_scale_factor;
    json present = json::array(), nint = json::array(), nmv = json::array(), lo = json::array(), hi = json::array(),
         vals = json::array();
    for (int c = 0; c < 3; c++) {
        const auto& m = p.comp[c];
        present.push_back(int(m.comp_model_present_flag));
        json l = json::array(), h = json::array(), v = json::array();
        if (m.comp_model_present_flag) {
            for (const auto& iv : m.intervals) {
                l.push_back(iv.intensity_interval_lower_bound);
                h.push_back(iv.intensity_interval_upper_bound);
                json row = json::array();
                for (int k = 0; k <= m.num_model_values_minus1; k++) row.push_back(iv.comp_model_value[k]);
                v.push_back(row);
            }
        }
        nint.push_back(m.comp_model_present_flag ? int(m.intervals.size()) - 1 : 0);
        nmv.push_back(m.comp_model_present_flag ? m.num_model_values_minus1 : 0);
        lo.push_back(l);
        hi.push_back(h);
        vals.push_back(v);
    }
    j["comp_model_present_flag"] = present;
    j["num_intensity_intervals_minus1"] = nint;
    j["num_model_values_minus1"] = nmv;
    j["intensity_interval_lower_bound"] = lo;
    j["intensity_interval_upper_bound"] = hi;
    j["comp_model_value"] = vals;
    j["film_grain_characteristics_persistence_flag"] = int(p.film_grain_characteristics_persistence_flag);
    j["film_grain_characteristics_repetition_period"] = p.film_grain_characteristics_repetition_period;
    return j;
}

}  // namespace filmgrain

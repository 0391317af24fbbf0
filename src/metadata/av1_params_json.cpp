#include "metadata/av1_params_json.hpp"

#include <algorithm>
#include <string>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"
#include "metadata/json_access.hpp"

namespace filmgrain {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& msg) { throw Error(ErrorCode::kMalformedPayload, "AV1 params JSON: " + msg); }

// Every value is checked against what its syntax element can carry (AV1 5.9.30
// film_grain_params(): f(1) flags, f(16) grain_seed, f(8) points and coefficients, f(9)
// offsets...), so nothing wraps on the way into an int; the rules that depend on the frame
// (point order, chroma points of 4:2:0, bit depth) are av1::validate_params's.
int get_int(const json& j, const char* key, int fallback, bool required, long long lo, long long hi) {
    auto it = j.find(key);
    if (it == j.end() || it->is_null()) {
        if (required) fail(std::string("missing key \"") + key + "\"");
        return fallback;
    }
    if (!it->is_number_integer() && !it->is_boolean())
        fail(std::string("\"") + key + "\" must be an integer, got " + json_brief(*it));
    try {
        return int(json_to_integer(*it, lo, hi, std::string("\"") + key + "\""));
    } catch (const Error& e) {
        fail(e.what());
    }
}

// Reads an integer array of at most N entries into out (leaving the rest);
// returns the number read.
template <std::size_t N>
int get_array(const json& j, const char* key, std::array<int, N>& out, bool required, long long lo, long long hi) {
    auto it = j.find(key);
    if (it == j.end() || it->is_null()) {
        if (required) fail(std::string("missing key \"") + key + "\"");
        return 0;
    }
    if (!it->is_array()) fail(std::string("\"") + key + "\" must be an array");
    if (it->size() > N)
        fail(std::string("\"") + key + "\" has " + std::to_string(it->size()) + " entries (at most " +
             std::to_string(N) + " allowed)");
    for (std::size_t i = 0; i < it->size(); ++i) {
        const json& e = (*it)[i];
        const std::string name = indexed(key, i);
        if (!e.is_number_integer()) fail("\"" + name + "\" must be an integer, got " + json_brief(e));
        try {
            out[i] = int(json_to_integer(e, lo, hi, "\"" + name + "\""));
        } catch (const Error& err) {
            fail(err.what());
        }
    }
    return static_cast<int>(it->size());
}

template <std::size_t N>
void read_points(const json& j, const char* num_key, const char* value_key, const char* scaling_key, int& num,
                 std::array<int, N>& values, std::array<int, N>& scalings, bool required) {
    num = get_int(j, num_key, 0, required, 0, static_cast<int>(N));
    const int nv = get_array(j, value_key, values, required && num > 0, 0, 255);
    const int ns = get_array(j, scaling_key, scalings, required && num > 0, 0, 255);
    if ((j.contains(value_key) && nv != num) || (j.contains(scaling_key) && ns != num))
        fail(std::string("\"") + value_key + "\" / \"" + scaling_key + "\" must have " + num_key + " = " +
             std::to_string(num) + " entries (got " + std::to_string(nv) + " / " + std::to_string(ns) + ")");
}

template <std::size_t N>
void read_coeffs(const json& j, const char* key, std::array<int, N>& out, int expected, bool signalled) {
    const int n = get_array(j, key, out, signalled && expected > 0, 0, 255);
    if (signalled && n != expected)
        fail(std::string("\"") + key + "\" has " + std::to_string(n) + " entries, expected " +
             std::to_string(expected) + " for this ar_coeff_lag / num_y_points");
}

json int_array(const int* v, int n) {
    json a = json::array();
    for (int i = 0; i < n; ++i) a.push_back(v[i]);
    return a;
}

}  // namespace

Av1FilmGrainParams av1_params_from_json(const json& j) {
    if (!j.is_object()) fail("parameters must be a JSON object");
    Av1FilmGrainParams p;
    p.apply_grain = get_int(j, "apply_grain", 0, true, 0, 1);
    const bool req = p.apply_grain != 0;
    p.grain_seed = get_int(j, "grain_seed", 0, req, 0, 65535);
    p.update_grain = get_int(j, "update_grain", 1, false, 0, 1);
    p.film_grain_params_ref_idx = get_int(j, "film_grain_params_ref_idx", 0, false, 0, 7);
    read_points(j, "num_y_points", "point_y_value", "point_y_scaling", p.num_y_points, p.point_y_value,
                p.point_y_scaling, req);
    p.chroma_scaling_from_luma = get_int(j, "chroma_scaling_from_luma", 0, false, 0, 1);
    read_points(j, "num_cb_points", "point_cb_value", "point_cb_scaling", p.num_cb_points, p.point_cb_value,
                p.point_cb_scaling, false);
    read_points(j, "num_cr_points", "point_cr_value", "point_cr_scaling", p.num_cr_points, p.point_cr_value,
                p.point_cr_scaling, false);
    p.grain_scaling_minus_8 = get_int(j, "grain_scaling_minus_8", 0, req, 0, 3);
    p.ar_coeff_lag = get_int(j, "ar_coeff_lag", 0, req, 0, 3);
    read_coeffs(j, "ar_coeffs_y_plus_128", p.ar_coeffs_y_plus_128, p.num_pos_luma(), req && p.num_y_points > 0);
    read_coeffs(j, "ar_coeffs_cb_plus_128", p.ar_coeffs_cb_plus_128, p.num_pos_chroma(),
                req && (p.chroma_scaling_from_luma || p.num_cb_points > 0));
    read_coeffs(j, "ar_coeffs_cr_plus_128", p.ar_coeffs_cr_plus_128, p.num_pos_chroma(),
                req && (p.chroma_scaling_from_luma || p.num_cr_points > 0));
    p.ar_coeff_shift_minus_6 = get_int(j, "ar_coeff_shift_minus_6", 0, req, 0, 3);
    p.grain_scale_shift = get_int(j, "grain_scale_shift", 0, req, 0, 3);
    p.cb_mult = get_int(j, "cb_mult", 128, false, 0, 255);
    p.cb_luma_mult = get_int(j, "cb_luma_mult", 192, false, 0, 255);
    p.cb_offset = get_int(j, "cb_offset", 256, false, 0, 511);
    p.cr_mult = get_int(j, "cr_mult", 128, false, 0, 255);
    p.cr_luma_mult = get_int(j, "cr_luma_mult", 192, false, 0, 255);
    p.cr_offset = get_int(j, "cr_offset", 256, false, 0, 511);
    p.overlap_flag = get_int(j, "overlap_flag", 0, req, 0, 1);
    p.clip_to_restricted_range = get_int(j, "clip_to_restricted_range", 0, req, 0, 1);
    // 1: a set from an AFGS1 payload, which signals the chroma point counts (optional key)
    p.chroma_point_counts_signalled = get_int(j, "chroma_point_counts_signalled", 0, false, 0, 1) != 0;
    return p;
}

json av1_params_to_json(const Av1FilmGrainParams& p) {
    json j;
    j["apply_grain"] = p.apply_grain;
    if (!p.apply_grain) return j;  // nothing else is signalled
    j["grain_seed"] = p.grain_seed;
    j["update_grain"] = p.update_grain;
    if (!p.update_grain) j["film_grain_params_ref_idx"] = p.film_grain_params_ref_idx;
    const int ny = std::clamp(p.num_y_points, 0, 14), ncb = std::clamp(p.num_cb_points, 0, 10),
              ncr = std::clamp(p.num_cr_points, 0, 10);
    j["num_y_points"] = p.num_y_points;
    j["point_y_value"] = int_array(p.point_y_value.data(), ny);
    j["point_y_scaling"] = int_array(p.point_y_scaling.data(), ny);
    j["chroma_scaling_from_luma"] = p.chroma_scaling_from_luma;
    j["num_cb_points"] = p.num_cb_points;
    j["point_cb_value"] = int_array(p.point_cb_value.data(), ncb);
    j["point_cb_scaling"] = int_array(p.point_cb_scaling.data(), ncb);
    j["num_cr_points"] = p.num_cr_points;
    j["point_cr_value"] = int_array(p.point_cr_value.data(), ncr);
    j["point_cr_scaling"] = int_array(p.point_cr_scaling.data(), ncr);
    j["grain_scaling_minus_8"] = p.grain_scaling_minus_8;
    j["ar_coeff_lag"] = p.ar_coeff_lag;
    const int lag = std::clamp(p.ar_coeff_lag, 0, 3);
    const int npl = 2 * lag * (lag + 1), npc = npl + (p.num_y_points > 0 ? 1 : 0);
    j["ar_coeffs_y_plus_128"] = int_array(p.ar_coeffs_y_plus_128.data(), p.num_y_points > 0 ? npl : 0);
    j["ar_coeffs_cb_plus_128"] =
        int_array(p.ar_coeffs_cb_plus_128.data(), (p.chroma_scaling_from_luma || p.num_cb_points) ? npc : 0);
    j["ar_coeffs_cr_plus_128"] =
        int_array(p.ar_coeffs_cr_plus_128.data(), (p.chroma_scaling_from_luma || p.num_cr_points) ? npc : 0);
    j["ar_coeff_shift_minus_6"] = p.ar_coeff_shift_minus_6;
    j["grain_scale_shift"] = p.grain_scale_shift;
    const bool cb = p.num_cb_points > 0, cr = p.num_cr_points > 0;
    j["cb_mult"] = cb ? json(p.cb_mult) : json(nullptr);
    j["cb_luma_mult"] = cb ? json(p.cb_luma_mult) : json(nullptr);
    j["cb_offset"] = cb ? json(p.cb_offset) : json(nullptr);
    j["cr_mult"] = cr ? json(p.cr_mult) : json(nullptr);
    j["cr_luma_mult"] = cr ? json(p.cr_luma_mult) : json(nullptr);
    j["cr_offset"] = cr ? json(p.cr_offset) : json(nullptr);
    j["overlap_flag"] = p.overlap_flag;
    j["clip_to_restricted_range"] = p.clip_to_restricted_range;
    if (p.chroma_point_counts_signalled) j["chroma_point_counts_signalled"] = 1;  // an AFGS1 set
    return j;
}

Av1ColorInfo av1_color_info_from_json(const json& j) {
    if (!j.is_object()) fail("frame facts must be a JSON object");
    Av1ColorInfo c;
    // AV1 color_config(): BitDepth 8, 10 or 12; flags of one bit; matrix_coefficients f(8).
    c.bit_depth = get_int(j, "bit_depth", 8, false, 8, 12);
    if (c.bit_depth != 8 && c.bit_depth != 10 && c.bit_depth != 12)
        fail("\"bit_depth\" = " + std::to_string(c.bit_depth) + " is not an AV1 bit depth (allowed 8, 10, 12)");
    c.mono_chrome = get_int(j, "mono_chrome", 0, false, 0, 1);
    c.subsampling_x = get_int(j, "subsampling_x", 1, false, 0, 1);
    c.subsampling_y = get_int(j, "subsampling_y", 1, false, 0, 1);
    if (c.subsampling_y > c.subsampling_x)
        fail("subsampling_y = 1 with subsampling_x = 0 (4:4:0) is not an AV1 format (allowed subsampling_y <= "
             "subsampling_x)");
    c.matrix_coefficients = get_int(j, "matrix_coefficients", 2, false, 0, 255);
    return c;
}

void av1_color_info_to_json(const Av1ColorInfo& c, json& j) {
    j["bit_depth"] = c.bit_depth;
    j["mono_chrome"] = c.mono_chrome;
    j["subsampling_x"] = c.subsampling_x;
    j["subsampling_y"] = c.subsampling_y;
    j["matrix_coefficients"] = c.matrix_coefficients;
}

namespace {

// One frame from {"av1": {...}, facts...}, {"params": {"av1": ...}} or a bare parameter object.
Av1FrameParams frame_from_json(const json& e, const std::string& where) {
    if (!e.is_object()) fail(where + " must be a JSON object");
    try {
        if (auto it = e.find("params"); it != e.end() && it->is_object() && it->contains("av1"))
            return frame_from_json(*it, where + ".params");
        Av1FrameParams f;
        if (auto it = e.find("av1"); it != e.end()) {
            f.grain = av1_params_from_json(*it);
            if (e.contains("bit_depth") || e.contains("subsampling_x") || e.contains("mono_chrome") ||
                e.contains("matrix_coefficients"))
                f.color = av1_color_info_from_json(e);
        } else {
            f.grain = av1_params_from_json(e);
        }
        return f;
    } catch (const Error& err) {
        if (where.empty()) throw;
        throw Error(err.code(), std::string(err.what()) + " (in " + where + ")");
    }
}

}  // namespace

std::vector<Av1FrameParams> av1_frame_params_from_json(const json& doc) {
    if (!doc.is_object()) fail("document must be a JSON object");
    const json* list = nullptr;
    const char* name = nullptr;
    if (auto it = doc.find("frames_info"); it != doc.end() && it->is_array()) list = &*it, name = "frames_info";
    else if (auto it2 = doc.find("frames"); it2 != doc.end() && it2->is_array()) list = &*it2, name = "frames";
    std::vector<Av1FrameParams> out;
    if (!list) {
        out.push_back(frame_from_json(doc, ""));
        return out;
    }
    for (std::size_t i = 0; i < list->size(); ++i)
        out.push_back(frame_from_json((*list)[i], indexed(name, i)));
    return out;
}

json av1_frame_params_to_json(const std::vector<Av1FrameParams>& frames) {
    json arr = json::array();
    for (const auto& f : frames) {
        json e;
        e["av1"] = av1_params_to_json(f.grain);
        if (f.color) av1_color_info_to_json(*f.color, e);
        arr.push_back(std::move(e));
    }
    return json{{"frames", arr}};
}

}  // namespace filmgrain

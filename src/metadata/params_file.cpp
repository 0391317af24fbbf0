#include "metadata/params_file.hpp"

#include <fstream>
#include <sstream>

#include "filmgrain/error.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/json_access.hpp"

namespace filmgrain {

using nlohmann::json;

bool ParamsFile::has_fgc() const {
    for (const auto& f : frames)
        if (f.fgc) return true;
    return false;
}
bool ParamsFile::has_av1() const {
    for (const auto& f : frames)
        if (f.av1) return true;
    return false;
}

namespace {
bool looks_like_fgc(const json& j) {
    return j.contains("film_grain_model_id") || j.contains("comp_model_present_flag") ||
           j.contains("film_grain_characteristics_cancel_flag") || j.contains("log2_scale_factor");
}
bool looks_like_av1(const json& j) { return j.contains("apply_grain") || j.contains("num_y_points"); }

FrameParams frame_from_json(const json& e, std::size_t k) {
    const std::string ctx = "frames[" + std::to_string(k) + "]";
    JsonObject o(e, ctx);
    FrameParams f;
    if (o.has("poc")) f.poc = o.require_int("poc", INT32_MIN / 2, INT32_MAX / 2);
    if (o.has("idr_pic_id")) f.idr_pic_id = o.require_int("idr_pic_id", 0, 65535);
    if (o.has("pic_offset")) f.pic_offset = o.require_int("pic_offset", INT32_MIN / 2, INT32_MAX / 2);
    if (e.contains("pts") && e["pts"].is_number_integer()) f.pts = e["pts"].get<long long>();
    bool sei_present = !(e.contains("sei_present") && e["sei_present"].is_boolean() && !e["sei_present"].get<bool>());
    const json* params = &e;
    if (e.contains("params") && e["params"].is_object()) params = &e["params"];
    if (params->contains("fgc") && !(*params)["fgc"].is_null()) {
        if (sei_present) f.fgc = fgc_params_from_json((*params)["fgc"]);
    } else if (params->contains("av1") && !(*params)["av1"].is_null()) {
        json a = (*params)["av1"];
        // case.json keeps the picture facts beside "av1"; carry them along
        for (const char* key : {"bit_depth", "mono_chrome", "subsampling_x", "subsampling_y", "matrix_coefficients"})
            if (params->contains(key) && !a.contains(key)) a[key] = (*params)[key];
        f.av1 = a;
    }
    return f;
}
}  // namespace

ParamsFile parse_params_json(const json& j) {
    ParamsFile out;
    if (!j.is_object()) throw Error(ErrorCode::kInvalidParams, "parameter file: expected a JSON object");
    // case.json has "frames" as a count beside "frames_info"
    const char* list_key = j.contains("frames_info")                       ? "frames_info"
                           : j.contains("frames") && j["frames"].is_array() ? "frames"
                                                                           : nullptr;
    if (list_key) {
        const json& arr = j[list_key];
        if (!arr.is_array()) throw Error(ErrorCode::kInvalidParams, std::string("parameter file: '") + list_key + "' must be an array");
        out.per_frame = true;
        for (std::size_t k = 0; k < arr.size(); k++) out.frames.push_back(frame_from_json(arr[k], k));
        return out;
    }
    FrameParams f;
    if (j.contains("fgc")) f.fgc = fgc_params_from_json(j["fgc"]);
    else if (j.contains("av1")) f.av1 = j["av1"];
    else if (looks_like_fgc(j)) f.fgc = fgc_params_from_json(j);
    else if (looks_like_av1(j)) f.av1 = j;
    else
        throw Error(ErrorCode::kInvalidParams,
                    "parameter file: neither FGC SEI syntax elements (film_grain_model_id, ...) nor AV1 "
                    "film_grain_params (apply_grain, ...) nor a 'frames' list found");
    out.frames.push_back(f);
    return out;
}

ParamsFile load_params_file(const std::string& path) { return parse_params_json(read_json_file(path)); }

json params_file_to_json(const ParamsFile& f) {
    json frames = json::array();
    for (const auto& fr : f.frames) {
        json e = json::object();
        if (fr.poc) e["poc"] = *fr.poc;
        if (fr.idr_pic_id) e["idr_pic_id"] = *fr.idr_pic_id;
        if (fr.pic_offset) e["pic_offset"] = *fr.pic_offset;
        if (fr.pts) e["pts"] = *fr.pts;
        if (fr.fgc) e["fgc"] = fgc_params_to_json(*fr.fgc);
        if (fr.av1) e["av1"] = *fr.av1;
        frames.push_back(e);
    }
    if (!f.per_frame && f.frames.size() == 1) return frames[0];
    return json{{"frames", frames}};
}

}  // namespace filmgrain

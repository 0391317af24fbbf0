// The per-frame parameter file `filmgrain apply --params` reads and `params extract`
// writes. Accepted JSON shapes:
//   {...FGC syntax elements...}                   one SEI, received with the first picture
//   {"fgc": {...}} or {"av1": {...}}               the same, explicit model
//   {"frames": [{"poc": N, "idr_pic_id": N, "fgc": {...}}, {"poc": N+1}, ...]}
//   {"frames_info": [...]}                          the conformance case.json layout
// A frame entry without "fgc" (or with "sei_present": false) means no SEI arrived with
// that picture, and persistence decides. Without ids, frame k has POC k, idr_pic_id 0.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filmgrain/fgc_params.hpp"

namespace filmgrain {

struct FrameParams {
    std::optional<int> poc;
    std::optional<int> idr_pic_id;
    std::optional<int> pic_offset;  // overrides POC/idr_pic_id when a file gives it
    std::optional<FgcParams> fgc;   // an FGC SEI arrived with this picture
    std::optional<nlohmann::json> av1;  // AV1 film_grain_params() of this picture (raw JSON)
    std::optional<long long> pts;
};

struct ParamsFile {
    bool per_frame = false;            // false: `frames[0]` is received with the first picture only
    std::vector<FrameParams> frames;
    bool has_fgc() const;
    bool has_av1() const;
};

ParamsFile parse_params_json(const nlohmann::json& j);
ParamsFile load_params_file(const std::string& path);  // JSON; throws Error naming the key
nlohmann::json params_file_to_json(const ParamsFile& f);

}  // namespace filmgrain

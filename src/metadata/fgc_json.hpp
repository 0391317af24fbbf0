// The project's JSON form of an FGC SEI: one object whose keys are the SEI syntax element
// names (film_grain_model_id, log2_scale_factor, comp_model_present_flag[3], ...).
#pragma once
#include <nlohmann/json.hpp>

#include "filmgrain/fgc_params.hpp"

namespace filmgrain {

// Missing keys take the SEI's defaults (0 / not present). Throws Error(kInvalidParams)
// naming the key on a wrong type, a wrong array length or an out-of-range value.
FgcParams fgc_params_from_json(const nlohmann::json& j);
nlohmann::json fgc_params_to_json(const FgcParams& p);

}  // namespace filmgrain

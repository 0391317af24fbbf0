// AV1 film grain parameters <-> JSON, with the key names of the AV1 spec's
// film_grain_params() (as the conformance case.json `params.av1` uses them):
// raw bitstream values including the +128 / +256 biases, `null` for the chroma
// mult/offset fields of a component without points.
#pragma once
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "filmgrain/av1_params.hpp"

namespace filmgrain {

// Throws filmgrain::Error(kMalformedPayload) naming the key on a missing or
// mistyped field, or an array longer than its syntax allows. Ranges are not
// checked here (av1::validate_params does that against the frame format).
// Keys other than apply_grain may be absent when apply_grain is 0.
Av1FilmGrainParams av1_params_from_json(const nlohmann::json& j);
nlohmann::json av1_params_to_json(const Av1FilmGrainParams& p);

// bit_depth, mono_chrome, subsampling_x, subsampling_y, matrix_coefficients.
Av1ColorInfo av1_color_info_from_json(const nlohmann::json& j);
void av1_color_info_to_json(const Av1ColorInfo& c, nlohmann::json& j);

struct Av1FrameParams {
    Av1FilmGrainParams grain;
    std::optional<Av1ColorInfo> color;  // present when the JSON carried the frame facts
    bool operator==(const Av1FrameParams&) const = default;
};

// Per-frame parameters from any of these forms:
//   - a single parameter object {"apply_grain": ..., ...}             -> 1 frame
//   - {"av1": {...}, "bit_depth": ..., ...}                            -> 1 frame
//   - {"frames": [ {"av1": {...}, ...} | {"params": {"av1": ...}} ]}   -> one per element
//   - a conformance case.json {"frames_info": [ {"params": {"av1": ...}}, ... ]}
std::vector<Av1FrameParams> av1_frame_params_from_json(const nlohmann::json& doc);
// Writes the {"frames": [{"av1": {...}, <color facts>}, ...]} form.
nlohmann::json av1_frame_params_to_json(const std::vector<Av1FrameParams>& frames);

}  // namespace filmgrain

// The JSON parameter files (FGC and AV1 forms, per-frame lists, case.json). Input
// that is not JSON is the JSON library's business; once it parses as JSON, our
// readers may only fail with filmgrain::Error (naming the key), never with a
// JSON type error, a crash or another exception.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "filmgrain/error.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/params_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(data, data + size);
    } catch (const nlohmann::json::exception&) {
        return 0;
    }
    try {
        (void)filmgrain::parse_params_json(j);
    } catch (const filmgrain::Error&) {
    }
    try {
        const auto frames = filmgrain::av1_frame_params_from_json(j);
        (void)filmgrain::av1_frame_params_to_json(frames);
    } catch (const filmgrain::Error&) {
    }
    return 0;
}

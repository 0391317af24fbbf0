#include "bitstream/decode_restart.hpp"

namespace filmgrain::bitstream {

namespace {

// libavcodec's FGC SEI state before each unit (see the header).
struct ExportedFgcState {
    bool present = false;
    bool persists = false;
    void unit(const AccessUnit& au, StreamCodec codec) {
        for (const FoundFgc& f : au.fgc) {
            // a payload libavcodec refuses changes nothing either; it reads FGC in prefix SEI only
            if (!f.params || f.suffix) continue;
            present = !f.params->film_grain_characteristics_cancel_flag;
            persists = codec == StreamCodec::kH264 ? f.params->film_grain_characteristics_repetition_period != 0
                                                   : f.params->film_grain_characteristics_persistence_flag;
        }
        if (au.pictures > 0 && present) present = persists;
    }
};

}  // namespace

std::optional<DecodeRestart> plan_decode_restart(const StreamScan& scan, int64_t first_output) {
    if (!scan.warnings.empty() || scan.codec == StreamCodec::kH266) return std::nullopt;  // FFmpeg 5.1 has no H.266
    const bool av1 = scan.codec == StreamCodec::kAv1;
    if (av1 && scan.container != "ivf" && scan.container != "obu" && scan.container != "annexb-av1") return std::nullopt;
    std::optional<DecodeRestart> best;
    ExportedFgcState fgc;
    int64_t outputs = 0;
    std::vector<std::pair<std::size_t, std::size_t>> parameter_sets;
    for (const AccessUnit& au : scan.units) {
        if (outputs > first_output || !au.warnings.empty()) break;
        bool own_fgc = false;
        for (const FoundFgc& f : au.fgc) own_fgc |= f.params && !f.suffix;
        if (au.index > 0 && au.random_access && (av1 || own_fgc || !fgc.present)) {
            DecodeRestart r;
            r.unit = au.index;
            r.output_before = outputs;
            r.offset = au.offset;
            if (!av1) r.parameter_sets = parameter_sets;
            best = std::move(r);
        }
        if (!av1) fgc.unit(au, scan.codec);
        parameter_sets.insert(parameter_sets.end(), au.parameter_sets.begin(), au.parameter_sets.end());
        if (au.pictures > 0 && au.output) outputs++;
    }
    if (best && scan.container == "ivf") best->ivf_header_bytes = scan.units.front().offset;  // frames follow the header
    return best;
}

}  // namespace filmgrain::bitstream

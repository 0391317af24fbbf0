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

std::vector<DecodeRestart> decode_restart_points(const StreamScan& scan, int64_t last_output) {
    std::vector<DecodeRestart> points;
    if (!scan.warnings.empty() || scan.codec == StreamCodec::kH266) return points;  // FFmpeg 5.1 has no H.266
    const bool av1 = scan.codec == StreamCodec::kAv1;
    if (av1 && scan.container != "ivf" && scan.container != "obu" && scan.container != "annexb-av1") return points;
    ExportedFgcState fgc;
    int64_t outputs = 0;
    for (const AccessUnit& au : scan.units) {
        if (outputs > last_output || !au.warnings.empty()) break;
        bool own_fgc = false;
        for (const FoundFgc& f : au.fgc) own_fgc |= f.params && !f.suffix;
        if (au.index > 0 && au.random_access && (av1 || own_fgc || !fgc.present)) {
            DecodeRestart r;
            r.unit = au.index;
            r.output_before = outputs;
            r.offset = au.offset;
            if (scan.container == "ivf") r.ivf_header_bytes = scan.units.front().offset;  // frames follow the header
            points.push_back(std::move(r));
        }
        if (!av1) fgc.unit(au, scan.codec);
        if (au.pictures > 0 && au.output) outputs++;
    }
    return points;
}

std::optional<DecodeRestart> plan_decode_restart(const StreamScan& scan, int64_t first_output) {
    std::vector<DecodeRestart> points = decode_restart_points(scan, first_output);
    if (points.empty()) return std::nullopt;
    DecodeRestart r = std::move(points.back());
    // AV1's sequence header travels in the restart unit itself (random_access requires it)
    for (int i = 0; i < r.unit && scan.codec != StreamCodec::kAv1; i++)
        r.parameter_sets.insert(r.parameter_sets.end(), scan.units[std::size_t(i)].parameter_sets.begin(),
                                scan.units[std::size_t(i)].parameter_sets.end());
    return r;
}

}  // namespace filmgrain::bitstream

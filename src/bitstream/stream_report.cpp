#include "bitstream/stream_report.hpp"

#include <cstdio>
#include <variant>

#include "bitstream/afgs1_in_stream.hpp"
#include "core/field_names.hpp"
#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_json.hpp"

namespace filmgrain::bitstream {
namespace {

using nlohmann::json;

std::string hex(const std::vector<uint8_t>& b, std::size_t max_bytes) {
    std::string s;
    char buf[4];
    for (std::size_t i = 0; i < b.size() && i < max_bytes; i++) {
        std::snprintf(buf, sizeof buf, "%02x", b[i]);
        s += buf;
    }
    if (b.size() > max_bytes) s += "...";
    return s;
}

std::string afgs1_target_text(const Afgs1SetTarget& t) {
    std::string s = std::to_string(t.width()) + "x" + std::to_string(t.height()) + " " +
                    (t.luma_only_flag         ? "4:0:0"
                     : t.subsampling_y        ? "4:2:0"
                     : t.subsampling_x        ? "4:2:2"
                                              : "4:4:4");
    s += t.video_signal_characteristics_flag ? " " + std::to_string(8 + t.bit_depth_minus8) + "-bit" : " any depth";
    return s;
}

std::string afgs1_summary(const Afgs1Payload& payload) {
    if (!payload.afgs1_enable_flag) return "afgs1_enable_flag 0 (no grain)";
    std::string s = std::to_string(payload.sets.size()) + " set(s)";
    for (const Afgs1ParamSet& set : payload.sets) {
        const Av1FilmGrainParams& p = set.params;
        s += "; #" + std::to_string(set.film_grain_param_set_idx) + " ";
        if (!p.apply_grain) {
            s += "apply_grain_flag 0";
            continue;
        }
        s += afgs1_target_text(set.target) + ", seed " + std::to_string(p.grain_seed);
        if (!p.update_grain) s += " on the stored parameters";
        s += ", points Y " + std::to_string(p.num_y_points) +
             (p.chroma_scaling_from_luma ? std::string(", Cb/Cr from luma")
                                         : " Cb " + std::to_string(p.num_cb_points) + " Cr " +
                                               std::to_string(p.num_cr_points)) +
             ", ar_coeff_lag " + std::to_string(p.ar_coeff_lag);
    }
    return s;
}

json afgs1_to_json(const Afgs1Payload& payload) {
    json sets = json::array();
    for (const Afgs1ParamSet& set : payload.sets) {
        const Av1FilmGrainParams& p = set.params;
        json j{{"film_grain_param_set_idx", set.film_grain_param_set_idx}, {"apply_grain", p.apply_grain}};
        if (p.apply_grain) {
            const Afgs1SetTarget& t = set.target;
            j.update({{"update_grain", p.update_grain},
                      {"grain_seed", p.grain_seed},
                      {"width", t.width()},
                      {"height", t.height()},
                      {"luma_only", t.luma_only_flag},
                      {"subsampling_x", t.subsampling_x},
                      {"subsampling_y", t.subsampling_y},
                      {"num_y_points", p.num_y_points},
                      {"chroma_scaling_from_luma", p.chroma_scaling_from_luma},
                      {"num_cb_points", p.num_cb_points},
                      {"num_cr_points", p.num_cr_points},
                      {"ar_coeff_lag", p.ar_coeff_lag}});
            if (t.video_signal_characteristics_flag) j["bit_depth"] = 8 + t.bit_depth_minus8;
        }
        sets.push_back(j);
    }
    return json{{"afgs1_enable_flag", payload.afgs1_enable_flag}, {"sets", sets}};
}

json t35_to_json(const FoundT35& t) {
    json j{{"suffix", t.suffix}, {"country_code", t.t35.country_code}, {"size", t.t35.bytes.size()}};
    if (t.t35.country_code_extension >= 0) j["country_code_extension"] = t.t35.country_code_extension;
    if (t.t35.provider_code >= 0) j["provider_code"] = t.t35.provider_code;
    if (t.t35.provider_oriented_code >= 0) j["provider_oriented_code"] = t.t35.provider_oriented_code;
    j["afgs1"] = is_afgs1_t35(t.t35);
    j["hex"] = hex(t.t35.bytes, 4096);
    return j;
}

std::string fgc_summary(const FgcParams& p) {
    if (p.film_grain_characteristics_cancel_flag) return "cancel";
    std::string s = "model " + std::to_string(p.film_grain_model_id) + ", blending " +
                    std::to_string(p.blending_mode_id) + ", log2_scale_factor " + std::to_string(p.log2_scale_factor);
    for (int c = 0; c < 3; c++)
        if (p.comp[c].comp_model_present_flag)
            s += ", " + std::string(plane_name(c)) + ": " + std::to_string(p.comp[c].intervals.size()) + " interval(s)";
    s += ", persistence " + std::to_string(int(p.film_grain_characteristics_persistence_flag));
    return s;
}

}  // namespace

json stream_scan_to_json(const StreamScan& scan) {
    json units = json::array();
    const std::vector<std::vector<Afgs1Read>> afgs1 = read_afgs1_in_decode_order(scan);
    for (std::size_t unit = 0; unit < scan.units.size(); unit++) {
        const AccessUnit& u = scan.units[unit];
        json j{{"index", u.index}, {"offset", u.offset}, {"nal_units", u.nal_units}, {"pictures", u.pictures}};
        if (!u.picture_type.empty()) j["picture_type"] = u.picture_type;
        if (u.poc) j["poc"] = *u.poc;
        if (u.idr_pic_id) j["idr_pic_id"] = *u.idr_pic_id;
        if (scan.codec != StreamCodec::kAv1) j["sequence"] = u.sequence;
        j["output"] = u.output;
        if (u.pts) j["pts"] = *u.pts;
        if (const auto& h = u.av1_sequence_header)
            j["sequence_header"] = json{{"seq_profile", h->seq_profile},
                                        {"max_frame_width", h->max_frame_width},
                                        {"max_frame_height", h->max_frame_height},
                                        {"bit_depth", h->bit_depth},
                                        {"mono_chrome", h->mono_chrome},
                                        {"subsampling_x", h->subsampling_x},
                                        {"subsampling_y", h->subsampling_y},
                                        {"matrix_coefficients", h->matrix_coefficients},
                                        {"film_grain_params_present", h->film_grain_params_present}};
        json fgc = json::array();
        for (const FoundFgc& f : u.fgc) {
            json e{{"suffix", f.suffix}, {"size", f.payload.size()}};
            if (f.params)
                e["params"] = fgc_params_to_json(*f.params);
            else
                e["error"] = f.error;
            fgc.push_back(e);
        }
        j["fgc"] = fgc;
        json t35 = json::array();
        for (std::size_t i = 0; i < u.t35.size(); i++) {
            json e = t35_to_json(u.t35[i]);
            const Afgs1Read& read = afgs1[unit][i];
            if (const auto* p = std::get_if<Afgs1Payload>(&read)) e["afgs1_payload"] = afgs1_to_json(*p);
            if (const auto* err = std::get_if<std::string>(&read)) e["afgs1_error"] = *err;
            t35.push_back(e);
        }
        j["t35"] = t35;
        j["warnings"] = u.warnings;
        units.push_back(j);
    }
    return json{{"codec", stream_codec_name(scan.codec)},
                {"container", scan.container},
                {"poc_support", scan.poc_support},
                {"warnings", scan.warnings},
                {"access_units", units}};
}

std::string stream_scan_to_text(const StreamScan& scan) {
    std::string s = std::string(stream_codec_name(scan.codec)) + " (" + scan.container + "), " +
                    std::to_string(scan.units.size()) + (scan.codec == StreamCodec::kAv1 ? " temporal" : " access") +
                    " unit(s); POC: " + scan.poc_support + "\n";
    for (const std::string& w : scan.warnings) s += "warning: " + w + "\n";
    int fgc = 0, t35 = 0;
    const std::vector<std::vector<Afgs1Read>> afgs1 = read_afgs1_in_decode_order(scan);
    for (std::size_t unit = 0; unit < scan.units.size(); unit++) {
        const AccessUnit& u = scan.units[unit];
        s += (scan.codec == StreamCodec::kAv1 ? "TU " : "AU ") + std::to_string(u.index) + " @" + std::to_string(u.offset);
        if (!u.picture_type.empty()) s += " " + u.picture_type;
        if (u.poc) s += " poc=" + std::to_string(*u.poc);
        if (u.idr_pic_id) s += " idr_pic_id=" + std::to_string(*u.idr_pic_id);
        if (u.pts) s += " pts=" + std::to_string(*u.pts);
        if (!u.output) s += " (not output)";
        s += "\n";
        if (const auto& h = u.av1_sequence_header)
            s += "  sequence header: profile " + std::to_string(h->seq_profile) + ", " +
                 std::to_string(h->max_frame_width) + "x" + std::to_string(h->max_frame_height) + ", " +
                 std::to_string(h->bit_depth) + "-bit, " +
                 (h->mono_chrome ? std::string("4:0:0")
                                 : h->subsampling_y ? std::string("4:2:0")
                                 : h->subsampling_x ? std::string("4:2:2")
                                                    : std::string("4:4:4")) +
                 ", film_grain_params_present " + std::to_string(h->film_grain_params_present) + "\n";
        for (const FoundFgc& f : u.fgc) {
            fgc++;
            s += std::string("  FGC SEI (") + (f.suffix ? "suffix" : "prefix") + ", " + std::to_string(f.payload.size()) +
                 " bytes): " + (f.params ? fgc_summary(*f.params) : "unparsable: " + f.error) + "\n";
        }
        for (std::size_t i = 0; i < u.t35.size(); i++) {
            const FoundT35& t = u.t35[i];
            t35++;
            char buf[160];
            std::snprintf(buf, sizeof buf, "  ITU-T T.35 (country 0x%02X, provider 0x%04X, %zu bytes)%s",
                          t.t35.country_code, t.t35.provider_code < 0 ? 0 : t.t35.provider_code, t.t35.bytes.size(),
                          is_afgs1_t35(t.t35) ? " AFGS1" : "");
            s += buf;
            const Afgs1Read& read = afgs1[unit][i];
            if (const auto* p = std::get_if<Afgs1Payload>(&read)) s += ": " + afgs1_summary(*p);
            if (const auto* err = std::get_if<std::string>(&read)) s += ": unreadable: " + *err;
            s += "\n";
        }
        for (const std::string& w : u.warnings) s += "  warning: " + w + "\n";
    }
    s += std::to_string(fgc) + " FGC SEI message(s), " + std::to_string(t35) + " T.35 payload(s), " +
         std::to_string(scan.bad_units()) + " damaged unit(s)\n";
    return s;
}

ParamsFile params_file_from_scan(const StreamScan& scan, std::vector<std::string>& warnings) {
    if (scan.codec == StreamCodec::kAv1)
        throw Error(ErrorCode::kUnsupported,
                    "AV1 streams: film grain parameters are AV1 sets (AFGS1 metadata or frame headers), not FGC "
                    "SEIs; use av1_params_from_scan");
    ParamsFile f;
    f.per_frame = true;
    for (const AccessUnit* u : units_in_output_order(scan)) {
        FrameParams fp;
        fp.poc = u->poc;
        if (scan.codec == StreamCodec::kH264) fp.idr_pic_id = u->idr_pic_id;
        for (const FoundFgc& g : u->fgc) {
            if (!g.params) {
                warnings.push_back("AU " + std::to_string(u->index) + ": FGC SEI skipped: " + g.error);
            } else if (!fp.fgc) {
                fp.fgc = g.params;
            } else {
                warnings.push_back("AU " + std::to_string(u->index) + ": more than one FGC SEI; the first is used");
            }
        }
        f.frames.push_back(std::move(fp));
    }
    if (f.frames.empty()) throw Error(ErrorCode::kMalformedPayload, "the stream holds no decodable picture");
    return f;
}

}  // namespace filmgrain::bitstream

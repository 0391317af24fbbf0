// `filmgrain params convert`: one parameter form into another that can express it.
//   AV1 model:  JSON (film_grain_params names)  <->  libaom filmgrn1 table  <->  AFGS1 T.35 payload
//   FGC model:  JSON (SEI syntax element names) <->  raw FGC SEI payload (--sei-codec)
// What the target form cannot carry is named on stderr; the exit status is non-zero
// only when nothing sensible can be written (e.g. FGC parameters to an AV1 form).
#include <cctype>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>

#include "cli_common.hpp"
#include "grain_outputs.hpp"
#include "filmgrain/error.hpp"
#include "io/xz_file.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/json_access.hpp"
#include "metadata/params_file.hpp"
#include "io/payload_files.hpp"
#include "session/parameter_file_feed.hpp"

namespace filmgrain::cli {
namespace {

struct ConvertOptions {
    std::vector<std::string> inputs;
    std::string output, from, to, sei_codec = "hevc";
    std::string size;  // picture size for AFGS1 (target resolution / set selection)
    std::string pix_fmt;
    std::string fps = "25";
    int frames = 0;
    bool quiet = false;
};

using Form = session::ParameterForm;
using io::FilePattern;
using io::PayloadFiles;

std::string form_name(Form f) { return session::parameter_form_name(f); }

Form parse_form(const std::string& s, const char* option) {
    if (s == "json") return Form::kJson;
    if (s == "tbl" || s == "table") return Form::kTable;
    if (s == "afgs1") return Form::kAfgs1;
    if (s == "sei") return Form::kSei;
    throw Error(ErrorCode::kInvalidArgument,
                std::string(option) + " '" + s + "' is not known (allowed json, tbl, afgs1, sei)");
}

Form detect_input(const ConvertOptions& o, bool sei_codec_given) {
    if (!o.from.empty()) return parse_form(o.from, "--from");
    return session::detect_parameter_form(o.inputs[0], sei_codec_given);
}

class Notes {
public:
    explicit Notes(bool quiet) : quiet_(quiet) {}
    void add(const std::string& what) {
        if (seen_[what]++ == 0 && !quiet_) std::fprintf(stderr, "filmgrain: not carried: %s\n", what.c_str());
    }

private:
    bool quiet_;
    std::map<std::string, int> seen_;
};

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    write_file_atomically(path, std::string(bytes.begin(), bytes.end()));
}

// ------------------------------------------------------------------ AV1 forms

int64_t ticks_per_frame(const VideoInfo& info) { return int64_t(10000000) * info.fps_den / info.fps_num; }

std::vector<Av1FrameParams> frames_from_table(const AomGrainTable& t, const ConvertOptions& o, const VideoInfo& info,
                                              Notes& notes) {
    const int64_t tick = ticks_per_frame(info);
    int count = o.frames;
    if (count <= 0) {
        int64_t end = 0;
        for (const auto& e : t.entries) end = std::max(end, e.end_time);
        const int64_t n = (end + tick - 1) / tick;
        if (n > 100000)
            throw Error(ErrorCode::kInvalidArgument, "the table spans " + std::to_string(n) +
                                                         " frames at --fps " + o.fps + "; say how many with --frames");
        count = int(std::max<int64_t>(n, 1));
    }
    std::vector<Av1FrameParams> frames;
    for (int k = 0; k < count; ++k) {
        Av1FrameParams f;
        const auto idx = t.find_index(int64_t(k) * tick);
        if (idx) f.grain = t.resolved_params(*idx);
        else notes.add("frames without a table entry (written with apply_grain = 0)");
        frames.push_back(f);
    }
    return frames;
}

AomGrainTable table_from_frames(const std::vector<Av1FrameParams>& frames, const VideoInfo& info, Notes& notes) {
    const int64_t tick = ticks_per_frame(info);
    AomGrainTable t;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        Av1FilmGrainParams p = frames[k].grain;
        if (p.clip_to_restricted_range) notes.add("clip_to_restricted_range = 1 (filmgrn1 tables have no field for it)");
        if (frames[k].color)
            notes.add("bit_depth / subsampling / matrix_coefficients (tables describe no picture format)");
        p.clip_to_restricted_range = 0;
        p.update_grain = 1;
        p.film_grain_params_ref_idx = 0;
        if (!t.entries.empty() && t.entries.back().params == p) {
            t.entries.back().end_time = int64_t(k + 1) * tick;
            continue;
        }
        AomGrainTableEntry e;
        e.start_time = int64_t(k) * tick;
        e.end_time = int64_t(k + 1) * tick;
        e.params = p;
        t.entries.push_back(e);
    }
    return t;
}

std::optional<Av1ColorInfo> color_of(const Afgs1SetTarget& t) {
    if (!t.video_signal_characteristics_flag && t.luma_only_flag == 0 && t.subsampling_x == 1 && t.subsampling_y == 1)
        return std::nullopt;
    Av1ColorInfo c;
    c.mono_chrome = t.luma_only_flag;
    c.subsampling_x = t.luma_only_flag ? 1 : t.subsampling_x;
    c.subsampling_y = t.luma_only_flag ? 1 : t.subsampling_y;
    c.bit_depth = t.video_signal_characteristics_flag ? t.bit_depth_minus8 + 8 : 8;
    if (t.cicp_info_present_flag) c.matrix_coefficients = t.matrix_coefficients;
    return c;
}

std::vector<Av1FrameParams> frames_from_afgs1(const PayloadFiles& files, const ConvertOptions& o, Notes& notes) {
    Afgs1Reader reader;
    std::vector<Av1FrameParams> frames;
    const auto payloads = files.all();
    for (std::size_t k = 0; k < payloads.size(); ++k) {
        const auto& b = payloads[k];
        const Afgs1Payload pl = reader.receive(b, afgs1_has_t35_header(b.data(), b.size()));
        Av1FrameParams f;
        if (!pl.afgs1_enable_flag || pl.sets.empty()) {
            frames.push_back(f);
            continue;
        }
        std::size_t chosen = 0;
        if (!o.size.empty()) {
            RawVideoOptions r;
            r.size = o.size;
            if (!o.pix_fmt.empty()) r.pix_fmt = o.pix_fmt;
            const VideoInfo vi = r.to_info();
            const auto sel = select_afgs1_set(pl, Afgs1Picture{vi.width, vi.height, vi.format.chroma,
                                                               vi.format.bit_depth});
            if (!sel) {
                notes.add("payloads with no set for a " + o.size + " picture (written with apply_grain = 0)");
                frames.push_back(f);
                continue;
            }
            chosen = sel->set_index;
        }
        if (pl.sets.size() > 1)
            notes.add("all but one parameter set of multi-set payloads (the one " +
                      std::string(o.size.empty() ? "signalled first" : "selected for --size") + " is kept)");
        const Afgs1ParamSet& s = pl.sets[chosen];
        f.grain = afgs1_set_as_frame_params(s);
        f.color = color_of(s.target);
        if (s.target.apply_horz_resolution || s.target.apply_vert_resolution)
            notes.add("apply_horz_resolution / apply_vert_resolution (the target picture size)");
        if (s.target.cicp_info_present_flag)
            notes.add("color_primaries / transfer_characteristics / video_full_range_flag");
        frames.push_back(f);
    }
    if (frames.empty()) throw Error(ErrorCode::kInvalidParams, "no AFGS1 payload found in the input");
    return frames;
}

Afgs1SetTarget target_for(const Av1FrameParams& f, const ConvertOptions& o, Notes& notes) {
    Afgs1SetTarget t;
    if (!o.size.empty()) {
        RawVideoOptions r;
        r.size = o.size;
        const VideoInfo vi = r.to_info();
        // The finest unit in which both dimensions fit 12 bits.
        int log2 = 0;
        while (((vi.width >> log2) > 4095 || (vi.height >> log2) > 4095) && log2 < 15) ++log2;
        if ((vi.width >> log2 << log2) != vi.width || (vi.height >> log2 << log2) != vi.height)
            notes.add("the exact picture size (not a multiple of the resolution unit)");
        t.apply_units_resolution_log2 = log2;
        t.apply_horz_resolution = vi.width >> log2;
        t.apply_vert_resolution = vi.height >> log2;
    } else {
        notes.add("a target picture size (no --size: written as 0x0, which fits any picture)");
    }
    Av1ColorInfo c;
    bool known = false;
    if (f.color) {
        c = *f.color;
        known = true;
    } else if (!o.pix_fmt.empty()) {
        RawVideoOptions r;
        r.pix_fmt = o.pix_fmt;
        c = av1_color_of(r.to_info().format, c.matrix_coefficients);
        known = true;
    } else {
        notes.add("the picture format (no --pix-fmt and none in the input: 4:2:0 assumed, bit depth not signalled)");
    }
    t.luma_only_flag = c.mono_chrome;
    t.subsampling_x = c.mono_chrome ? 0 : c.subsampling_x;
    t.subsampling_y = c.mono_chrome ? 0 : c.subsampling_y;
    if (known) {
        t.video_signal_characteristics_flag = 1;
        t.bit_depth_minus8 = c.bit_depth - 8;
        if (c.matrix_coefficients != 2) {
            // matrix_coefficients only travels with the other CICP fields, unspecified here.
            t.cicp_info_present_flag = 1;
            t.color_primaries = 2;
            t.transfer_characteristics = 2;
            t.matrix_coefficients = c.matrix_coefficients;
            t.video_full_range_flag = 0;
        }
    }
    return t;
}

// One payload per frame; a frame whose parameters equal the previous one's but for
// the seed is sent as update_grain_flag = 0 (the stored set with a new seed).
std::vector<std::vector<uint8_t>> afgs1_from_frames(const std::vector<Av1FrameParams>& frames,
                                                    const ConvertOptions& o, Notes& notes) {
    std::vector<std::vector<uint8_t>> out;
    std::optional<Afgs1ParamSet> previous;
    for (const auto& f : frames) {
        Afgs1ParamSet s;
        s.film_grain_param_set_idx = 0;
        s.params = f.grain;
        s.params.film_grain_params_ref_idx = 0;
        s.params.update_grain = 1;
        s.target = target_for(f, o, notes);
        if (f.grain.apply_grain && previous && previous->params.apply_grain) {
            Av1FilmGrainParams a = previous->params, b = s.params;
            a.grain_seed = b.grain_seed = 0;
            if (a == b && previous->target == s.target) s.params.update_grain = 0;
        }
        Afgs1Payload pl;
        pl.sets.push_back(s);
        out.push_back(write_afgs1(pl));
        if (s.params.update_grain) previous = s;
    }
    return out;
}

void write_payloads(const std::vector<std::vector<uint8_t>>& payloads, const std::string& output, Notes& notes) {
    bool all_same = true;
    for (const auto& p : payloads) all_same = all_same && p == payloads[0];
    const auto pattern = FilePattern::parse(output);
    if (!pattern) {
        if (!all_same)
            notes.add("frames 1.." + std::to_string(payloads.size() - 1) +
                      " (one payload file per picture needs an output pattern such as out%d.bin)");
        write_bytes(output, payloads[0]);
        return;
    }
    for (std::size_t k = 0; k < payloads.size(); ++k) write_bytes(pattern->name_for(int(k)), payloads[k]);
}

std::vector<Av1FrameParams> read_av1(Form from, const ConvertOptions& o, const VideoInfo& info, Notes& notes) {
    if (from == Form::kTable) return frames_from_table(read_aom_grain_table(o.inputs[0]), o, info, notes);
    if (from == Form::kAfgs1) return frames_from_afgs1(PayloadFiles(o.inputs), o, notes);
    auto frames = av1_frame_params_from_json(read_json_file(o.inputs[0]));
    if (frames.empty()) throw Error(ErrorCode::kInvalidParams, "'" + o.inputs[0] + "' holds no AV1 parameters");
    return frames;
}

// ------------------------------------------------------------------ FGC forms

ParamsFile read_fgc(Form from, const ConvertOptions& o, FgcCodec codec) {
    if (from == Form::kJson) return load_params_file(o.inputs[0]);
    ParamsFile pf;
    const PayloadFiles files(o.inputs);
    pf.per_frame = !files.one_for_every_picture();
    for (const auto& b : files.all()) {
        FrameParams f;
        f.fgc = parse_fgc_sei_payload(b, codec);
        pf.frames.push_back(f);
    }
    if (pf.frames.empty()) throw Error(ErrorCode::kInvalidParams, "no FGC SEI payload found in the input");
    return pf;
}

int run_convert(const ConvertOptions& o, bool sei_codec_given) {
    if (o.inputs.empty()) throw Error(ErrorCode::kInvalidArgument, "give an input file");
    const Form from = detect_input(o, sei_codec_given);
    const Form to = o.to.empty() ? session::parameter_form_from_name(o.output, sei_codec_given) : parse_form(o.to, "--to");
    RawVideoOptions r;
    r.fps = o.fps;
    const VideoInfo info = r.to_info();
    Notes notes(o.quiet);

    // Which model the input holds.
    bool fgc = from == Form::kSei;
    if (from == Form::kJson) {
        const ParamsFile pf = load_params_file(o.inputs[0]);
        fgc = pf.has_fgc();
    }
    if (fgc) {
        if (to != Form::kJson && to != Form::kSei)
            throw Error(ErrorCode::kInvalidParams, "FGC SEI parameters (frequency-filtering model) cannot be "
                                                   "expressed as " + form_name(to) +
                                                   " (an AV1 auto-regressive form); convert to json or sei");
        const FgcCodec codec = parse_fgc_codec(o.sei_codec);
        ParamsFile pf = read_fgc(from, o, codec);
        if (to == Form::kJson) {
            write_file_atomically(o.output, params_file_to_json(pf).dump(2) + "\n");
        } else {
            std::vector<std::vector<uint8_t>> payloads;
            for (std::size_t k = 0; k < pf.frames.size(); ++k) {
                const auto& f = pf.frames[k];
                if (!f.fgc) {
                    notes.add("pictures without an SEI (no payload file is written for them)");
                    continue;
                }
                if (f.poc || f.idr_pic_id || f.pic_offset) notes.add("poc / idr_pic_id (SEI payloads carry no picture ids)");
                payloads.push_back(write_fgc_sei_payload(*f.fgc, codec));
            }
            if (payloads.empty()) throw Error(ErrorCode::kInvalidParams, "the input holds no FGC SEI to write");
            write_payloads(payloads, o.output, notes);
        }
    } else {
        if (to == Form::kSei)
            throw Error(ErrorCode::kInvalidParams, "AV1 film grain parameters cannot be expressed as an FGC SEI "
                                                   "payload (a different synthesis model)");
        const std::vector<Av1FrameParams> frames = read_av1(from, o, info, notes);
        if (to == Form::kJson) {
            write_file_atomically(o.output, av1_frame_params_to_json(frames).dump(2) + "\n");
        } else if (to == Form::kTable) {
            write_aom_grain_table(table_from_frames(frames, info, notes), o.output);
        } else {
            write_payloads(afgs1_from_frames(frames, o, notes), o.output, notes);
        }
    }
    if (!o.quiet)
        std::fprintf(stderr, "filmgrain: %s -> %s written to %s\n", form_name(from).c_str(), form_name(to).c_str(),
                     o.output.c_str());
    return 0;
}

}  // namespace

void register_params(CLI::App& app) {
    CLI::App* params = app.add_subcommand("params", "parameter files: convert between forms");
    params->require_subcommand(1);
    auto o = std::make_shared<ConvertOptions>();
    CLI::App* conv = params->add_subcommand(
        "convert", "convert parameters: AV1 JSON <-> libaom grain table <-> AFGS1 T.35 payload; FGC JSON <-> FGC SEI");
    conv->add_option("input", o->inputs,
                     "input: JSON, .tbl, AFGS1 or SEI payload file(s) (several for pictures 0,1,... or a %d pattern)")
        ->required();
    conv->add_option("--output,-o", o->output, "output file (or a %d pattern for per-picture payloads)")->required();
    conv->add_option("--to", o->to, "json, tbl, afgs1 or sei (default: from the output name; .bin = afgs1)");
    conv->add_option("--from", o->from, "json, tbl, afgs1 or sei (default: from the content and name)");
    auto* codec = conv->add_option("--sei-codec", o->sei_codec, "FGC SEI syntax: avc, hevc or vvc")->capture_default_str();
    conv->add_option("--size", o->size,
                     "picture size WxH: AFGS1 target resolution when writing, set selection when reading");
    conv->add_option("--pix-fmt", o->pix_fmt, "picture format (AFGS1 subsampling and bit depth when the input has none)");
    conv->add_option("--fps", o->fps, "frame rate N or N/D: grain table timestamps (10 MHz ticks)")->capture_default_str();
    conv->add_option("--frames", o->frames, "frames to take from a grain table (default: the table's time span)");
    conv->add_flag("--quiet,-q", o->quiet, "no messages on stderr except errors");
    conv->callback([o, codec]() {
        const int rc = run_convert(*o, codec->count() > 0);
        if (rc) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli

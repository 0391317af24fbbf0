// `filmgrain inspect STREAM [--json]` and `filmgrain params extract STREAM -o params.json`:
// the film grain metadata inside a coded H.264/H.265/H.266/AV1 stream.
#include <cstdio>
#include <fstream>
#include <memory>

#include "bitstream/av1_grain_extraction.hpp"
#include "bitstream/stream_report.hpp"
#include "bitstream/stream_scan.hpp"
#include "cli_common.hpp"
#include "option_parsing.hpp"
#include "grain_outputs.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::cli {
namespace {

struct InspectOptions {
    std::string stream, codec, output;
    std::string size, pix_fmt;  // params extract of AFGS1 in H.26x: the picture sets are selected for
    bool json = false;
    bool quiet = false;
};

bitstream::StreamScan scan(const InspectOptions& o) {
    std::optional<bitstream::StreamCodec> codec;
    if (!o.codec.empty()) codec = bitstream::parse_stream_codec(o.codec);
    return bitstream::scan_stream_file(o.stream, codec);
}

int run_inspect(const InspectOptions& o) {
    const bitstream::StreamScan s = scan(o);
    if (o.json)
        std::printf("%s\n", bitstream::stream_scan_to_json(s).dump(2).c_str());
    else
        std::fputs(bitstream::stream_scan_to_text(s).c_str(), stdout);
    // Damage is reported per unit and does not fail the listing; a stream with nothing
    // recognisable in it does.
    if (s.units.empty()) throw Error(ErrorCode::kMalformedPayload, "'" + o.stream + "' holds no access unit");
    return 0;
}

// Writes per-picture AV1 parameters in the per-frame form after the warnings, and the summary
// "N <units>, M with <grain>, written to ...".
int write_av1_frames(const InspectOptions& o, const std::vector<Av1FrameParams>& frames,
                     const std::vector<std::string>& warnings, const char* units, const char* grain) {
    if (!o.quiet)
        for (const auto& w : warnings) std::fprintf(stderr, "filmgrain: warning: %s\n", w.c_str());
    write_file_atomically(o.output, av1_frame_params_to_json(frames).dump(1) + "\n");
    int with_grain = 0;
    for (const auto& f : frames) with_grain += f.grain.apply_grain != 0;
    if (!o.quiet && o.output != "-")
        std::fprintf(stderr, "filmgrain: %zu %s, %d with %s, written to %s\n", frames.size(), units, with_grain, grain,
                     o.output.c_str());
    return 0;
}

// AV1: the frames' parameters from the stream's AFGS1 metadata or frame headers, in the AV1
// per-frame form.
int run_extract_av1(const InspectOptions& o, const bitstream::StreamScan& s, std::vector<std::string>& warnings) {
    return write_av1_frames(o, bitstream::av1_params_from_scan(s, warnings), warnings, "frame(s)", "film grain");
}

// H.26x with AFGS1 (T.35 SEI): each output picture's selected set, in the AV1 per-frame form.
// The scanner does not read picture sizes from parameter sets, so the picture the sets are
// selected for is given (--size, --pix-fmt), as `apply` is given it.
int run_extract_afgs1(const InspectOptions& o, const std::vector<std::optional<Afgs1Payload>>& payloads,
                      std::vector<std::string>& warnings, const std::vector<std::string>& afgs1_warnings) {
    if (o.size.empty() || o.pix_fmt.empty())
        throw Error(ErrorCode::kInvalidArgument,
                    "'" + o.stream + "' carries AFGS1 payloads, whose set is selected for the picture's size and "
                    "format: give --size WxH and --pix-fmt (e.g. --size 1920x1080 --pix-fmt yuv420p10le)");
    const PictureSize size = parse_picture_size(o.size, "--size");
    const PixelFormat fmt = parse_pix_fmt(o.pix_fmt);
    warnings.insert(warnings.end(), afgs1_warnings.begin(), afgs1_warnings.end());
    Afgs1Picture pic;
    pic.width = size.width;
    pic.height = size.height;
    pic.format = fmt.chroma;
    pic.bit_depth = fmt.bit_depth;
    std::vector<Av1FrameParams> frames;
    for (const auto& payload : payloads) {
        Av1FrameParams f;
        f.grain.apply_grain = 0;
        if (payload)
            if (const auto sel = select_afgs1_set(*payload, pic)) {
                f.grain = sel->params;
                f.color = av1_color_of(fmt, sel->matrix_coefficients);
            }
        frames.push_back(f);
    }
    return write_av1_frames(o, frames, warnings, "picture(s)", "AFGS1 film grain");
}

int run_extract(const InspectOptions& o) {
    const bitstream::StreamScan s = scan(o);
    std::vector<std::string> warnings;
    for (const auto& u : s.units)
        for (const auto& w : u.warnings) warnings.push_back("unit " + std::to_string(u.index) + ": " + w);
    if (s.codec == bitstream::StreamCodec::kAv1) return run_extract_av1(o, s, warnings);
    const ParamsFile f = bitstream::params_file_from_scan(s, warnings);
    std::vector<std::string> afgs1_warnings;
    const auto afgs1 = bitstream::afgs1_payloads_in_output_order(s, afgs1_warnings);
    if (!afgs1.empty() && !f.has_fgc()) return run_extract_afgs1(o, afgs1, warnings, afgs1_warnings);
    if (!afgs1.empty())
        warnings.push_back("the stream also carries AFGS1 payloads; this file holds its FGC SEI only");
    if (!o.quiet)
        for (const auto& w : warnings) std::fprintf(stderr, "filmgrain: warning: %s\n", w.c_str());
    write_file_atomically(o.output, params_file_to_json(f).dump(1) + "\n");
    int with_sei = 0;
    for (const auto& fr : f.frames) with_sei += fr.fgc.has_value();
    if (!o.quiet && o.output != "-")
        std::fprintf(stderr, "filmgrain: %zu picture(s), %d with an FGC SEI, written to %s\n", f.frames.size(), with_sei,
                     o.output.c_str());
    return 0;
}

void add_stream_options(CLI::App* sub, InspectOptions* o) {
    sub->add_option("stream", o->stream, "coded stream: Annex-B H.264/H.265/H.266, AV1 IVF / OBU / Annex-B")->required();
    sub->add_option("--codec", o->codec, "h264, h265, h266 or av1 (default: from the content and the file name)");
}

}  // namespace

void register_inspect(CLI::App& app) {
    auto o = std::make_shared<InspectOptions>();
    CLI::App* sub = app.add_subcommand("inspect", "list the FGC SEI and ITU-T T.35 payloads of a stream per access unit");
    add_stream_options(sub, o.get());
    sub->add_flag("--json", o->json, "JSON instead of text");
    sub->callback([o]() {
        if (int rc = run_inspect(*o)) throw CLI::RuntimeError(rc);
    });

    auto e = std::make_shared<InspectOptions>();
    // `params` also holds `convert` (cmd_params.cpp): join it when it is there
    CLI::App* params = nullptr;
    for (CLI::App* sub_app : app.get_subcommands([](CLI::App* a) { return a->get_name() == "params"; })) params = sub_app;
    if (!params) {
        params = app.add_subcommand("params", "parameter files");
        params->require_subcommand(1);
    }
    CLI::App* extract = params->add_subcommand(
        "extract",
        "write the per-frame parameter file `apply --params` reads: H.26x FGC SEI in output order with POC, AV1 "
        "film grain (AFGS1 metadata, else frame headers) as per-frame AV1 parameters");
    add_stream_options(extract, e.get());
    extract->add_option("--output,-o", e->output, "parameter file to write, - for stdout")->required();
    extract->add_flag("--quiet,-q", e->quiet, "no messages on stderr except errors");
    extract->add_option("--size", e->size,
                        "H.26x with AFGS1 T.35 SEI: the picture size WxH the AFGS1 sets are selected for");
    extract->add_option("--pix-fmt", e->pix_fmt, "H.26x with AFGS1 T.35 SEI: the picture's pixel format (yuv420p...)");
    extract->callback([e]() {
        if (int rc = run_extract(*e)) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli

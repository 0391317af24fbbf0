// `filmgrain preset`: grain parameters for content that never had grain, from a camera-like
// photon-noise model (ISO, sensor size, transfer function), for either model.
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "filmgrain/error.hpp"
#include "grain_outputs.hpp"

#ifdef FILMGRAIN_HAVE_ANALYSIS
#include "analysis/photon_noise.hpp"
#include "metadata/fgc_sei.hpp"
#endif

namespace filmgrain::cli {

#ifdef FILMGRAIN_HAVE_ANALYSIS
namespace {

struct PresetOptions {
    double iso = 0;
    std::string model, output, table, sei;
    std::string sei_codec = "hevc";
    std::string flavour = "rdd5";
    std::string transfer = "sdr";
    std::string sensor = "36x24";
    bool full_range = false;
    int frames = 1;
    double accuracy = 0.05;
    RawVideoOptions raw;
};

int run_preset(const PresetOptions& o) {
    if (o.model != "fgc" && o.model != "av1")
        throw Error(ErrorCode::kInvalidArgument, "--model '" + o.model + "' is not known (allowed fgc, av1)");
    const bool fgc = o.model == "fgc";
    if (fgc && !o.table.empty()) throw Error(ErrorCode::kInvalidArgument, "--table belongs to --model av1");
    if (!fgc && !o.sei.empty()) throw Error(ErrorCode::kInvalidArgument, "--sei belongs to --model fgc");
    if (o.raw.size.empty()) throw Error(ErrorCode::kInvalidArgument, "--size WxH is required (the sensor is spread over it)");
    if (o.frames < 1 || o.frames > 1000000) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("--frames", o.frames, 1, 1000000));
    const VideoInfo info = o.raw.to_info();
    analysis::CameraModel cam;
    cam.iso = o.iso;
    double sw = 0, sh = 0;
    char x = 0;
    if (std::sscanf(o.sensor.c_str(), "%lf%c%lf", &sw, &x, &sh) != 3 || (x != 'x' && x != 'X'))
        throw Error(ErrorCode::kInvalidArgument, "--sensor-size '" + o.sensor + "' is not WxH in millimetres");
    cam.sensor_width_mm = sw;
    cam.sensor_height_mm = sh;
    cam.width = info.width;
    cam.height = info.height;
    cam.transfer = analysis::parse_transfer_function(o.transfer);
    cam.bit_depth = info.format.bit_depth;
    cam.full_range = o.full_range;
    const FgcFlavour flavour = parse_flavour(o.flavour);
    if (flavour == FgcFlavour::kVfgs) throw Error(ErrorCode::kInvalidArgument, "--flavour vfgs is not supported here (allowed rdd5, vtm)");
    if (fgc) {
        analysis::FgcComponentReport rep;
        const FgcParams p = analysis::photon_noise_fgc(cam, info.format.chroma, flavour, o.accuracy, &rep);
        write_file_atomically(o.output, fgc_params_json_text(p));
        if (!o.sei.empty()) {
            const auto payload = write_fgc_sei_payload(p, parse_fgc_codec(o.sei_codec));
            write_file_atomically(o.sei, std::string(payload.begin(), payload.end()));
        }
        std::fprintf(stderr, "filmgrain preset: ISO %g photon noise, %d interval(s) (RMS error %.1f%%) -> %s\n", o.iso,
                     rep.chosen_order, 100 * rep.error, o.output.c_str());
    } else {
        analysis::Av1ComponentReport rep;
        const Av1FilmGrainParams p = analysis::photon_noise_av1(cam, info.format.chroma, o.accuracy, &rep);
        const auto frames = av1_per_frame(p, o.frames);
        Av1ColorInfo color;
        color.bit_depth = info.format.bit_depth;
        color.mono_chrome = info.format.chroma == ChromaFormat::k400;
        color.subsampling_x = chroma_shift_x(info.format.chroma);
        color.subsampling_y = chroma_shift_y(info.format.chroma);
        write_file_atomically(o.output, av1_params_json_text(frames, color));
        if (!o.table.empty()) write_file_atomically(o.table, av1_grain_table_text(frames, info.fps_num, info.fps_den));
        std::fprintf(stderr, "filmgrain preset: ISO %g photon noise, %zu scaling point(s) (worst error %.1f%%) -> %s\n",
                     o.iso, rep.points.size(), 100 * rep.error, o.output.c_str());
    }
    return 0;
}

}  // namespace

void register_preset(CLI::App& app) {
    auto o = std::make_shared<PresetOptions>();
    CLI::App* sub = app.add_subcommand("preset", "grain parameters from a photon-noise camera model (ISO, sensor, transfer)");
    sub->add_option("--photon-noise", o->iso, "ISO sensitivity of the simulated camera")->required();
    sub->add_option("--model", o->model, "fgc or av1")->required();
    sub->add_option("--output,-o", o->output, "parameter JSON, usable as `filmgrain apply --params`")->required();
    sub->add_option("--table", o->table, "av1: also write a libaom film grain table");
    sub->add_option("--sei", o->sei, "fgc: also write the FGC SEI payload");
    sub->add_option("--sei-codec", o->sei_codec, "fgc: avc, hevc or vvc")->capture_default_str();
    sub->add_option("--flavour", o->flavour, "fgc: rdd5 or vtm (calibrates the scale)")->capture_default_str();
    sub->add_option("--transfer", o->transfer, "sdr (BT.709 gamma), pq or hlg")->capture_default_str();
    sub->add_option("--sensor-size", o->sensor, "sensor WxH in millimetres (36x24 full frame, 23.5x15.6 APS-C, ...)")
        ->capture_default_str();
    sub->add_flag("--full-range", o->full_range, "full-range samples (default limited range)");
    sub->add_option("--frames", o->frames, "av1: pictures to list, each with its own grain_seed")->capture_default_str();
    sub->add_option("--accuracy", o->accuracy, "relative error the smallest model must meet")->capture_default_str();
    o->raw.add_to(sub);
    sub->callback([o]() {
        int rc = run_preset(*o);
        if (rc) throw CLI::RuntimeError(rc);
    });
}

#else

void register_preset(CLI::App& app) {
    CLI::App* sub = app.add_subcommand("preset", "photon-noise presets (unavailable: built without OpenCV)");
    sub->allow_extras();
    sub->callback([]() {
        throw Error(ErrorCode::kUnsupported, "preset needs OpenCV (libopencv-dev); rebuild after tools/install-deps");
    });
}

#endif

}  // namespace filmgrain::cli

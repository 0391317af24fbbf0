#include "cli_common.hpp"

#include "filmgrain/error.hpp"
#include "option_parsing.hpp"

namespace filmgrain::cli {

VideoInfo RawVideoOptions::to_info() const {
    VideoInfo info;
    if (!size.empty()) {
        const PictureSize s = parse_picture_size(size, "--size");
        info.width = s.width;
        info.height = s.height;
    }
    info.format = parse_pix_fmt(pix_fmt);
    const FrameRate r = parse_frame_rate(fps, "--fps");
    info.fps_num = r.num;
    info.fps_den = r.den;
    return info;
}

void parse_arguments(CLI::App& app, const std::vector<std::string>& args) {
    // CLI11 takes the vector from its back
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    try {
        app.parse(reversed);
    } catch (const CLI::RuntimeError&) {
        throw;
    } catch (const CLI::ParseError& e) {
        throw Error(ErrorCode::kInvalidArgument, std::string(e.what()));
    }
}

void RawVideoOptions::add_to(CLI::App* app) {
    app->add_option("--size,-s", size, "raw input size WxH (Y4M input carries its own)");
    app->add_option("--pix-fmt", pix_fmt,
                    "raw input format, FFmpeg names: gray, yuv420p, yuv422p, yuv444p and their 10le/12le/16le forms")
        ->capture_default_str();
    app->add_option("--fps", fps, "raw input frame rate N or N/D (selects libaom grain table entries)")
        ->capture_default_str();
}

FgcFlavour parse_flavour(const std::string& s) {
    if (s == "hm") return FgcFlavour::kVtm;
    for (FgcFlavour f : {FgcFlavour::kRdd5, FgcFlavour::kFfmpeg, FgcFlavour::kVtm, FgcFlavour::kVfgs, FgcFlavour::kTr})
        if (s == fgc_flavour_name(f)) return f;
    throw Error(ErrorCode::kInvalidArgument, "--flavour '" + s + "' is not known (allowed rdd5, ffmpeg, vtm, vfgs, tr)");
}

Av1ColorInfo av1_color_of(const PixelFormat& format, int matrix_coefficients) {
    Av1ColorInfo c;
    c.bit_depth = format.bit_depth;
    c.mono_chrome = format.chroma == ChromaFormat::k400;
    c.subsampling_x = chroma_shift_x(format.chroma);
    c.subsampling_y = chroma_shift_y(format.chroma);
    c.matrix_coefficients = matrix_coefficients;
    return c;
}

}  // namespace filmgrain::cli

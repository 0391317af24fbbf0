#include "cli_common.hpp"

#include "filmgrain/error.hpp"

namespace filmgrain::cli {

VideoInfo RawVideoOptions::to_info() const {
    VideoInfo info;
    if (!size.empty()) {
        int w = 0, h = 0;
        char x = 0;
        if (std::sscanf(size.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w <= 0 || h <= 0 ||
            w > 65536 || h > 65536)
            throw Error(ErrorCode::kInvalidArgument, "--size '" + size + "' is not WxH with 1..65536 in each dimension");
        info.width = w;
        info.height = h;
    }
    info.format = parse_pix_fmt(pix_fmt);
    int n = 0, d = 1;
    if (std::sscanf(fps.c_str(), "%d/%d", &n, &d) < 1 || n <= 0 || d <= 0)
        throw Error(ErrorCode::kInvalidArgument, "--fps '" + fps + "' is not N or N/D with positive integers");
    info.fps_num = n;
    info.fps_den = d;
    return info;
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
    if (s == "rdd5") return FgcFlavour::kRdd5;
    if (s == "vtm" || s == "hm") return FgcFlavour::kVtm;
    if (s == "vfgs") return FgcFlavour::kVfgs;
    if (s == "tr") return FgcFlavour::kTr;
    throw Error(ErrorCode::kInvalidArgument, "--flavour '" + s + "' is not known (allowed rdd5, vtm, vfgs, tr)");
}

std::string flavour_name(FgcFlavour f) {
    switch (f) {
        case FgcFlavour::kRdd5: return "rdd5";
        case FgcFlavour::kVtm: return "vtm";
        case FgcFlavour::kVfgs: return "vfgs";
        case FgcFlavour::kTr: return "tr";
    }
    return "?";
}

}  // namespace filmgrain::cli

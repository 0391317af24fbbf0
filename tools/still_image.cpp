#include "still_image.hpp"

#include <algorithm>
#include <filesystem>

#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

#ifdef FILMGRAIN_HAVE_OIIO
#include <OpenImageIO/imageio.h>
#endif

namespace filmgrain::cli {

bool is_video_path(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    return path == "-" || ext == ".y4m" || ext == ".yuv" || ext == ".Y4M" || ext == ".YUV";
}

#ifndef FILMGRAIN_HAVE_OIIO
bool have_still_image_support() { return false; }
StillImage read_still_image(const std::string& path) {
    throw Error(ErrorCode::kUnsupported, "cannot read " + path + ": this build has no OpenImageIO (stills)");
}
void write_still_image(const std::string& path, const StillImage&) {
    throw Error(ErrorCode::kUnsupported, "cannot write " + path + ": this build has no OpenImageIO (stills)");
}
#else
bool have_still_image_support() { return true; }

StillImage read_still_image(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error(ErrorCode::kIo, "cannot read " + path + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    StillImage img;
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) throw Error(ErrorCode::kIo, path + ": empty picture");
    img.format = spec.format.c_str();
    img.floating = spec.format.is_floating_point();
    img.alpha_channel = spec.alpha_channel;
    img.channel_names = spec.channelnames;
    std::vector<float> px(std::size_t(w) * h * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data()))
        throw Error(ErrorCode::kIo, "cannot read " + path + ": " + in->geterror());
    in->close();
    img.channels.assign(nc, FloatPlane(w, h));
    for (std::size_t i = 0; i < std::size_t(w) * h; i++)
        for (int c = 0; c < nc; c++) img.channels[c].v[i] = px[i * nc + c];
    return img;
}

void write_still_image(const std::string& path, const StillImage& img) {
    const int nc = int(img.channels.size());
    const int w = img.channels[0].width, h = img.channels[0].height;
    OIIO::TypeDesc type(img.format);
    OIIO::ImageSpec spec(w, h, nc, type);
    spec.alpha_channel = img.alpha_channel;
    if (int(img.channel_names.size()) == nc) spec.channelnames = img.channel_names;
    std::vector<float> px(std::size_t(w) * h * nc);
    for (std::size_t i = 0; i < std::size_t(w) * h; i++)
        for (int c = 0; c < nc; c++) {
            const float v = img.channels[c].v[i];
            px[i * nc + c] = img.floating ? v : std::clamp(v, 0.f, 1.f);
        }
    OutputFile file(path);  // its temporary keeps the extension, by which OpenImageIO picks the format
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw Error(ErrorCode::kIo, "cannot write " + path + ": " + OIIO::geterror());
    if (!out->open(file.write_path(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) || !out->close())
        throw Error(ErrorCode::kIo, "cannot write " + path + ": " + out->geterror());
    file.commit();
}
#endif

}  // namespace filmgrain::cli

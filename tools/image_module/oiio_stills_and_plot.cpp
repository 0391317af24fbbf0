// filmgrain-oiio.so: the tool's stills (read and written) and the tradeoff plot (drawn and
// written) through OpenImageIO; image_module.hpp says why this is a module of its own.
// Nothing here throws across the module boundary.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "image_module.hpp"

namespace filmgrain::cli {
namespace {

std::string read_image(const std::string& path, StillImage& img) try {
    auto in = OIIO::ImageInput::open(path);
    if (!in) return "cannot read " + path + ": " + OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    if (w <= 0 || h <= 0 || nc <= 0) return path + ": empty picture";
    img = StillImage{};
    img.format = spec.format.c_str();
    img.floating = spec.format.is_floating_point();
    img.alpha_channel = spec.alpha_channel;
    img.channel_names = spec.channelnames;
    std::vector<float> px(std::size_t(w) * h * nc);
    if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data()))
        return "cannot read " + path + ": " + in->geterror();
    in->close();
    img.channels.assign(nc, FloatPlane(w, h));
    for (std::size_t i = 0; i < std::size_t(w) * h; i++)
        for (int c = 0; c < nc; c++) img.channels[c].v[i] = px[i * nc + c];
    return {};
} catch (const std::exception& e) {
    return "cannot read " + path + ": " + e.what();
}

std::string write_image(const std::string& write_path, const std::string& format, const StillImage& img) try {
    const int nc = int(img.channels.size());
    if (nc == 0) return "no channels to write";
    const int w = img.channels[0].width, h = img.channels[0].height;
    OIIO::ImageSpec spec(w, h, nc, OIIO::TypeDesc(img.format));
    spec.alpha_channel = img.alpha_channel;
    if (int(img.channel_names.size()) == nc) spec.channelnames = img.channel_names;
    std::vector<float> px(std::size_t(w) * h * nc);
    for (std::size_t i = 0; i < std::size_t(w) * h; i++)
        for (int c = 0; c < nc; c++) {
            const float v = img.channels[c].v[i];
            px[i * nc + c] = img.floating ? v : std::clamp(v, 0.f, 1.f);
        }
    // created by the format's name: a temporary's or a device's own name may not say it
    auto out = OIIO::ImageOutput::create(format.empty() ? write_path : format);
    if (!out) return "no image format '" + format + "': " + OIIO::geterror();
    if (!out->open(write_path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, px.data()) || !out->close())
        return out->geterror();
    return {};
} catch (const std::exception& e) {
    return e.what();
}

const char* font_path() {
    for (const char* f : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"})
        if (std::filesystem::exists(f)) return f;
    return "";
}

std::string write_plot(const std::string& write_path, const std::string& format,
                       const std::vector<PlotPoint>& points) try {
    constexpr int kW = 960, kH = 600, kLeft = 90, kRight = 30, kTop = 40, kBottom = 70;
    if (points.empty()) return "no points";
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const auto& p : points) {
        x0 = std::min(x0, std::log10(std::max(p.throughput, 1e-6)));
        x1 = std::max(x1, std::log10(std::max(p.throughput, 1e-6)));
        y0 = std::min(y0, std::log10(std::max(p.error, 1e-6)));
        y1 = std::max(y1, std::log10(std::max(p.error, 1e-6)));
    }
    x0 = std::floor(x0);
    x1 = std::ceil(x1 + 1e-9);
    y0 = std::floor(y0);
    y1 = std::ceil(y1 + 1e-9);
    OIIO::ImageBuf img(OIIO::ImageSpec(kW, kH, 3, OIIO::TypeDesc::UINT8));
    const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, grid[3] = {0.85f, 0.85f, 0.85f};
    OIIO::ImageBufAlgo::fill(img, OIIO::cspan<float>(white, 3));
    auto px = [&](double lx) { return int(kLeft + (lx - x0) / (x1 - x0) * (kW - kLeft - kRight)); };
    auto py = [&](double ly) { return int(kH - kBottom - (ly - y0) / (y1 - y0) * (kH - kTop - kBottom)); };
    const std::string font = font_path();
    auto text = [&](int x, int y, const std::string& s, int size, const float* colour) {
        if (!font.empty()) OIIO::ImageBufAlgo::render_text(img, x, y, s, size, font, OIIO::cspan<float>(colour, 3));
    };
    for (double d = x0; d <= x1 + 1e-9; d += 1) {
        OIIO::ImageBufAlgo::render_line(img, px(d), py(y0), px(d), py(y1), OIIO::cspan<float>(grid, 3));
        char b[32];
        std::snprintf(b, sizeof b, "%g", std::pow(10.0, d));
        text(px(d) - 12, kH - kBottom + 22, b, 16, black);
    }
    for (double d = y0; d <= y1 + 1e-9; d += 1) {
        OIIO::ImageBufAlgo::render_line(img, px(x0), py(d), px(x1), py(d), OIIO::cspan<float>(grid, 3));
        char b[32];
        std::snprintf(b, sizeof b, "%g", std::pow(10.0, d));
        text(10, py(d) + 5, b, 16, black);
    }
    OIIO::ImageBufAlgo::render_line(img, px(x0), py(y0), px(x1), py(y0), OIIO::cspan<float>(black, 3));
    OIIO::ImageBufAlgo::render_line(img, px(x0), py(y0), px(x0), py(y1), OIIO::cspan<float>(black, 3));
    text(kW / 2 - 160, kH - 20, "throughput, Mpixel/s (log)", 18, black);
    text(kLeft, 25, "error of the second-order statistics vs the Boolean model's closed form (log)", 16, black);
    const float palette[][3] = {{0.85f, 0.1f, 0.1f}, {0.1f, 0.4f, 0.85f}, {0.1f, 0.6f, 0.2f}, {0.6f, 0.2f, 0.7f},
                                {0.9f, 0.5f, 0.0f}, {0.3f, 0.3f, 0.3f}};
    for (std::size_t i = 0; i < points.size(); i++) {
        const auto& p = points[i];
        const int cx = px(std::log10(std::max(p.throughput, 1e-6))), cy = py(std::log10(std::max(p.error, 1e-6)));
        const float* c = palette[i % 6];
        OIIO::ImageBufAlgo::render_box(img, cx - 5, cy - 5, cx + 5, cy + 5, OIIO::cspan<float>(c, 3), true);
        text(cx + 9, cy - 6 + int(i % 2) * 14, p.label, 14, c);
    }
    if (!img.write(write_path, OIIO::TypeUnknown, format)) return img.geterror();
    return {};
} catch (const std::exception& e) {
    return e.what();
}

constexpr ImageModule kModule{kImageModuleVersion, read_image, write_image, write_plot};

}  // namespace
}  // namespace filmgrain::cli

extern "C" __attribute__((visibility("default"))) const filmgrain::cli::ImageModule* filmgrain_image_module(int version) {
    return version == filmgrain::cli::kImageModuleVersion ? &filmgrain::cli::kModule : nullptr;
}

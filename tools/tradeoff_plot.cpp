#include "tradeoff_plot.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#ifdef FILMGRAIN_HAVE_OIIO
#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#endif

namespace filmgrain::cli {

#ifndef FILMGRAIN_HAVE_OIIO
bool write_tradeoff_plot(const std::string&, const std::vector<PlotPoint>&, std::string* why) {
    if (why) *why = "this build has no OpenImageIO";
    return false;
}
#else
namespace {
constexpr int kW = 960, kH = 600, kLeft = 90, kRight = 30, kTop = 40, kBottom = 70;

const char* font_path() {
    for (const char* f : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf"})
        if (std::filesystem::exists(f)) return f;
    return "";
}
}  // namespace

bool write_tradeoff_plot(const std::string& path, const std::vector<PlotPoint>& points, std::string* why) {
    if (points.empty()) {
        if (why) *why = "no points";
        return false;
    }
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
    OutputFile file(path);
    std::string format = std::filesystem::path(path).extension().string();  // the target's own,
    if (!format.empty()) format.erase(0, 1);                                  // which a device lacks
    if (!img.write(file.write_path(), OIIO::TypeUnknown, format)) {
        if (why) *why = img.geterror();
        return false;
    }
    try {
        file.commit();
    } catch (const Error& e) {
        if (why) *why = e.what();
        return false;
    }
    return true;
}
#endif

}  // namespace filmgrain::cli

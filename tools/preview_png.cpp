// PNG preview of a clean/grainy pair through OpenImageIO: the centre crop of both frames
// converted to RGB (BT.709, limited range) and enlarged 2x so the grain is visible.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cli_common.hpp"

#ifdef FILMGRAIN_HAVE_OIIO
#include <OpenImageIO/imageio.h>
#endif

namespace filmgrain::cli {

namespace {
double sample01(const FrameBuffer& f, int c, int x, int y) {
    FrameView v = const_cast<FrameBuffer&>(f).view();
    const int sx = c ? chroma_shift_x(v.format) : 0, sy = c ? chroma_shift_y(v.format) : 0;
    if (v.format == ChromaFormat::k400 && c) return 0.5;
    const PlaneView& p = v.planes[c];
    const int px = std::min(x >> sx, p.width - 1), py = std::min(y >> sy, p.height - 1);
    const double maxv = double((1 << v.bit_depth) - 1);
    const double s = v.bit_depth > 8 ? p.row<const uint16_t>(py)[px] : p.row<const uint8_t>(py)[px];
    return s / maxv;
}
}  // namespace

bool write_preview_png(const std::string& path, const FrameBuffer& clean, const FrameBuffer& grainy, std::string* why) {
#ifndef FILMGRAIN_HAVE_OIIO
    (void)path; (void)clean; (void)grainy;
    if (why) *why = "this build has no OpenImageIO";
    return false;
#else
    const int cw = std::min(clean.width(), 256), ch = std::min(clean.height(), 192), zoom = 2;
    const int x0 = (clean.width() - cw) / 2, y0 = (clean.height() - ch) / 2;
    const int gap = 8, W = (2 * cw * zoom) + gap, H = ch * zoom;
    std::vector<uint8_t> rgb(std::size_t(W) * H * 3, 255);
    for (int side = 0; side < 2; side++) {
        const FrameBuffer& f = side ? grainy : clean;
        for (int y = 0; y < ch; y++)
            for (int x = 0; x < cw; x++) {
                const double Y = (sample01(f, 0, x0 + x, y0 + y) * 255 - 16) / 219.0;
                const double U = (sample01(f, 1, x0 + x, y0 + y) * 255 - 128) / 224.0;
                const double V = (sample01(f, 2, x0 + x, y0 + y) * 255 - 128) / 224.0;
                const double r = Y + 1.5748 * V, g = Y - 0.1873 * U - 0.4681 * V, b = Y + 1.8556 * U;
                const uint8_t px[3] = {uint8_t(std::clamp(std::lround(r * 255), 0L, 255L)),
                                       uint8_t(std::clamp(std::lround(g * 255), 0L, 255L)),
                                       uint8_t(std::clamp(std::lround(b * 255), 0L, 255L))};
                for (int dy = 0; dy < zoom; dy++)
                    for (int dx = 0; dx < zoom; dx++) {
                        const int ox = side * (cw * zoom + gap) + x * zoom + dx, oy = y * zoom + dy;
                        std::copy(px, px + 3, &rgb[(std::size_t(oy) * W + ox) * 3]);
                    }
            }
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        if (why) *why = "OpenImageIO cannot write " + path;
        return false;
    }
    OIIO::ImageSpec spec(W, H, 3, OIIO::TypeDesc::UINT8);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !out->close()) {
        if (why) *why = out->geterror();
        return false;
    }
    return true;
#endif
}

}  // namespace filmgrain::cli

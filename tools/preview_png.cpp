// PNG preview of a clean/grainy pair (a still through the image module): the centre crop of
// both frames converted to RGB (BT.709, limited range) and enlarged 2x so the grain is visible.
#include <algorithm>
#include <cmath>
#include <vector>

#include "cli_common.hpp"
#include "filmgrain/error.hpp"
#include "still_image.hpp"

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
    const int cw = std::min(clean.width(), 256), ch = std::min(clean.height(), 192), zoom = 2;
    const int x0 = (clean.width() - cw) / 2, y0 = (clean.height() - ch) / 2;
    const int gap = 8, W = (2 * cw * zoom) + gap, H = ch * zoom;
    StillImage img;
    img.channels.assign(3, FloatPlane(W, H, 1.f));
    img.channel_names = {"R", "G", "B"};
    img.format = "uint8";
    for (int side = 0; side < 2; side++) {
        const FrameBuffer& f = side ? grainy : clean;
        for (int y = 0; y < ch; y++)
            for (int x = 0; x < cw; x++) {
                const double Y = (sample01(f, 0, x0 + x, y0 + y) * 255 - 16) / 219.0;
                const double U = (sample01(f, 1, x0 + x, y0 + y) * 255 - 128) / 224.0;
                const double V = (sample01(f, 2, x0 + x, y0 + y) * 255 - 128) / 224.0;
                const double rgb[3] = {Y + 1.5748 * V, Y - 0.1873 * U - 0.4681 * V, Y + 1.8556 * U};
                for (int c = 0; c < 3; c++) {
                    // 8-bit steps, as the PNG will hold them
                    const float v = float(std::clamp(std::lround(rgb[c] * 255), 0L, 255L)) / 255.f;
                    for (int dy = 0; dy < zoom; dy++)
                        for (int dx = 0; dx < zoom; dx++)
                            img.channels[c].at(side * (cw * zoom + gap) + x * zoom + dx, y * zoom + dy) = v;
                }
            }
    }
    try {
        write_still_image(path, img);
        return true;
    } catch (const Error& e) {
        if (why) *why = e.what();
        return false;
    }
}

}  // namespace filmgrain::cli

#include "synthetic_content.hpp"

#include <cmath>

namespace filmgrain::analysis_test {

FrameBuffer make_clean_picture(int width, int height, PixelFormat fmt, int lo, int hi) {
    FrameBuffer fb(width, height, fmt);
    FrameView v = fb.view();
    const int scale = 1 << (fmt.bit_depth - 8);
    for (int p = 0; p < v.plane_count(); p++) {
        const PlaneView& pv = v.planes[p];
        for (int y = 0; y < pv.height; y++)
            for (int x = 0; x < pv.width; x++) {
                const double u = double(x) / pv.width, w = double(y) / pv.height;
                double level;
                if (p == 0) {
                    // Patches of constant intensity in a grid, stepping through the range.
                    // Patches of 128x128 luma samples (at 384x256: 3x2), large enough for 64x64 DCT blocks.
                    const int cols = std::max(1, pv.width / 128), rows = std::max(1, pv.height / 128);
                    const int cx = std::min(cols - 1, int(u * cols)), cy = std::min(rows - 1, int(w * rows));
                    const double t = (cy * cols + cx) / double(cols * rows - 1);
                    level = lo + (hi - lo) * (0.85 * t + 0.15 * (0.5 * u + 0.5 * w));
                } else {
                    level = (p == 1 ? 64 + 128 * u : 64 + 128 * w);
                }
                const int val = int(std::lround(level * scale));
                if (fmt.bit_depth > 8)
                    pv.row<uint16_t>(y)[x] = uint16_t(val);
                else
                    pv.row<uint8_t>(y)[x] = uint8_t(val);
            }
    }
    return fb;
}

double grain_std_in_band(const FrameBuffer& grainy_c, const FrameBuffer& clean_c, int plane, int band_lo, int band_hi) {
    FrameBuffer& grainy = const_cast<FrameBuffer&>(grainy_c);
    FrameBuffer& clean = const_cast<FrameBuffer&>(clean_c);
    const FrameView g = grainy.view(), c = clean.view();
    const int shift = g.bit_depth - 8;
    double s = 0, ss = 0;
    long long n = 0;
    for (int y = 0; y < g.planes[plane].height; y++)
        for (int x = 0; x < g.planes[plane].width; x++) {
            int gv, cv;
            if (g.bit_depth > 8) {
                gv = g.planes[plane].row<uint16_t>(y)[x];
                cv = c.planes[plane].row<uint16_t>(y)[x];
            } else {
                gv = g.planes[plane].row<uint8_t>(y)[x];
                cv = c.planes[plane].row<uint8_t>(y)[x];
            }
            const int i8 = cv >> shift;
            if (i8 < band_lo || i8 > band_hi) continue;
            const double d = gv - cv;
            s += d;
            ss += d * d;
            n++;
        }
    if (n < 2) return 0.0;
    const double m = s / n;
    return std::sqrt(std::max(0.0, ss / n - m * m));
}

}  // namespace filmgrain::analysis_test

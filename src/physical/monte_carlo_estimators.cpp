#include "physical/monte_carlo_estimators.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain::physical {

namespace {
constexpr double kStripInputPixels = 8;
}  // namespace

void estimate_pixel_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out) {
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    out.value.assign(std::size_t(w) * h, 0.f);
    out.samples_total = 0;
    out.samples_min = s.count;
    out.samples_max = 0;
    const double* xi = s.offsets->data();
    const double tol2 = s.tolerance * s.tolerance;
    constexpr int kCheckEvery = 16;
    // Pixels are visited in strips a few pixels wide: the bins one pixel's samples read (a
    // disc a few filter sigmas wide) are nearly those of the pixel above, so a narrow strip
    // keeps them in L2 cache from one row to the next, where a full tile row would not.
    const int strip = std::max(1, int(std::lround(kStripInputPixels * s.zoom)));
    for (int sx0 = rect.x0; sx0 < rect.x1; sx0 += strip)
    for (int y = rect.y0; y < rect.y1; y++) {
        const double cy = output_to_input(y, s.zoom);
        for (int x = sx0; x < std::min(rect.x1, sx0 + strip); x++) {
            const double cx = output_to_input(x, s.zoom);
            int hits = 0, n = 0;
            if (s.tolerance > 0) {
                while (n < s.count) {
                    const int stop = std::min(s.count, n + kCheckEvery);
                    for (; n < stop; n++) hits += field.covered(cx + xi[2 * n], cy + xi[2 * n + 1]);
                    if (n >= s.min_samples) {
                        const double pt = (hits + 1.0) / (n + 2.0);
                        if (pt * (1 - pt) <= tol2 * n) break;
                    }
                }
            } else {
                for (; n < s.count; n++) hits += field.covered(cx + xi[2 * n], cy + xi[2 * n + 1]);
            }
            out.value[std::size_t(y - rect.y0) * w + (x - rect.x0)] = float(double(hits) / n);
            out.samples_total += n;
            out.samples_min = std::min(out.samples_min, n);
            out.samples_max = std::max(out.samples_max, n);
        }
    }
}

void estimate_grain_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out) {
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    std::vector<int> count(std::size_t(w) * h, 0), stamp(std::size_t(w) * h, -1);
    const std::vector<Grain>& grains = field.grains();
    std::vector<double> radius(grains.size());
    for (std::size_t i = 0; i < grains.size(); i++) radius[i] = std::sqrt(grains[i].r2);
    const double z = s.zoom;
    const double kc = field.cells_per_pixel();
    for (int k = 0; k < s.count; k++) {
        const double ox = (*s.offsets)[2 * k], oy = (*s.offsets)[2 * k + 1];
        for (std::size_t gi = 0; gi < grains.size(); gi++) {
            const Grain& g = grains[gi];
            const double r = radius[gi];
            // Pixel range from the bounding box, widened by one: the exact test decides.
            const int jx0 = std::max(rect.x0, int(std::ceil((g.x - r - ox) * z - 0.5)) - 1);
            const int jx1 = std::min(rect.x1 - 1, int(std::floor((g.x + r - ox) * z - 0.5)) + 1);
            if (jx0 > jx1) continue;
            const int jy0 = std::max(rect.y0, int(std::ceil((g.y - r - oy) * z - 0.5)) - 1);
            const int jy1 = std::min(rect.y1 - 1, int(std::floor((g.y + r - oy) * z - 0.5)) + 1);
            const float r2k = r2_in_bins(g.r2, kc);
            const double gxs = g.x * kc, gys = g.y * kc;
            for (int y = jy0; y <= jy1; y++) {
                const double sy = (output_to_input(y, z) + oy) * kc;
                const int64_t by = floor_to_int(sy);
                const float ly = bin_local(sy, by), gy = bin_local(gys, by);
                for (int x = jx0; x <= jx1; x++) {
                    const double sx = (output_to_input(x, z) + ox) * kc;
                    const int64_t bx = floor_to_int(sx);
                    if (inside_grain(bin_local(sx, bx), ly, bin_local(gxs, bx), gy, r2k)) {
                        const std::size_t i = std::size_t(y - rect.y0) * w + (x - rect.x0);
                        if (stamp[i] != k) {
                            stamp[i] = k;
                            count[i]++;
                        }
                    }
                }
            }
        }
    }
    out.value.resize(count.size());
    for (std::size_t i = 0; i < count.size(); i++) out.value[i] = float(double(count[i]) / s.count);
    out.samples_total = (long long)s.count * w * h;
    out.samples_min = out.samples_max = s.count;
}

}  // namespace filmgrain::physical

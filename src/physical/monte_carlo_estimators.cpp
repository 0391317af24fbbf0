#include "physical/monte_carlo_estimators.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain::physical {

namespace {
constexpr double kStripInputPixels = 8;

void start_estimate(const TileRect& rect, int count, TileEstimate& out) {
    out.value.assign(std::size_t(rect.x1 - rect.x0) * (rect.y1 - rect.y0), 0.f);
    out.samples_total = 0;
    out.samples_min = count;
    out.samples_max = 0;
}
}  // namespace

InputRect sample_reach(const SamplePoints& points, const TileRect& rect, double zoom) {
    if (points.unit_zoom()) {
        const StepExtent& s = points.step_extent();
        const int64_t kc = points.cells_per_pixel();
        const double k = double(kc);
        return {double(kc * rect.x0 + s.x0) / k, double(kc * rect.y0 + s.y0) / k,
                double(kc * (rect.x1 - 1) + s.x1 + 1) / k, double(kc * (rect.y1 - 1) + s.y1 + 1) / k};
    }
    const OffsetExtent& e = points.offset_extent();
    return {output_to_input(rect.x0, zoom) + e.x0, output_to_input(rect.y0, zoom) + e.y0,
            output_to_input(rect.x1 - 1, zoom) + e.x1, output_to_input(rect.y1 - 1, zoom) + e.y1};
}

void estimate_pixel_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out) {
    const SamplePoints& pts = *s.points;
    const int count = pts.count();
    start_estimate(rect, count, out);
    const int w = rect.x1 - rect.x0;
    const double tol2 = s.tolerance * s.tolerance;
    constexpr int kCheckEvery = 16;
    // Pixels are visited in strips a few pixels wide: the bins one pixel's samples read (a
    // disc a few filter sigmas wide) are nearly those of the pixel above, so a narrow strip
    // keeps them in L2 cache from one row to the next, where a full tile row would not.
    const int strip = std::max(1, int(std::lround(kStripInputPixels * pts.zoom())));
    for (int sx0 = rect.x0; sx0 < rect.x1; sx0 += strip)
        for (int y = rect.y0; y < rect.y1; y++) {
            for (int x = sx0; x < std::min(rect.x1, sx0 + strip); x++) {
                auto hit = [&](int i) {
                    const BinPoint bx = pts.x(x, i), by = pts.y(y, i);
                    return field.covered_in_bin(bx.bin, by.bin, bx.local, by.local);
                };
                int hits = 0, n = 0;
                if (s.tolerance > 0) {
                    while (n < count) {
                        const int stop = std::min(count, n + kCheckEvery);
                        for (; n < stop; n++) hits += hit(n);
                        if (n >= s.min_samples) {
                            const double pt = (hits + 1.0) / (n + 2.0);
                            if (pt * (1 - pt) <= tol2 * n) break;
                        }
                    }
                } else {
                    for (; n < count; n++) hits += hit(n);
                }
                out.value[std::size_t(y - rect.y0) * w + (x - rect.x0)] = float(double(hits) / n);
                out.samples_total += n;
                out.samples_min = std::min(out.samples_min, n);
                out.samples_max = std::max(out.samples_max, n);
            }
        }
}

void estimate_pixel_wise_by_masks(const BinGrid& grid, const TileRect& rect, const SampleSchedule& s,
                                  TileEstimate& out) {
    const SamplePoints& pts = *s.points;
    const SampleClasses& cls = *s.classes;
    const int count = pts.count();
    start_estimate(rect, count, out);
    const int64_t kc = pts.cells_per_pixel(), nbx = grid.nbx, words = cls.words;
    // Sample i of the pixel whose own bin is b reads word b * words + word_at[i], bit bit_at[i].
    std::vector<int64_t> word_at(static_cast<std::size_t>(count));
    for (int i = 0; i < count; i++)
        word_at[std::size_t(i)] = (pts.steps_y()[std::size_t(i)].bin * nbx + pts.steps_x()[std::size_t(i)].bin) * words +
                                  cls.sample_word[std::size_t(i)];
    const uint8_t* bit_at = cls.sample_bit.data();
    const MaskWord* masks = out.masks.data();
    const int w = rect.x1 - rect.x0;
    for (int y = rect.y0; y < rect.y1; y++) {
        const int64_t row = (kc * y - grid.by0) * nbx;
        for (int x = rect.x0; x < rect.x1; x++) {
            const MaskWord* base = masks + (row + kc * x - grid.bx0) * words;
            int hits = 0;
            for (int i = 0; i < count; i++) hits += int((base[word_at[std::size_t(i)]] >> bit_at[i]) & 1u);
            out.value[std::size_t(y - rect.y0) * w + (x - rect.x0)] = float(double(hits) / count);
        }
    }
    out.samples_total = (long long)count * w * (rect.y1 - rect.y0);
    out.samples_min = out.samples_max = count;
}

void estimate_grain_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out) {
    const SamplePoints& pts = *s.points;
    const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
    std::vector<int> count(std::size_t(w) * h, 0), stamp(std::size_t(w) * h, -1);
    const std::vector<Grain>& grains = field.grains();
    std::vector<double> radius(grains.size());
    for (std::size_t i = 0; i < grains.size(); i++) radius[i] = std::sqrt(grains[i].r2);
    const double z = pts.zoom();
    const double kc = field.cells_per_pixel();
    std::vector<BinPoint> column(static_cast<std::size_t>(w));
    for (int k = 0; k < pts.count(); k++) {
        const double ox = pts.offset_x(k), oy = pts.offset_y(k);
        for (int x = rect.x0; x < rect.x1; x++) column[std::size_t(x - rect.x0)] = pts.x(x, k);
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
                const BinPoint py = pts.y(y, k);
                const float gy = bin_local(gys, py.bin);
                for (int x = jx0; x <= jx1; x++) {
                    const BinPoint px = column[std::size_t(x - rect.x0)];
                    if (inside_grain(px.local, py.local, bin_local(gxs, px.bin), gy, r2k)) {
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
    for (std::size_t i = 0; i < count.size(); i++) out.value[i] = float(double(count[i]) / pts.count());
    out.samples_total = (long long)pts.count() * w * h;
    out.samples_min = out.samples_max = pts.count();
}

}  // namespace filmgrain::physical

// Tiles, threads and the choice of algorithm for the Boolean-model renderer. Tiles are
// fixed by the parameters (never by the thread count) and every value depends only on
// global coordinates, so the output is the same however the work is split.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <thread>

#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"
#include "physical/boolean_model.hpp"
#include "physical/cell_random.hpp"
#include "physical/coverage_masks.hpp"
#include "physical/grain_field.hpp"
#include "physical/monte_carlo_estimators.hpp"
#include "physical/monte_carlo_offsets.hpp"
#include "physical/sample_points.hpp"

namespace filmgrain::physical {

namespace {

void check_range(const char* field, double v, double lo, double hi, bool lo_open = false) {
    const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi;
    if (ok) return;
    std::ostringstream s;
    s << "physical model: " << field << " = " << v << ", allowed range " << (lo_open ? "(" : "[") << lo << ", " << hi
      << "]";
    throw Error(ErrorCode::kInvalidParams, s.str());
}

// Largest expected grain count per input pixel (at grey level 1 - epsilon) the renderer
// accepts: beyond it one picture would hold billions of grains.
constexpr double kMaxGrainsPerPixel = 2e5;
// Bins (and cells) one tile may hold, which bounds a thread's memory.
constexpr double kMaxBinsPerTile = 4e6;
// Bytes of coverage masks one tile may hold (the unit-zoom estimator): they are read once
// per sample of every pixel, so they should stay near the L2 cache.
constexpr double kMaxMaskBytesPerTile = 8e6;

int cells_per_pixel_for(const GrainRadiusLaw& law) {
    // Cells about one typical grain diameter wide: a bin then lists a few grains.
    const double k = std::round(1.0 / (2.0 * std::sqrt(law.mean_square())));
    return int(std::clamp(k, 1.0, 256.0));
}

// Grains are drawn per cell: a hash and a Poisson draw each. Cells three bins wide hold about
// nine grains at mid grey (one per cell when cells were bins), so that cost is spread over the
// grains, and the darkest allowed grey still asks the Poisson inversion for a mean near 80,
// whose exp(-mean) a double holds.
int generation_cells_per_pixel(int bins_per_pixel) { return std::max(1, (bins_per_pixel + 1) / 3); }

void sort_offsets_by_bin(std::vector<double>& xi, int k) {
    const std::size_t n = xi.size() / 2;
    std::vector<std::pair<std::pair<int64_t, int64_t>, std::size_t>> key(n);
    for (std::size_t i = 0; i < n; i++) {
        const int64_t by = int64_t(std::floor(xi[2 * i + 1] * k)), bx = int64_t(std::floor(xi[2 * i] * k));
        key[i] = {{by, (by & 1) ? -bx : bx}, i};  // boustrophedon rows
    }
    std::sort(key.begin(), key.end());
    std::vector<double> sorted(xi.size());
    for (std::size_t i = 0; i < n; i++) {
        sorted[2 * i] = xi[2 * key[i].second];
        sorted[2 * i + 1] = xi[2 * key[i].second + 1];
    }
    xi.swap(sorted);
}

}  // namespace

const char* algorithm_name(BooleanAlgorithm a) {
    switch (a) {
        case BooleanAlgorithm::kPixelWise: return "pixel-wise";
        case BooleanAlgorithm::kGrainWise: return "grain-wise";
        default: return "auto";
    }
}

int zoomed_size(int input_size, double zoom) { return std::max(1, int(std::floor(input_size * zoom + 1e-9))); }

void validate(const BooleanModelParams& p) {
    check_range("radius_mean", p.radius_mean, 0, 256, true);
    check_range("radius_sigma", p.radius_sigma, 0, 100 * p.radius_mean);
    check_range("filter_sigma", p.filter_sigma, 0, 64);
    check_range("zoom", p.zoom, 1.0 / 64, 64);
    check_range("samples", p.samples, 1, 1e6);
    check_range("tolerance", p.tolerance, 0, 0.5);
    check_range("min_samples", p.min_samples, 1, 1e6);
    check_range("max_samples", p.max_samples, p.min_samples, 1e6);
    check_range("grey_epsilon", p.grey_epsilon, 1e-9, 0.5);
    check_range("threads", p.threads, 1, kMaxThreads);
    const GrainRadiusLaw law(p.radius_mean, p.radius_sigma);
    const double grains = std::log(1.0 / p.grey_epsilon) / (3.141592653589793 * law.mean_square());
    if (grains > kMaxGrainsPerPixel) {
        std::ostringstream s;
        s << "physical model: radius_mean = " << p.radius_mean << " (radius_sigma " << p.radius_sigma << ") gives "
          << grains << " grains per input pixel at full scale, allowed at most " << kMaxGrainsPerPixel
          << " (radius_mean >= about " << std::sqrt(std::log(1.0 / p.grey_epsilon) / (3.141592653589793 * kMaxGrainsPerPixel))
          << " for a constant radius)";
        throw Error(ErrorCode::kInvalidParams, s.str());
    }
}

RenderReport render_boolean_model(const FloatPlane& u, const BooleanModelParams& p, const OutputRegion& region_in,
                                  uint64_t plane_seed, FloatPlane& out) {
    validate(p);
    if (u.width <= 0 || u.height <= 0 || u.v.size() != std::size_t(u.width) * u.height)
        throw Error(ErrorCode::kInvalidArgument, "physical model: empty or inconsistent input plane");
    const int full_w = zoomed_size(u.width, p.zoom), full_h = zoomed_size(u.height, p.zoom);
    OutputRegion r = region_in;
    if (r.w == 0 && r.h == 0) r = {0, 0, full_w, full_h};
    if (r.x < 0 || r.y < 0 || r.w <= 0 || r.h <= 0 || r.x + r.w > full_w || r.y + r.h > full_h) {
        std::ostringstream s;
        s << "physical model: region " << r.x << "," << r.y << "," << r.w << "," << r.h
          << " is not inside the output picture 0,0," << full_w << "," << full_h;
        throw Error(ErrorCode::kInvalidArgument, s.str());
    }
    out = FloatPlane(r.w, r.h, 0.f);

    const GrainRadiusLaw law(p.radius_mean, p.radius_sigma);
    const int k = cells_per_pixel_for(law);
    const bool adaptive = p.tolerance > 0;
    // Without a filter every offset is zero and one sample says all.
    const int n_offsets = p.filter_sigma == 0 ? 1 : (adaptive ? p.max_samples : p.samples);
    std::vector<double> xi = monte_carlo_offsets(p, plane_seed, n_offsets);
    // With a fixed N the estimate is a sum, so the order of the samples is free: visiting
    // them bin row by bin row keeps the bins a pixel looks at in cache. (With a tolerance
    // the first n samples must stay an unbiased draw, so their order is kept; at unit zoom
    // the mask estimator reads bits, not bins, and the order does not matter.)
    const bool unit_zoom = p.zoom == 1.0;
    if (!adaptive && !unit_zoom) sort_offsets_by_bin(xi, k);
    const SamplePoints points(xi, n_offsets, p.zoom, k);
    const auto [xmin, xmax, ymin, ymax] = points.offset_extent();
    const double margin = std::max({-xmin, xmax, -ymin, ymax}) + law.max_radius();

    // Input pixels the region can see.
    const int px0 = int(std::floor(output_to_input(r.x, p.zoom) + xmin - law.max_radius())) - 1;
    const int px1 = int(std::floor(output_to_input(r.x + r.w - 1, p.zoom) + xmax + law.max_radius())) + 1;
    const int py0 = int(std::floor(output_to_input(r.y, p.zoom) + ymin - law.max_radius())) - 1;
    const int py1 = int(std::floor(output_to_input(r.y + r.h - 1, p.zoom) + ymax + law.max_radius())) + 1;
    const CellIntensity intensity(u, law, p.grey_epsilon, generation_cells_per_pixel(k), px0, py0, px1, py1);

    RenderReport report;
    const double mean_cell_count = intensity.average_mean();
    const bool any_grain = intensity.any_grain();

    // Cost per output pixel and sample: a bin look-up and the grains of the bin, against
    // every grain's bounding box of pixels (plus the per-grain overhead).
    const double lambda = mean_cell_count * intensity.cells_per_pixel() * intensity.cells_per_pixel();
    const double er = law.mean();
    const double pixel_cost = 4.0 + lambda * std::pow(1.0 / k + 2 * er, 2);
    const double grain_cost = 1.0 + lambda / (p.zoom * p.zoom) * (3.0 + std::pow(2 * er * p.zoom + 2, 2));
    BooleanAlgorithm algo = p.algorithm;
    if (algo == BooleanAlgorithm::kAuto || adaptive)
        algo = (adaptive || pixel_cost <= grain_cost) ? BooleanAlgorithm::kPixelWise : BooleanAlgorithm::kGrainWise;
    report.algorithm = algo;
    // The mask estimator: unit zoom, a fixed N (a tolerance stops each pixel on its own).
    const bool by_masks = unit_zoom && !adaptive && algo == BooleanAlgorithm::kPixelWise;
    SampleClasses classes;
    if (by_masks) classes = group_samples_by_class(points);

    if (!any_grain) {  // a black plane: no grain, nothing to model
        report.mean_samples = 0;
        return report;
    }

    // Tile side in output pixels: about 64 input pixels, fewer when the bins would not fit.
    // The mask estimator takes 128: every tile generates and paints the grains of a margin
    // around it (the samples' reach, about 2.7 pixels each side at filter sigma 0.8), which
    // is 18 % more than the tile itself at 64 pixels and 9 % at 128, and its 16-bit masks of
    // a 128-pixel tile at ten bins per pixel (3.6 MB) are within kMaxMaskBytesPerTile
    // (r = 0.05 on 480x270 content: 2.08 against 2.26 s user time, six interleaved runs).
    int tile = std::clamp(int(std::lround((by_masks ? 128 : 64) * p.zoom)), 1, 256);
    while (tile > 1 && std::pow((tile / p.zoom + 2 * margin) * k, 2) > kMaxBinsPerTile) tile = (tile + 1) / 2;
    while (by_masks && tile > 8 &&
           std::pow((tile + 2 * margin) * k + 2, 2) * classes.words * double(sizeof(MaskWord)) > kMaxMaskBytesPerTile)
        tile = (tile + 1) / 2;
    const int tiles_x = (r.w + tile - 1) / tile, tiles_y = (r.h + tile - 1) / tile;
    report.tiles = tiles_x * tiles_y;

    std::atomic<int> next{0};
    std::atomic<std::size_t> grains{0};
    std::atomic<long long> samples_used{0};
    std::atomic<int> min_used{1 << 30}, max_used{0};
    auto worker = [&]() {
        TileEstimate est;
        GrainField field;
        for (int t; (t = next.fetch_add(1)) < report.tiles;) {
            const int tx = t % tiles_x, ty = t / tiles_x;
            TileRect rect;
            rect.x0 = r.x + tx * tile;
            rect.y0 = r.y + ty * tile;
            rect.x1 = std::min(rect.x0 + tile, r.x + r.w);
            rect.y1 = std::min(rect.y0 + tile, r.y + r.h);
            const InputRect reach = sample_reach(points, rect, p.zoom);
            if (by_masks) {
                grains += paint_tile_masks(field, intensity, law, plane_seed, reach.x0, reach.y0, reach.x1, reach.y1,
                                           classes, p.reference_kernels, est.masks);
            } else {
                field.generate(intensity, law, k, plane_seed, reach.x0, reach.y0, reach.x1, reach.y1,
                               algo == BooleanAlgorithm::kPixelWise);
                grains += field.grains().size();
            }
            SampleSchedule sched;
            sched.points = &points;
            sched.classes = by_masks ? &classes : nullptr;
            sched.tolerance = (adaptive && p.filter_sigma > 0) ? p.tolerance : 0;
            sched.min_samples = std::min(p.min_samples, n_offsets);
            sched.reference_kernels = p.reference_kernels;
            if (by_masks)
                estimate_pixel_wise_by_masks(field.grid(), rect, sched, est);
            else if (algo == BooleanAlgorithm::kPixelWise)
                estimate_pixel_wise(field, rect, sched, est);
            else
                estimate_grain_wise(field, rect, sched, est);
            for (int y = rect.y0; y < rect.y1; y++)
                for (int x = rect.x0; x < rect.x1; x++)
                    out.at(x - r.x, y - r.y) = est.value[std::size_t(y - rect.y0) * (rect.x1 - rect.x0) + (x - rect.x0)];
            samples_used += est.samples_total;
            int lo = min_used.load();
            while (est.samples_min < lo && !min_used.compare_exchange_weak(lo, est.samples_min)) {}
            int hi = max_used.load();
            while (est.samples_max > hi && !max_used.compare_exchange_weak(hi, est.samples_max)) {}
        }
    };
    const int nthreads = std::min(p.threads, report.tiles);
    std::vector<std::thread> pool;
    for (int i = 1; i < nthreads; i++) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    report.grains = grains;
    report.mean_samples = double(samples_used) / (double(r.w) * r.h);
    report.min_samples = min_used;
    report.max_samples = max_used;
    return report;
}

}  // namespace filmgrain::physical

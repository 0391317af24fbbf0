#include "physical/grain_field.hpp"

#include <algorithm>
#include <cmath>

#include "physical/cell_random.hpp"

namespace filmgrain::physical {

namespace {
int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
}  // namespace

CellIntensity::CellIntensity(const FloatPlane& u, const GrainRadiusLaw& radius, double grey_epsilon,
                             int cells_per_pixel, int px0, int py0, int px1, int py1) {
    x0_ = std::clamp(px0, 0, u.width - 1);
    x1_ = std::clamp(px1, 0, u.width - 1);
    y0_ = std::clamp(py0, 0, u.height - 1);
    y1_ = std::clamp(py1, 0, u.height - 1);
    k_ = cells_per_pixel;
    w_ = x1_ - x0_ + 1;
    h_ = y1_ - y0_ + 1;
    m_.resize(std::size_t(w_) * h_);
    e_.resize(m_.size());
    const double cell_area = 1.0 / (double(cells_per_pixel) * cells_per_pixel);
    const double per_log = cell_area / (3.141592653589793 * radius.mean_square());
    for (int y = 0; y < h_; y++)
        for (int x = 0; x < w_; x++) {
            double g = u.at(x0_ + x, y0_ + y);
            if (!(g > 0)) g = 0;  // also maps NaN to black
            g = std::min(g, 1.0 - grey_epsilon);
            const double m = -std::log1p(-g) * per_log;
            m_[std::size_t(y) * w_ + x] = m;
            e_[std::size_t(y) * w_ + x] = std::exp(-m);
        }
}

double CellIntensity::average_mean() const {
    double s = 0;
    for (double m : m_) s += m;
    return s / double(m_.size());
}

bool CellIntensity::any_grain() const {
    return std::any_of(m_.begin(), m_.end(), [](double m) { return m > 0; });
}

std::size_t CellIntensity::index(int px, int py) const {
    px = std::clamp(px, x0_, x1_);
    py = std::clamp(py, y0_, y1_);
    return std::size_t(py - y0_) * w_ + std::size_t(px - x0_);
}

void generate_cell_grains(int64_t cx, int64_t cy, const CellIntensity& intensity, const GrainRadiusLaw& radius,
                          uint64_t seed, std::vector<Grain>& out) {
    const int cells_per_pixel = intensity.cells_per_pixel();
    const int px = int(std::clamp<int64_t>(floor_div(cx, cells_per_pixel), -1, 1 << 30));
    const int py = int(std::clamp<int64_t>(floor_div(cy, cells_per_pixel), -1, 1 << 30));
    const double e = intensity.exp_neg_mean(px, py);
    if (e >= 1.0) return;
    const double m = intensity.mean(px, py);
    CellRandom rng(hash_coordinates(cx, cy, seed));
    // Poisson count by inversion of the CDF.
    const double t = rng.uniform();
    int n = 0;
    double p = e, cdf = e;
    while (t > cdf && n < kMaxGrainsPerCell) {
        n++;
        p *= m / n;
        cdf += p;
        if (p < 1e-300 && cdf < t) break;  // t beyond the double precision of the CDF
    }
    const double inv_k = 1.0 / cells_per_pixel;
    for (int i = 0; i < n; i++) {
        const double gx = (double(cx) + rng.uniform()) * inv_k;
        const double gy = (double(cy) + rng.uniform()) * inv_k;
        const double r = radius.constant() ? radius.max_radius() : radius.radius_from_normal(rng.normal());
        out.push_back({gx, gy, r * r});
    }
}

GrainField::CellBox GrainField::cells_reaching(const CellIntensity& intensity, const GrainRadiusLaw& radius, double x0,
                                               double y0, double x1, double y1) {
    const double rm = radius.max_radius();
    const int kc = intensity.cells_per_pixel();
    return {int64_t(std::floor((x0 - rm) * kc)), int64_t(std::floor((y0 - rm) * kc)), int64_t(std::floor((x1 + rm) * kc)),
            int64_t(std::floor((y1 + rm) * kc))};
}

void GrainField::generate(const CellIntensity& intensity, const GrainRadiusLaw& radius, int bins_per_pixel,
                          uint64_t seed, double x0, double y0, double x1, double y1, bool build_bins) {
    grains_.clear();
    const CellBox c = cells_reaching(intensity, radius, x0, y0, x1, y1);
    for (int64_t cy = c.y0; cy <= c.y1; cy++)
        for (int64_t cx = c.x0; cx <= c.x1; cx++) generate_cell_grains(cx, cy, intensity, radius, seed, grains_);
    grid_ = bin_grid_over(x0, y0, x1, y1, bins_per_pixel);
    if (!build_bins) return;

    const int64_t nbx = grid_.nbx;
    start_.assign(std::size_t(nbx * grid_.nby) + 1, 0);
    // Each grain's bin range is computed once, for the count and again for the fill.
    ranges_.resize(grains_.size());
    for (std::size_t i = 0; i < grains_.size(); i++) {
        const BinRange b = ranges_[i] = bins_met_by(grains_[i], std::sqrt(grains_[i].r2), grid_);
        for (int64_t by = b.ly; by <= b.hy; by++)
            for (int64_t bx = b.lx; bx <= b.hx; bx++) start_[std::size_t(by * nbx + bx) + 1]++;
    }
    for (std::size_t i = 1; i < start_.size(); i++) start_[i] += start_[i - 1];
    binned_.resize(start_.back());
    fill_.assign(start_.begin(), start_.end() - 1);
    const double k = grid_.k;
    for (std::size_t i = 0; i < grains_.size(); i++) {
        const Grain& g = grains_[i];
        const BinRange b = ranges_[i];
        const float r2k = r2_in_bins(g.r2, k);
        for (int64_t by = b.ly; by <= b.hy; by++)
            for (int64_t bx = b.lx; bx <= b.hx; bx++)
                binned_[fill_[std::size_t(by * nbx + bx)]++] = {bin_local(g.x * k, bx + grid_.bx0),
                                                                bin_local(g.y * k, by + grid_.by0), r2k};
    }
}

}  // namespace filmgrain::physical

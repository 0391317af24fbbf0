#include "physical/monte_carlo_offsets.hpp"

#include <cmath>

#include "physical/boolean_model.hpp"
#include "physical/cell_random.hpp"
#include "physical/normal_quantile.hpp"

namespace filmgrain::physical {

namespace {
// 1/g and 1/g^2 for the plastic number g, the real root of x^3 = x + 1 (the R2 sequence).
constexpr double kR2StepX = 0.7548776662466927600495;
constexpr double kR2StepY = 0.5698402909980532659114;

double fraction(double v) { return v - std::floor(v); }
}  // namespace

std::vector<double> shifted_r2_points(uint64_t plane_seed, int count) {
    CellRandom rng(hash_coordinates(-1, -1, plane_seed ^ 0x5bd1e995u));
    const double shift_x = rng.uniform(), shift_y = rng.uniform();
    std::vector<double> pts(2 * std::size_t(count));
    for (int i = 0; i < count; i++) {
        // The multiple of the step is reduced first so that large indices keep the precision
        // of small ones.
        pts[2 * std::size_t(i)] = fraction(shift_x + fraction(double(i + 1) * kR2StepX));
        pts[2 * std::size_t(i) + 1] = fraction(shift_y + fraction(double(i + 1) * kR2StepY));
    }
    return pts;
}

std::vector<double> independent_gaussian_offsets(const BooleanModelParams& p, uint64_t seed, int count) {
    CellRandom rng(hash_coordinates(-2, -2, seed));
    const double s = p.filter_sigma / p.zoom;
    std::vector<double> xi(2 * std::size_t(count));
    for (double& v : xi) v = s * rng.normal();
    return xi;
}

std::vector<double> monte_carlo_offsets(const BooleanModelParams& p, uint64_t plane_seed, int count) {
    std::vector<double> xi = shifted_r2_points(plane_seed, count);
    const double s = p.filter_sigma / p.zoom;
    // A point exactly on the edge (probability zero, but representable) stays finite.
    for (double& v : xi) v = s * standard_normal_quantile(v > 0 ? v : 0x1.0p-53);
    return xi;
}

}  // namespace filmgrain::physical

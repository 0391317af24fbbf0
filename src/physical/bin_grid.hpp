// The grid of bins over a rectangle and the bins a grain can reach. The bin lists of
// GrainField and the coverage masks painted grain by grain (coverage_masks.hpp) both take a
// grain's bins from here, so they consider the same (grain, bin) pairs.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "physical/grain_geometry.hpp"

namespace filmgrain::physical {

struct BinGrid {
    double k = 1;             // bins per input pixel
    int64_t bx0 = 0, by0 = 0;  // global coordinates of the first bin
    int64_t nbx = 0, nby = 0;
};

// The bins that meet [x0, x1] x [y0, y1] (input-pixel units).
inline BinGrid bin_grid_over(double x0, double y0, double x1, double y1, int bins_per_pixel) {
    BinGrid g;
    g.k = bins_per_pixel;
    g.bx0 = int64_t(std::floor(x0 * g.k));
    g.by0 = int64_t(std::floor(y0 * g.k));
    g.nbx = int64_t(std::floor(x1 * g.k)) - g.bx0 + 1;
    g.nby = int64_t(std::floor(y1 * g.k)) - g.by0 + 1;
    return g;
}

// Grid-relative bin ranges [lx, hx] x [ly, hy]; empty (lx > hx or ly > hy) when the grain
// misses the grid.
struct BinRange {
    int64_t lx, hx, ly, hy;
};

// The bins of the grid that a grain's bounding square, widened by a pad, meets. The pad (in
// bin units) makes every grain that the float test of inside_grain() can accept for a point
// of a bin meet that bin: float rounding of bin-local coordinates is below 1e-6 bin units,
// the pad is a hundred times that. `r` is sqrt(g.r2).
inline BinRange bins_met_by(const Grain& g, double r, const BinGrid& grid) {
    constexpr double kPad = 1e-4;
    const double k = grid.k;
    return {std::max<int64_t>(floor_to_int((g.x - r) * k - kPad) - grid.bx0, 0),
            std::min<int64_t>(floor_to_int((g.x + r) * k + kPad) - grid.bx0, grid.nbx - 1),
            std::max<int64_t>(floor_to_int((g.y - r) * k - kPad) - grid.by0, 0),
            std::min<int64_t>(floor_to_int((g.y + r) * k + kPad) - grid.by0, grid.nby - 1)};
}

}  // namespace filmgrain::physical

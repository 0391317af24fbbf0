// The grains of the Boolean model over a rectangle, generated cell by cell and binned.
// Grains are drawn per cell; the bins a look-up reads are a finer grid of their own.
// Cells are squares of side 1/cells_per_pixel aligned on the input pixel grid, so each lies
// in one input pixel and its grain count is Poisson(lambda(pixel) * cell area). A cell's
// grains depend only on its coordinates and the seed (cell_random.hpp).
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/float_plane.hpp"
#include "physical/bin_grid.hpp"
#include "physical/grain_geometry.hpp"
#include "physical/grain_radius.hpp"

namespace filmgrain::physical {

// Per-input-pixel Poisson law of a cell's grain count, over a box of input pixels.
class CellIntensity {
public:
    // Covers input pixels [px0, px1] x [py0, py1] (clamped to the picture; points outside
    // take the nearest edge pixel).
    CellIntensity(const FloatPlane& u, const GrainRadiusLaw& radius, double grey_epsilon, int cells_per_pixel,
                  int px0, int py0, int px1, int py1);
    // exp(-mean) and mean of the grain count of a cell lying in input pixel (px, py).
    double exp_neg_mean(int px, int py) const { return e_[index(px, py)]; }
    double mean(int px, int py) const { return m_[index(px, py)]; }
    double average_mean() const;
    bool any_grain() const;
    int cells_per_pixel() const { return k_; }

private:
    std::size_t index(int px, int py) const;
    int x0_, y0_, x1_, y1_, w_, h_, k_;
    std::vector<double> m_, e_;
};

// Largest Poisson count drawn for one cell; reached with probability < 1e-30 for every
// allowed parameter set, it only bounds the loop.
constexpr int kMaxGrainsPerCell = 4096;

// Appends the grains of cell (cx, cy) to `out`.
void generate_cell_grains(int64_t cx, int64_t cy, const CellIntensity& intensity, const GrainRadiusLaw& radius,
                          uint64_t seed, std::vector<Grain>& out);

// The grains that can cover any point of [x0, x1] x [y0, y1] (input-pixel units), and
// optionally their bins: a grain is listed in every bin of the grid over that rectangle
// that bins_met_by() gives it.
// One field is reused tile after tile: its vectors keep their capacity, so a worker stops
// allocating (and the kernel stops zeroing fresh pages) after its first tile.
class GrainField {
public:
    // Bins are 1/bins_per_pixel wide; the grains come from the intensity's own cells. The
    // grid is set either way; the bin lists are built only with build_bins.
    void generate(const CellIntensity& intensity, const GrainRadiusLaw& radius, int bins_per_pixel, uint64_t seed,
                  double x0, double y0, double x1, double y1, bool build_bins);

    // As generate() without bins, but the grains go to use(const std::vector<Grain>&) one row
    // of cells at a time and are not kept: a row is still in cache when it is used. Returns
    // how many grains there were; grains() holds only the last row afterwards.
    template <typename Use>
    std::size_t generate_by_cell_rows(const CellIntensity& intensity, const GrainRadiusLaw& radius, int bins_per_pixel,
                                      uint64_t seed, double x0, double y0, double x1, double y1, Use&& use) {
        const CellBox c = cells_reaching(intensity, radius, x0, y0, x1, y1);
        grid_ = bin_grid_over(x0, y0, x1, y1, bins_per_pixel);
        std::size_t total = 0;
        for (int64_t cy = c.y0; cy <= c.y1; cy++) {
            grains_.clear();
            for (int64_t cx = c.x0; cx <= c.x1; cx++) generate_cell_grains(cx, cy, intensity, radius, seed, grains_);
            total += grains_.size();
            use(static_cast<const std::vector<Grain>&>(grains_));
        }
        return total;
    }

    const std::vector<Grain>& grains() const { return grains_; }
    // Whether the point at bin-local (lx, ly) of global bin (bx, by) is inside some grain of
    // that bin. The bin must lie in the rectangle, and the bins must have been built.
    bool covered_in_bin(int64_t bx, int64_t by, float lx, float ly) const {
        const std::size_t b = std::size_t(by - grid_.by0) * grid_.nbx + std::size_t(bx - grid_.bx0);
        for (uint32_t i = start_[b], e = start_[b + 1]; i < e; i++) {
            const BinnedGrain& g = binned_[i];
            if (inside_grain(lx, ly, g.x, g.y, g.r2)) return true;
        }
        return false;
    }
    double cells_per_pixel() const { return grid_.k; }
    const BinGrid& grid() const { return grid_; }
    // The bin grid: global coordinates of its first bin, its size, and per bin (row-major)
    // the range [bin_start()[b], bin_start()[b + 1]) of binned_grains().
    int64_t first_bin_x() const { return grid_.bx0; }
    int64_t first_bin_y() const { return grid_.by0; }
    int64_t bins_x() const { return grid_.nbx; }
    int64_t bins_y() const { return grid_.nby; }
    const std::vector<uint32_t>& bin_start() const { return start_; }
    const std::vector<BinnedGrain>& binned_grains() const { return binned_; }

private:
    // The cells whose grains can reach [x0, x1] x [y0, y1].
    struct CellBox {
        int64_t x0, y0, x1, y1;
    };
    static CellBox cells_reaching(const CellIntensity& intensity, const GrainRadiusLaw& radius, double x0, double y0,
                                  double x1, double y1);

    BinGrid grid_;
    std::vector<Grain> grains_;
    std::vector<uint32_t> start_;
    std::vector<BinnedGrain> binned_;
    std::vector<uint32_t> fill_;
    std::vector<BinRange> ranges_;
};

}  // namespace filmgrain::physical

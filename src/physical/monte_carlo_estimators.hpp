// The Monte Carlo estimators of the filtered Boolean model over one tile of output pixels
// (Newson, Delon, Galerne 2017, algorithms 2 and 3). All of them test the same sample points
// (sample_points.hpp) against the same grains with the same arithmetic, so they agree exactly.
#pragma once
#include <vector>

#include "physical/coverage_masks.hpp"
#include "physical/grain_field.hpp"
#include "physical/sample_points.hpp"

namespace filmgrain::physical {

struct TileRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // output pixels, end exclusive
};

struct SampleSchedule {
    const SamplePoints* points = nullptr;
    const SampleClasses* classes = nullptr;  // unit zoom with a fixed N: the mask estimator
    double tolerance = 0;                    // > 0: stop per pixel (pixel-wise only)
    int min_samples = 1;
    bool reference_kernels = false;          // the scalar coverage-mask kernel (for tests)
};

struct TileEstimate {
    std::vector<float> value;  // row-major over the tile
    long long samples_total = 0;
    int samples_min = 0, samples_max = 0;
    std::vector<MaskWord> masks;  // scratch of the mask estimator, kept between tiles
};

// Per pixel, each sample point is looked up in its bin. With a tolerance, sampling of a
// pixel stops once the standard error of its estimate, sqrt(p(1-p)/n) with the
// Agresti-Coull p = (hits + 1) / (n + 2) so that it is never zero, reaches the target.
void estimate_pixel_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out);

// Unit zoom, fixed N: per bin, the mask of the samples its grains cover (coverage_masks.hpp),
// then per pixel one bit per sample. Needs s.classes, and out.masks painted by
// paint_tile_masks() over the tile's sample_reach(), whose bin grid is `grid`: its bins are
// the bins the samples fall in.
void estimate_pixel_wise_by_masks(const BinGrid& grid, const TileRect& rect, const SampleSchedule& s,
                                  TileEstimate& out);

// Per sample, every grain marks the pixels whose shifted centres it covers.
void estimate_grain_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out);

// The rectangle (input-pixel units) whose bins hold every sample point of the tile, for
// GrainField::generate. At unit zoom it is made of whole bins, so that the bin grid lines up
// with the sample points' bins.
struct InputRect {
    double x0, y0, x1, y1;
};
InputRect sample_reach(const SamplePoints& points, const TileRect& rect, double zoom);

}  // namespace filmgrain::physical

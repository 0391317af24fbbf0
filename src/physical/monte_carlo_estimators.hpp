// The two Monte Carlo estimators of the filtered Boolean model over one tile of output
// pixels (Newson, Delon, Galerne 2017, algorithms 2 and 3). Both test the same sample
// points y + xi_k against the same grains with the same arithmetic, so they agree exactly.
#pragma once
#include <vector>

#include "physical/grain_field.hpp"

namespace filmgrain::physical {

// The input-pixel coordinate of the centre of output pixel j (the same expression
// everywhere, so that every algorithm rounds the same way).
inline double output_to_input(int j, double zoom) { return (double(j) + 0.5) / zoom; }

struct TileRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // output pixels, end exclusive
};

struct SampleSchedule {
    const std::vector<double>* offsets = nullptr;  // xi_k as x, y pairs
    int count = 0;                                 // N (or the cap with a tolerance)
    double tolerance = 0;                          // > 0: stop per pixel (pixel-wise only)
    int min_samples = 1;
    double zoom = 1;
};

struct TileEstimate {
    std::vector<float> value;  // row-major over the tile
    long long samples_total = 0;
    int samples_min = 0, samples_max = 0;
};

// Per pixel, each sample point is looked up in its bin. With a tolerance, sampling of a
// pixel stops once the standard error of its estimate, sqrt(p(1-p)/n) with the
// Agresti-Coull p = (hits + 1) / (n + 2) so that it is never zero, reaches the target.
void estimate_pixel_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out);

// Per sample, every grain marks the pixels whose shifted centres it covers.
void estimate_grain_wise(const GrainField& field, const TileRect& rect, const SampleSchedule& s, TileEstimate& out);

}  // namespace filmgrain::physical

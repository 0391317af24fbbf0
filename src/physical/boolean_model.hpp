// Physically based film grain: the inhomogeneous Boolean model of Newson, Delon and
// Galerne ("A Stochastic Film Grain Model for Resolution-Independent Rendering", CGF 2017).
// Grain centres form a Poisson process whose intensity at a point of input pixel p is
//     lambda(p) = ln(1 / (1 - u(p))) / (pi E[r^2]),
// so that the probability of being covered by a grain equals the grey level u(p). The
// output pixel at y is the Gaussian-filtered indicator of the union of grains, estimated by
// Monte Carlo: v(y) = (1/N) sum_k 1[y + xi_k is covered], xi_k ~ N(0, (sigma/zoom)^2 I).
//
// Differences from the published code, on purpose:
// - grains of a cell come from a hash of the cell's coordinates and the seed only, so the
//   output is identical for every thread count, tiling and region of interest;
// - the offsets xi_k are shared by all pixels (as the published grain-wise algorithm does)
//   in both algorithms here, so the pixel-wise and the grain-wise algorithm give the same
//   output and the choice between them is only about speed; they are a randomly shifted
//   low-discrepancy set, not independent draws (monte_carlo_offsets.hpp: isotropic grain
//   in every frame, mean still unbiased);
// - outside the picture the intensity of the nearest edge pixel continues, so borders are
//   not darkened;
// - u is clamped to 1 - grey_epsilon (lambda is infinite at u = 1).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/float_plane.hpp"

namespace filmgrain::physical {

enum class BooleanAlgorithm { kAuto, kPixelWise, kGrainWise };

struct BooleanModelParams {
    double radius_mean = 0.1;   // mu_r, in input pixels
    double radius_sigma = 0.0;  // sigma_r; 0 = constant radius
    double filter_sigma = 0.8;  // Gaussian filter, in output pixels
    double zoom = 1.0;          // output pixels per input pixel
    int samples = 800;          // N, the Monte Carlo sample count (fixed-N mode)
    // > 0: per pixel, stop when the estimated standard error of the pixel reaches this
    // value (at least min_samples, at most max_samples). Pixel-wise only.
    double tolerance = 0.0;
    int min_samples = 32;
    int max_samples = 4096;
    double grey_epsilon = 1e-3;  // u is clamped to [0, 1 - grey_epsilon]
    uint64_t seed = 0;
    BooleanAlgorithm algorithm = BooleanAlgorithm::kAuto;
    int threads = 1;
    // The scalar reference kernels instead of the vector ones (same output; for the tests).
    bool reference_kernels = false;
};

// A region of output pixels (coordinates in the full zoomed picture). w == 0: everything.
struct OutputRegion {
    int x = 0, y = 0, w = 0, h = 0;
};

struct RenderReport {
    BooleanAlgorithm algorithm = BooleanAlgorithm::kPixelWise;
    double mean_samples = 0;  // the N actually used per pixel, averaged
    int min_samples = 0, max_samples = 0;
    std::size_t grains = 0;  // grains generated (with the margins of every tile)
    int tiles = 0;
};

// Throws filmgrain::Error(kInvalidParams) naming the field, its value and the allowed range.
void validate(const BooleanModelParams& p);

// Output size of the full zoomed picture: floor(zoom * size), at least 1.
int zoomed_size(int input_size, double zoom);

// Renders `region` of the grain picture of the grey levels `u` (values in [0, 1]) into
// `out` (resized to the region). `plane_seed` separates planes / frames.
RenderReport render_boolean_model(const FloatPlane& u, const BooleanModelParams& p, const OutputRegion& region,
                                  uint64_t plane_seed, FloatPlane& out);

const char* algorithm_name(BooleanAlgorithm a);

}  // namespace filmgrain::physical

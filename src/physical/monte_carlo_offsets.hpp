// The Monte Carlo offsets xi_k of the filtered Boolean model, shared by every pixel of a
// plane (Newson, Delon, Galerne 2017, the grain-wise algorithm; here both algorithms).
//
// Independent Gaussian draws make the realized filter of one plane a random cloud of N
// points: at N = 800 its second moments differ along x and y by a few percent, so the
// grain of one frame is stretched along one axis and the next frame along another, which
// shows as flicker in the grain's direction. The offsets here are the R2 low-discrepancy
// sequence (Roberts 2018, the generalized golden ratio in two dimensions) moved by a random
// shift modulo 1 (a Cranley-Patterson rotation) drawn from the plane seed, then mapped to a
// Gaussian coordinate by coordinate through the normal quantile function. Each
// shifted point is uniform on the unit square, so every xi_k is exactly N(0, s^2 I) and the
// mean of the estimate stays the grey level (unbiased). Each coordinate of the set is an
// evenly spread one-dimensional sequence, so the realized filter has nearly the Gaussian's
// moments along x and along y alike: isotropic in every plane. (Box-Muller, radius from one
// coordinate and angle from the other, was tried: its few far points, whose angles are not
// balanced, left the anisotropy at N <= 200 no smaller than independent draws give.)
#pragma once
#include <cstdint>
#include <vector>

namespace filmgrain::physical {

struct BooleanModelParams;

// x, y pairs in input-pixel units; the first k are the same for every count >= k.
std::vector<double> monte_carlo_offsets(const BooleanModelParams& p, uint64_t plane_seed, int count);

// Independent N(0, s^2 I) draws from a seeded generator: what the offsets were before the
// low-discrepancy set, and the Monte Carlo error the set is judged against (tests, tradeoff).
std::vector<double> independent_gaussian_offsets(const BooleanModelParams& p, uint64_t seed, int count);

// The unit-square points behind the offsets (for the tests: they must be uniform).
std::vector<double> shifted_r2_points(uint64_t plane_seed, int count);

}  // namespace filmgrain::physical

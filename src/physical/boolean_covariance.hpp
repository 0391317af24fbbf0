// Exact first and second order statistics of the Boolean model at a constant grey level u
// (Newson, Delon, Galerne, "Realistic film grain rendering", IPOL 2017, and the analysis
// of the filtered model's covariance in their follow-up work):
//   mean            E[1_Z(y)] = u
//   covariance      C(t) = (1-u)^2 (exp(lambda E[A_r(t)]) - 1),   t = |y - y'|
// with A_r(t) the area of the intersection of two discs of radius r at distance t
// (E over the radius law; numerical integration for log-normal radii). Filtering with a
// Gaussian of standard deviation s (input units) gives the covariance of v = 1_Z * g_s:
//   C_s(t) = (C * g_{sqrt(2) s})(t),
// computed in polar form with the modified Bessel function I0. The Monte Carlo output with
// N shared offsets xi_k has, for given offsets, covariance (1/N^2) sum_{k,l} C(d + xi_k - xi_l),
// whose mean over the offsets is C(d)/N + (1 - 1/N) C_s(d).
#pragma once
#include <vector>

#include "physical/boolean_model.hpp"
#include "physical/grain_radius.hpp"

namespace filmgrain::physical {

// Area of the intersection of two discs of radius r whose centres are t apart.
double disc_intersection_area(double r, double t);

class BooleanCovariance {
public:
    // The statistics of the model `p` at grey level u (clamped as the renderer clamps it).
    BooleanCovariance(const BooleanModelParams& p, double u);
    // The same model at another grey level (reuses the radius integration).
    BooleanCovariance at_grey(double u) const;

    double grey() const { return u_; }
    double lambda() const { return lambda_; }
    // Unfiltered covariance of the coverage indicator at distance t (input pixels).
    double coverage(double t) const;
    // Covariance of the filtered model (N -> infinity) at distance t (input pixels).
    double filtered(double t) const;
    // The same at a lag of (dx, dy) output pixels.
    double filtered_output_lag(double dx, double dy) const;
    // Expected covariance of the N-sample output at a lag of output pixels.
    double expected_monte_carlo(double dx, double dy, int n) const;
    // Covariance of the output for the given offsets (x, y pairs, input units).
    double given_offsets(double dx, double dy, const std::vector<double>& xi) const;
    // Distance beyond which coverage() is zero.
    double coverage_support() const { return 2 * law_.max_radius(); }

private:
    double mean_lens_area(double t) const;
    GrainRadiusLaw law_;
    double zoom_, s_;  // s_: filter sigma in input pixels
    void set_grey(double u);
    double eps_;
    double u_, lambda_, q_;
    std::vector<double> lens_table_;  // E[A_r(t)] on a uniform grid of [0, 2 r_max]
    double table_step_ = 0;
};

}  // namespace filmgrain::physical

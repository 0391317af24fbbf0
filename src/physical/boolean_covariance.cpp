#include "physical/boolean_covariance.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain::physical {

namespace {
constexpr double kPi = 3.141592653589793;
constexpr int kLensTableSize = 4096;
constexpr int kRadiusNodes = 400;  // quadrature over the standard normal of the log radius

// I0(x) * exp(-x) for x >= 0 (Abramowitz & Stegun 9.8.1 and 9.8.2, relative error < 2e-7).
double scaled_bessel_i0(double x) {
    if (x < 3.75) {
        const double t = (x / 3.75) * (x / 3.75);
        return std::exp(-x) *
               (1 + t * (3.5156229 + t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813))))));
    }
    const double t = 3.75 / x;
    return (0.39894228 + t * (0.01328592 + t * (0.00225319 + t * (-0.00157565 + t * (0.00916281 + t * (-0.02057706 +
            t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))))) / std::sqrt(x);
}
}  // namespace

double disc_intersection_area(double r, double t) {
    if (t >= 2 * r) return 0;
    const double h = t / (2 * r);
    return 2 * r * r * std::acos(h) - 0.5 * t * std::sqrt(std::max(0.0, 4 * r * r - t * t));
}

BooleanCovariance::BooleanCovariance(const BooleanModelParams& p, double u)
    : law_(p.radius_mean, p.radius_sigma), zoom_(p.zoom), s_(p.filter_sigma / p.zoom), eps_(p.grey_epsilon) {
    set_grey(u);
    table_step_ = coverage_support() / (kLensTableSize - 1);
    lens_table_.resize(kLensTableSize);
    for (int i = 0; i < kLensTableSize; i++) lens_table_[i] = mean_lens_area(i * table_step_);
}

void BooleanCovariance::set_grey(double u) {
    u_ = std::clamp(u, 0.0, 1.0 - eps_);
    q_ = 1 - u_;
    lambda_ = -std::log1p(-u_) / (kPi * law_.mean_square());
}

BooleanCovariance BooleanCovariance::at_grey(double u) const {
    BooleanCovariance c = *this;
    c.set_grey(u);
    return c;
}

double BooleanCovariance::mean_lens_area(double t) const {
    if (law_.constant()) return disc_intersection_area(law_.max_radius(), t);
    // E over z ~ N(0,1) of A_{min(exp(mu + s z), r_max)}(t): midpoint rule on [-8, 8].
    double sum = 0, wsum = 0;
    const double dz = 16.0 / kRadiusNodes;
    for (int i = 0; i < kRadiusNodes; i++) {
        const double z = -8 + (i + 0.5) * dz;
        const double w = std::exp(-0.5 * z * z);
        sum += w * disc_intersection_area(law_.radius_from_normal(z), t);
        wsum += w;
    }
    return sum / wsum;
}

double BooleanCovariance::coverage(double t) const {
    t = std::abs(t);
    if (t >= coverage_support() || u_ <= 0) return 0;
    const double f = t / table_step_;
    const int i = std::min(int(f), kLensTableSize - 2);
    const double a = lens_table_[i] + (f - i) * (lens_table_[i + 1] - lens_table_[i]);
    return q_ * q_ * std::expm1(lambda_ * a);
}

double BooleanCovariance::filtered(double t) const {
    if (s_ == 0) return coverage(t);
    // C_s(t) = (1/v) int_0^R C(rho) rho exp(-(t^2 + rho^2) / 2v) I0(t rho / v) drho, v = 2 s^2,
    // the angular integral of the 2-D Gaussian of variance v per axis done in closed form.
    const double v = 2 * s_ * s_;
    // The integrand is negligible where |rho - t| > 9 sqrt(v): integrate only where it lives.
    const double lo = std::max(0.0, t - 9 * std::sqrt(v)), hi = std::min(coverage_support(), t + 9 * std::sqrt(v));
    if (hi <= lo) return 0;
    constexpr int kNodes = 512;  // Simpson
    const double h = (hi - lo) / kNodes;
    double sum = 0;
    for (int i = 0; i <= kNodes; i++) {
        const double rho = lo + i * h;
        const double x = t * rho / v;
        const double f = coverage(rho) * rho * std::exp(-(t - rho) * (t - rho) / (2 * v)) * scaled_bessel_i0(x);
        sum += f * ((i == 0 || i == kNodes) ? 1 : (i % 2 ? 4 : 2));
    }
    return sum * h / 3 / v;
}

double BooleanCovariance::filtered_output_lag(double dx, double dy) const {
    return filtered(std::hypot(dx, dy) / zoom_);
}

double BooleanCovariance::expected_monte_carlo(double dx, double dy, int n) const {
    const double t = std::hypot(dx, dy) / zoom_;
    if (s_ == 0) return coverage(t);
    return coverage(t) / n + (1 - 1.0 / n) * filtered(t);
}

double BooleanCovariance::given_offsets(double dx, double dy, const std::vector<double>& xi) const {
    const std::size_t n = xi.size() / 2;
    const double ix = dx / zoom_, iy = dy / zoom_;
    double sum = 0;
    for (std::size_t k = 0; k < n; k++)
        for (std::size_t l = 0; l < n; l++)
            sum += coverage(std::hypot(ix + xi[2 * k] - xi[2 * l], iy + xi[2 * k + 1] - xi[2 * l + 1]));
    return sum / (double(n) * n);
}

}  // namespace filmgrain::physical

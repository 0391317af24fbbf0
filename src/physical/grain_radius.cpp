#include "physical/grain_radius.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain::physical {

namespace {
double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
}  // namespace

GrainRadiusLaw::GrainRadiusLaw(double mean, double sigma) {
    if (sigma <= 0) {
        r_max_ = mean_r_ = mean;
        mean_r2_ = mean * mean;
        return;
    }
    sigma_ln_ = std::sqrt(std::log1p((sigma * sigma) / (mean * mean)));
    mu_ln_ = std::log(mean) - 0.5 * sigma_ln_ * sigma_ln_;
    r_max_ = std::exp(mu_ln_ + 3.090232306167813 * sigma_ln_);
    // E[min(R, m)^k] = E[R^k; R < m] + m^k P(R >= m), with
    // E[R^k; R < m] = exp(k mu + k^2 s^2 / 2) Phi((ln m - mu - k s^2) / s).
    const double a = (std::log(r_max_) - mu_ln_) / sigma_ln_;
    const double tail = 1.0 - normal_cdf(a);
    mean_r_ = std::exp(mu_ln_ + 0.5 * sigma_ln_ * sigma_ln_) * normal_cdf(a - sigma_ln_) + r_max_ * tail;
    mean_r2_ = std::exp(2 * mu_ln_ + 2 * sigma_ln_ * sigma_ln_) * normal_cdf(a - 2 * sigma_ln_) + r_max_ * r_max_ * tail;
}

double GrainRadiusLaw::radius_from_normal(double z) const {
    if (constant()) return r_max_;
    return std::min(std::exp(mu_ln_ + sigma_ln_ * z), r_max_);
}

}  // namespace filmgrain::physical

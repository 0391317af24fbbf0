// The grain radius law of the Boolean model: a constant radius, or a log-normal radius
// with the given mean and standard deviation, capped at a maximum radius (Newson, Delon,
// Galerne 2017, section 3.3). The cap is applied by min(R, r_max), and every moment here
// is of that capped law, so the intensity computed from E[r^2] gives coverage u exactly.
#pragma once

namespace filmgrain::physical {

class GrainRadiusLaw {
public:
    // sigma == 0: constant radius `mean`. Otherwise log-normal, capped at its 0.999 quantile.
    GrainRadiusLaw(double mean, double sigma);

    bool constant() const { return sigma_ln_ == 0.0; }
    double max_radius() const { return r_max_; }
    double mean_square() const { return mean_r2_; }
    double mean() const { return mean_r_; }
    // The radius for a standard normal draw z (ignored for a constant radius).
    double radius_from_normal(double z) const;
    double mu_ln() const { return mu_ln_; }
    double sigma_ln() const { return sigma_ln_; }

private:
    double mu_ln_ = 0, sigma_ln_ = 0, r_max_ = 0, mean_r2_ = 0, mean_r_ = 0;
};

}  // namespace filmgrain::physical

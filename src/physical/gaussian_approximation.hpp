// A Gaussian texture with the second-order statistics of the filtered Boolean model: at an
// output pixel of grey level u the value is u + (h_u * W)(y), W one white Gaussian field
// shared by all grey levels (so texture is continuous across level changes) and h_u the
// convolution square root of the closed-form covariance C_u (boolean_covariance.hpp):
// h_u = F^-1 sqrt(max(F C_u, 0)) on a periodic grid larger than the covariance's support,
// cropped to where it holds all but 1e-4 of its energy. That is spectral synthesis per grey
// level done as a small spot-noise convolution, cheap enough for video; kernels are built
// only for the grey levels a picture uses.
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "core/float_plane.hpp"
#include "physical/boolean_covariance.hpp"
#include "physical/boolean_model.hpp"

namespace filmgrain::physical {

class GaussianApproximation {
public:
    // `levels`: number of grey levels with their own kernel (u quantized to them).
    GaussianApproximation(const BooleanModelParams& p, int levels = 256);

    // Renders `region` (output pixels of the zoomed picture, as render_boolean_model).
    void render(const FloatPlane& u, const OutputRegion& region, uint64_t seed, FloatPlane& out) const;

    // The kernel of a level: (2R+1)^2 taps, row-major. Built on first use.
    const std::vector<float>& kernel(int level) const;
    int kernel_radius() const { return radius_; }
    int levels() const { return levels_; }
    int kernels_built() const;
    // The covariance the texture is built to have, at a lag of output pixels.
    double target_covariance(double u, double dx, double dy) const;
    // The covariance the cropped kernel actually gives: sum_o h(o) h(o + d).
    double kernel_covariance(int level, int dx, int dy) const;

private:
    std::vector<float> build_kernel(int level) const;
    BooleanModelParams p_;
    int levels_;
    int grid_;    // periodic grid for the spectral square root
    int radius_;  // kernel half-size after cropping
    BooleanCovariance base_;
    mutable std::mutex mutex_;
    mutable std::vector<std::unique_ptr<std::vector<float>>> kernels_;
};

}  // namespace filmgrain::physical

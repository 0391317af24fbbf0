// Where the Monte Carlo sample k of an output pixel falls on the bin grid: the bin and the
// point's coordinate inside that bin, per axis. Every estimator asks this one class, so the
// coverage test sees the same float coordinates whichever algorithm runs.
//
// At zoom 1 a pixel centre is an integer plus one half and a bin is 1/cells_per_pixel of an
// input pixel, so moving one pixel moves the sample by exactly cells_per_pixel bins: the
// bin-local coordinate of sample k is the same for every pixel. It is computed once, from
// cells_per_pixel * (1/2 + xi_k), which is what lets the unit-zoom estimator precompute,
// per bin, which samples its grains cover (coverage_masks.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include "physical/grain_field.hpp"

namespace filmgrain::physical {

// The input-pixel coordinate of the centre of output pixel j (the same expression
// everywhere, so that every algorithm rounds the same way).
inline double output_to_input(int j, double zoom) { return (double(j) + 0.5) / zoom; }

struct BinPoint {
    int64_t bin;
    float local;
};

class SamplePoints {
public:
    // offsets: xi_k as x, y pairs (input-pixel units); count of them used.
    SamplePoints(const std::vector<double>& offsets, int count, double zoom, int cells_per_pixel)
        : xi_(offsets.data()), count_(count), zoom_(zoom), k_(cells_per_pixel), unit_zoom_(zoom == 1.0) {
        if (!unit_zoom_) return;
        step_x_.resize(std::size_t(count));
        step_y_.resize(std::size_t(count));
        for (int i = 0; i < count; i++) {
            step_x_[std::size_t(i)] = split(k_ * (0.5 + xi_[2 * i]));
            step_y_[std::size_t(i)] = split(k_ * (0.5 + xi_[2 * i + 1]));
        }
    }

    bool unit_zoom() const { return unit_zoom_; }
    int count() const { return count_; }
    int cells_per_pixel() const { return k_; }
    double zoom() const { return zoom_; }
    double offset_x(int i) const { return xi_[2 * i]; }
    double offset_y(int i) const { return xi_[2 * i + 1]; }

    // Sample i of output column j / row j.
    BinPoint x(int j, int i) const { return unit_zoom_ ? shifted(j, step_x_[std::size_t(i)]) : scaled(j, xi_[2 * i]); }
    BinPoint y(int j, int i) const {
        return unit_zoom_ ? shifted(j, step_y_[std::size_t(i)]) : scaled(j, xi_[2 * i + 1]);
    }

    // Unit zoom only: the bin step (relative to cells_per_pixel * j) and local coordinate.
    const std::vector<BinPoint>& steps_x() const { return step_x_; }
    const std::vector<BinPoint>& steps_y() const { return step_y_; }

private:
    static BinPoint split(double scaled) {
        const int64_t b = floor_to_int(scaled);
        return {b, bin_local(scaled, b)};
    }
    BinPoint shifted(int j, const BinPoint& step) const { return {int64_t(k_) * j + step.bin, step.local}; }
    BinPoint scaled(int j, double offset) const { return split((output_to_input(j, zoom_) + offset) * k_); }

    const double* xi_;
    int count_;
    double zoom_;
    int k_;
    bool unit_zoom_;
    std::vector<BinPoint> step_x_, step_y_;
};

}  // namespace filmgrain::physical

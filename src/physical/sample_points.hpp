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
#include <algorithm>
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

// The smallest and largest offsets of the samples, per axis, the zero offset included
// (input-pixel units): how far from a pixel centre its samples reach.
struct OffsetExtent {
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};
// Unit zoom: the smallest and largest bin steps of the samples, per axis.
struct StepExtent {
    int64_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

class SamplePoints {
public:
    // offsets: xi_k as x, y pairs (input-pixel units); count of them used.
    SamplePoints(const std::vector<double>& offsets, int count, double zoom, int cells_per_pixel)
        : xi_(offsets.data()), count_(count), zoom_(zoom), k_(cells_per_pixel), unit_zoom_(zoom == 1.0) {
        for (int i = 0; i < count; i++) {
            offset_extent_.x0 = std::min(offset_extent_.x0, xi_[2 * i]);
            offset_extent_.x1 = std::max(offset_extent_.x1, xi_[2 * i]);
            offset_extent_.y0 = std::min(offset_extent_.y0, xi_[2 * i + 1]);
            offset_extent_.y1 = std::max(offset_extent_.y1, xi_[2 * i + 1]);
        }
        if (!unit_zoom_) return;
        step_x_.resize(std::size_t(count));
        step_y_.resize(std::size_t(count));
        for (int i = 0; i < count; i++) {
            const BinPoint sx = split(k_ * (0.5 + xi_[2 * i])), sy = split(k_ * (0.5 + xi_[2 * i + 1]));
            step_x_[std::size_t(i)] = sx;
            step_y_[std::size_t(i)] = sy;
            step_extent_.x0 = i ? std::min(step_extent_.x0, sx.bin) : sx.bin;
            step_extent_.x1 = i ? std::max(step_extent_.x1, sx.bin) : sx.bin;
            step_extent_.y0 = i ? std::min(step_extent_.y0, sy.bin) : sy.bin;
            step_extent_.y1 = i ? std::max(step_extent_.y1, sy.bin) : sy.bin;
        }
    }

    bool unit_zoom() const { return unit_zoom_; }
    int count() const { return count_; }
    int cells_per_pixel() const { return k_; }
    double zoom() const { return zoom_; }
    double offset_x(int i) const { return xi_[2 * i]; }
    double offset_y(int i) const { return xi_[2 * i + 1]; }
    const OffsetExtent& offset_extent() const { return offset_extent_; }
    const StepExtent& step_extent() const { return step_extent_; }  // unit zoom only

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
    OffsetExtent offset_extent_;
    StepExtent step_extent_;
};

}  // namespace filmgrain::physical

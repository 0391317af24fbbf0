// A single-channel float image, values normalised so that 0 is black and 1 is full scale.
// The physical model and the statistics work on these; conversion from/to integer
// planes (8..16 bit) happens at the edges.
#pragma once
#include <cstdint>
#include <vector>

#include "filmgrain/frame.hpp"

namespace filmgrain {

struct FloatPlane {
    int width = 0;
    int height = 0;
    std::vector<float> v;

    FloatPlane() = default;
    FloatPlane(int w, int h, float fill = 0.f) : width(w), height(h), v(std::size_t(w) * h, fill) {}
    float& at(int x, int y) { return v[std::size_t(y) * width + x]; }
    float at(int x, int y) const { return v[std::size_t(y) * width + x]; }
};

// Samples / (2^bit_depth - 1).
FloatPlane float_plane_from(const PlaneView& p, int bit_depth);
// Rounds value * (2^bit_depth - 1), clamped to the sample range.
void store_float_plane(const FloatPlane& f, const PlaneView& p, int bit_depth);

}  // namespace filmgrain

// Piecewise-linear scaling function of AV1 spec 7.18.3.4 / 7.18.3.5 (scale_lut).
// It maps a sample intensity to the strength (0..255) of the grain added there.
#pragma once
#include <cstdint>
#include <vector>

namespace filmgrain::av1 {

class ScalingLookup {
public:
    ScalingLookup() = default;

    // Builds the function from `count` (value, scaling) points, values strictly
    // increasing in 0..255. count == 0 gives a function that is 0 everywhere.
    ScalingLookup(const int* point_value, const int* point_scaling, int count, int bit_depth);
    // The same, rebuilding this object in place (reusing its storage).
    void assign(const int* point_value, const int* point_scaling, int count, int bit_depth);

    // scale_lut(plane, index) for index in 0..(1 << bit_depth) - 1.
    int operator()(int index) const { return full_[static_cast<std::size_t>(index)]; }

    // The 256-entry 8-bit table (ScalingLut[plane] in the spec).
    const std::vector<uint8_t>& table8() const { return lut8_; }
    int bit_depth() const { return bit_depth_; }

private:
    int bit_depth_ = 8;
    std::vector<uint8_t> lut8_;
    std::vector<uint8_t> full_;  // precomputed scale_lut over the whole bit-depth range
};

}  // namespace filmgrain::av1

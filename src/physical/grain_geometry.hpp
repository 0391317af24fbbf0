// A grain, and the coverage test every estimator makes, in the float frame of a bin.
#pragma once
#include <cstdint>

namespace filmgrain::physical {

// floor() for the bin look-up without a libm call.
inline int64_t floor_to_int(double v) {
    const int64_t t = int64_t(v);
    return t - (double(t) > v);
}

struct Grain {
    double x, y, r2;
};

// The coverage test is made in the frame of the bin that holds the sample point: point and
// grain centre relative to that bin's corner, in bin units, rounded to float. Bin corners
// are global (a multiple of 1/cells_per_pixel), so the rounding depends on the point and the
// grain only, never on the tile or the thread; and the pixel-wise and grain-wise estimators
// both call these helpers, so they still agree exactly. Float halves the memory a bin
// occupies, which is what the pixel-wise look-up is bound by.
struct BinnedGrain {
    float x, y, r2;  // centre relative to the bin corner, squared radius, in bin units
};

inline float bin_local(double scaled, int64_t bin) { return float(scaled - double(bin)); }
inline float r2_in_bins(double r2, double cells_per_pixel) { return float(r2 * (cells_per_pixel * cells_per_pixel)); }
inline bool inside_grain(float lx, float ly, float gx, float gy, float r2) {
    const float dx = lx - gx, dy = ly - gy;
    return dx * dx + dy * dy <= r2;
}

}  // namespace filmgrain::physical

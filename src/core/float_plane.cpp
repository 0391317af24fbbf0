#include "core/float_plane.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain {

FloatPlane float_plane_from(const PlaneView& p, int bit_depth) {
    FloatPlane f(p.width, p.height);
    const float scale = 1.f / float((1 << bit_depth) - 1);
    for (int y = 0; y < p.height; y++)
        for (int x = 0; x < p.width; x++)
            f.at(x, y) = (bit_depth > 8 ? float(p.row<const uint16_t>(y)[x]) : float(p.row<const uint8_t>(y)[x])) * scale;
    return f;
}

void store_float_plane(const FloatPlane& f, const PlaneView& p, int bit_depth) {
    const float maxv = float((1 << bit_depth) - 1);
    for (int y = 0; y < p.height; y++)
        for (int x = 0; x < p.width; x++) {
            const float s = f.at(x, y);
            const long q = std::isfinite(s) ? std::lround(std::clamp(s * maxv, 0.f, maxv)) : 0;
            if (bit_depth > 8)
                p.row<uint16_t>(y)[x] = uint16_t(q);
            else
                p.row<uint8_t>(y)[x] = uint8_t(q);
        }
}

}  // namespace filmgrain

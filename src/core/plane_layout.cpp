#include "core/plane_layout.hpp"

#include <cstdint>
#include <cstdio>
#include <string>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain {

void check_plane_layout(const FrameView& v, const std::string& name) {
    if (v.width <= 0 || v.height <= 0) return;
    const int bps = v.bytes_per_sample();
    for (int p = 0; p < v.plane_count(); p++) {
        const PlaneView& pl = v.planes[p];
        const std::string idx = indexed("", p);
        const unsigned long long rows = static_cast<unsigned long long>(plane_height(v.format, p, v.height));
        const unsigned long long row = static_cast<unsigned long long>(plane_width(v.format, p, v.width)) * unsigned(bps);
        if (rows > 1) {
            // The magnitude in unsigned arithmetic: -PTRDIFF_MIN does not fit a ptrdiff_t.
            const unsigned long long mag =
                pl.stride < 0 ? 0ULL - static_cast<unsigned long long>(pl.stride) : static_cast<unsigned long long>(pl.stride);
            const unsigned long long most = (static_cast<unsigned long long>(PTRDIFF_MAX) - row) / (rows - 1);
            if (mag < row || mag > most)
                throw Error(ErrorCode::kInvalidArgument,
                            name + ".strides" + idx + " = " + std::to_string(pl.stride) + " is out of range (allowed " +
                                std::to_string(row) + ".." + std::to_string(most) + " or -" + std::to_string(most) +
                                "..-" + std::to_string(row) + ": at least a row of the plane, " + std::to_string(row) +
                                " bytes, and its " + std::to_string(rows) + " rows within PTRDIFF_MAX bytes)");
        }
        if (bps == 2) {
            const auto address = reinterpret_cast<std::uintptr_t>(pl.data);
            if (address & 1) {
                char hex[32];
                std::snprintf(hex, sizeof hex, "%#llx", static_cast<unsigned long long>(address));
                throw Error(ErrorCode::kInvalidArgument,
                            name + ".planes" + idx + " = " + hex + " is an odd address: " + std::to_string(v.bit_depth) +
                                "-bit samples are uint16_t and must be 2-byte aligned (allowed: even addresses)");
            }
            if (rows > 1 && (pl.stride & 1))
                throw Error(ErrorCode::kInvalidArgument,
                            name + ".strides" + idx + " = " + std::to_string(pl.stride) + " is odd: " +
                                std::to_string(v.bit_depth) +
                                "-bit samples are uint16_t and every row must be 2-byte aligned (allowed: even strides)");
        }
    }
}

}  // namespace filmgrain

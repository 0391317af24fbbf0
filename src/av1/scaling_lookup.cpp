// AV1 spec 7.18.3.4 (scaling lookup initialization) and scale_lut() of 7.18.3.5.
#include "av1/scaling_lookup.hpp"

namespace filmgrain::av1 {

ScalingLookup::ScalingLookup(const int* point_value, const int* point_scaling, int count, int bit_depth) {
    assign(point_value, point_scaling, count, bit_depth);
}

void ScalingLookup::assign(const int* point_value, const int* point_scaling, int count, int bit_depth) {
    if (count == built_count_ && bit_depth == bit_depth_ && !full_.empty() &&
        std::equal(point_value, point_value + count, built_value_.begin()) &&
        std::equal(point_scaling, point_scaling + count, built_scaling_.begin()))
        return;
    built_count_ = -1;
    if (count >= 0 && count <= kMaxKeptPoints) {
        std::copy_n(point_value, count, built_value_.begin());
        std::copy_n(point_scaling, count, built_scaling_.begin());
    }
    // assign() keeps the vectors' capacity, so rebuilding per frame does not allocate.
    bit_depth_ = bit_depth;
    lut8_.assign(256, 0);
    full_.assign(static_cast<std::size_t>(1) << bit_depth, 0);
    if (count > 0) {
        // Constant before the first point and after the last one.
        for (int x = 0; x < point_value[0]; ++x) lut8_[static_cast<std::size_t>(x)] = static_cast<uint8_t>(point_scaling[0]);
        // Between points: a 16.16 fixed-point slope with a rounded reciprocal of
        // the run, so the result is integer-exact across implementations.
        for (int i = 0; i + 1 < count; ++i) {
            const int delta_y = point_scaling[i + 1] - point_scaling[i];
            const int delta_x = point_value[i + 1] - point_value[i];
            const int delta = delta_y * ((65536 + (delta_x >> 1)) / delta_x);
            for (int x = 0; x < delta_x; ++x) {
                const int v = point_scaling[i] + ((x * delta + 32768) >> 16);
                lut8_[static_cast<std::size_t>(point_value[i] + x)] = static_cast<uint8_t>(v);
            }
        }
        for (int x = point_value[count - 1]; x < 256; ++x)
            lut8_[static_cast<std::size_t>(x)] = static_cast<uint8_t>(point_scaling[count - 1]);
    }

    // Above 8 bits the table is indexed by the top 8 bits and the low bits
    // interpolate linearly towards the next entry (the last entry has no
    // successor and is used as is).
    const int shift = bit_depth - 8;
    for (int index = 0; index < (1 << bit_depth); ++index) {
        const int x = index >> shift;
        const int rem = index - (x << shift);
        int v;
        if (shift == 0 || x == 255) {
            v = lut8_[static_cast<std::size_t>(x)];
        } else {
            const int start = lut8_[static_cast<std::size_t>(x)];
            const int end = lut8_[static_cast<std::size_t>(x + 1)];
            v = start + (((end - start) * rem + (1 << (shift - 1))) >> shift);
        }
        full_[static_cast<std::size_t>(index)] = static_cast<uint8_t>(v);
    }

    full_chain_.assign(shift > 0 ? full_.size() : 0, 0);
    for (std::size_t i = 0; i < full_chain_.size(); ++i)
        full_chain_[i] = static_cast<uint8_t>(full_[i] ^ (i + 16 < full_.size() ? full_[i + 16] : 0));
    for (std::size_t i = 0; i < 256; ++i) next8_[i] = lut8_[i < 255 ? i + 1 : 255];
    for (std::size_t i = 0; i < 256; ++i) {
        const bool chained = (i >> 4) % 8 != 7;
        lut8_chain_[i] = static_cast<uint8_t>(lut8_[i] ^ (chained ? lut8_[i + 16] : 0));
        next8_chain_[i] = static_cast<uint8_t>(next8_[i] ^ (chained ? next8_[i + 16] : 0));
    }
    if (count >= 0 && count <= kMaxKeptPoints) built_count_ = count;
}

}  // namespace filmgrain::av1

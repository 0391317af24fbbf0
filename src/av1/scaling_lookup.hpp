// Piecewise-linear scaling function of AV1 spec 7.18.3.4 / 7.18.3.5 (scale_lut).
// It maps a sample intensity to the strength (0..255) of the grain added there.
#pragma once
#include <algorithm>
#include <array>
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

    // scale_lut(plane, index) for index in 0..(1 << bit_depth) - 1. Larger indices (samples
    // beyond the declared bit depth: bad input nobody scans for) read the last entry rather
    // than past the table.
    int operator()(int index) const {
        return full_[std::min(static_cast<std::size_t>(index), full_.size() - 1)];
    }

    // The 256-entry 8-bit table (ScalingLut[plane] in the spec).
    const std::vector<uint8_t>& table8() const { return lut8_; }
    // scale_lut over 0..(1 << bit_depth) - 1, one byte each.
    const uint8_t* full_table() const { return full_.data(); }

    // ScalingLut laid out for the optimized blends' 16-entry byte shuffles
    // (simd/av1_kernels), made here once per parameter set rather than per row:
    // next8(): ScalingLut[min(i + 1, 255)], the end point of scale_lut's interpolation above
    // 8 bits; *_chain(): row j XOR row j + 1 for j % 8 != 7 (row j itself at 7 and 15), so
    // that XOR-ing every row's shuffle by an index raised by 16 per row (zero once it
    // saturates past 127) cancels all rows but the index's own.
    const uint8_t* next8() const { return next8_.data(); }
    const uint8_t* lut8_chain() const { return lut8_chain_.data(); }
    // The full table's rows XOR'd the same way over windows of 16 rows: entry i is
    // full_table()[i] ^ full_table()[i + 16] (the last row: itself), so that a chain over rows
    // base..base + 15 reads this table but at the two rows that end its halves (base + 7 and
    // base + 15), which it reads from full_table() (above 8 bits only; empty at 8).
    const uint8_t* full_chain() const { return full_chain_.data(); }
    const uint8_t* next8_chain() const { return next8_chain_.data(); }
    int bit_depth() const { return bit_depth_; }

private:
    int bit_depth_ = 8;
    std::vector<uint8_t> lut8_;
    std::vector<uint8_t> full_;  // precomputed scale_lut over the whole bit-depth range
    std::vector<uint8_t> full_chain_;
    std::array<uint8_t, 256> next8_{}, lut8_chain_{}, next8_chain_{};
    // The points the tables were built from: a stream usually repeats them frame after
    // frame (only the seed changes), and then assign() has nothing to rebuild.
    static constexpr int kMaxKeptPoints = 16;
    int built_count_ = -1;
    std::array<int, kMaxKeptPoints> built_value_{}, built_scaling_{};
};

}  // namespace filmgrain::av1

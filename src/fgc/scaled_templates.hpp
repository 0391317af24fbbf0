// The templates of one component's intensity intervals already scaled for blending: for each
// interval and block sign, (sign * scale * template) >> (log2_scale_factor + 6) (RDD 5 4.3,
// TR 23002-9 7.3.2) as int16, and one table of zeros. The optimized stripes then copy a block's rows instead of
// multiplying every sample of every block; the values are the ones the reference computes
// per sample, so the output is unchanged.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fgc/params_resolution.hpp"
#include "fgc/template_generation.hpp"

namespace filmgrain::fgc {

class ScaledTemplates {
public:
    // Two 8 KiB tables per interval: above this count a component's blocks are scaled as
    // they are used instead, which keeps the memory of a context near that of its raw
    // templates whatever the SEI signals (up to 256 intervals per component).
    static constexpr int kMaxIntervals = 16;

    // Makes the tables for `comp` (whose templates `cache` holds) unless they are already
    // there for the same scales, cut-offs and shift: allocates only when the parameters
    // change. Returns false, keeping nothing, when the component has more than
    // kMaxIntervals intervals. Not thread-safe: call before the stripes run.
    bool update(const ResolvedComponent& comp, const TemplateCache& cache, int shift);

    // Whether every value fits int8 (always so for 8-bit video, where |grain| <= 126): the
    // tables are then held as int8, half the size, so that the tables of a component's
    // intervals stay in the first-level cache while its stripes copy block rows out of them.
    bool narrow() const { return !narrow_data_.empty(); }

    // One more interval after the signalled ones is all zeros: blocks in no interval take
    // their (zero) grain from it like any other block, so the stripe needs no branch.
    int zero_interval() const { return int(keys_.size()); }

    // Row 0 of interval `interval`'s table for the sign of LFSR state bit 0 (`negative`);
    // rows are 64 values apart, as in the raw template. table<int8_t> when narrow(), else
    // table<int16_t>.
    template <typename T>
    const T* table(int interval, uint32_t negative) const {
        const std::size_t at = (std::size_t(interval) * 2 + negative) * kTemplateSize * kTemplateSize;
        if constexpr (sizeof(T) == 1)
            return narrow_data_.data() + at;
        else
            return data_.data() + at;
    }
    std::size_t bytes() const { return data_.capacity() * sizeof(int16_t) + narrow_data_.capacity(); }

private:
    struct Key {
        int scale, cutoff_h, cutoff_v;
        bool operator==(const Key&) const = default;
    };
    std::vector<Key> keys_;
    int shift_ = -1;
    bool valid_ = false;
    std::vector<int16_t> data_;        // empty when narrow
    std::vector<int8_t> narrow_data_;  // empty when not narrow
};

}  // namespace filmgrain::fgc

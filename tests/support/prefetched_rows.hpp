// The rows an FGC blend kernel prefetches (fgc::simd::NextStripeRow: the next stripe's row
// to read and its row to write), for the equivalence tests: each given or not as the test
// picks, the one to write filled with a marker that prefetching must leave as it is.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

#include "fgc/simd/fgc_kernels.hpp"

namespace filmgrain::test_support {

template <typename Pixel>
class PrefetchedRows {
public:
    explicit PrefetchedRows(std::size_t samples) : read_(samples), written_(samples, kMarker) {}
    // each row given where coin() says so (first the row to read, then the one to write)
    template <class Coin>
    fgc::simd::NextStripeRow<Pixel> pick(Coin&& coin) {
        const bool read = coin();
        const bool write = coin();
        return {read ? read_.data() : nullptr, write ? written_.data() : nullptr};
    }
    bool untouched() const {
        return std::all_of(written_.begin(), written_.end(), [](Pixel v) { return v == kMarker; });
    }

private:
    static constexpr Pixel kMarker = Pixel(0x5A);
    std::vector<Pixel> read_, written_;
};

}  // namespace filmgrain::test_support

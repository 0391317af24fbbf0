// The colour term of FGC model 1 (fgc/colour_correlation.hpp): the per-subsampling form
// equals the reference on random grain and p1 values, for every subsampling and for plane
// sizes whose co-located samples cross the previous plane's last column and row.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "fgc/colour_correlation.hpp"

namespace filmgrain::fgc {
namespace {

TEST(ColourCorrelation, EqualsTheReferenceForEverySubsampling) {
    std::mt19937 rng(2024);
    std::uniform_int_distribution<int> grain_value(-4096, 4095), p1(-128, 127), coin(0, 3);
    for (int sx = 0; sx <= 1; sx++)
        for (int sy = 0; sy <= 1; sy++)
            for (int pw : {1, 2, 7, 64, 65})
                for (int ph : {1, 3, 32, 33}) {
                    SCOPED_TRACE(testing::Message() << "shift " << sx << "," << sy << " previous " << pw << "x" << ph);
                    std::vector<int32_t> prev(std::size_t(pw) * ph);
                    for (auto& v : prev) v = grain_value(rng);
                    const PreviousGrain previous{prev.data(), pw, ph, sx, sy};
                    // this component's size: the subsampled size, rounded up, plus a column
                    // and a row past it (a stripe's padding reaches there)
                    const int width = ((pw + (1 << sx) - 1) >> sx) + 1, height = ((ph + (1 << sy) - 1) >> sy) + 1;
                    const int stride = width + 2;
                    for (int L : {2, 5, 7})
                        for (int y0 : {0, height / 2}) {
                            const int rows = height - y0;
                            std::vector<int16_t> rho(std::size_t(stride) * rows);
                            for (auto& r : rho) r = int16_t(coin(rng) ? p1(rng) : 0);  // some samples without the term
                            std::vector<int32_t> ref(std::size_t(stride) * rows), opt;
                            for (auto& g : ref) g = grain_value(rng);
                            opt = ref;
                            add_colour_correlation_reference(previous, L, y0, rows, width, ref.data(), rho.data(), stride);
                            add_colour_correlation(previous, L, y0, rows, width, opt.data(), rho.data(), stride);
                            ASSERT_EQ(opt, ref) << "L " << L << " y0 " << y0;
                        }
                }
}

// The reference itself, on a hand-computed case: 4:2:0, the rounded mean of the 2x2 luma grain.
TEST(ColourCorrelation, ReferenceAddsTheRoundedCoLocatedMean) {
    const std::vector<int32_t> luma = {1, 2, 3, 4,  //
                                       5, 6, 7, 8};
    const PreviousGrain previous{luma.data(), 4, 2, 1, 1};
    std::vector<int32_t> grain = {10, 20};
    const std::vector<int16_t> rho = {32, -32};
    add_colour_correlation_reference(previous, 5, 0, 1, 2, grain.data(), rho.data(), 2);
    // co-located means (1+2+5+6+2)>>2 = 4 and (3+4+7+8+2)>>2 = 6; p1 32/32 = 1 and -1
    EXPECT_EQ(grain, (std::vector<int32_t>{14, 14}));
}

}  // namespace
}  // namespace filmgrain::fgc

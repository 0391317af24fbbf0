// Grain templates of the FGC auto-regressive model (film_grain_model_id = 1, TR 23002-9
// 7.4.1 and its Figure 18; the VSEI film grain characteristics semantics).
//
// The model (all values in units of 2^-log2_scale_factor, L below):
//
//   G[c][x][y] = sigma * n
//              + p0 * (G[c][x-1][y] + A * G[c][x][y-1])          p0 = comp_model_value[1]
//              + p2 * A * (G[c][x-1][y-1] + G[c][x+1][y-1])        p2 = comp_model_value[3]
//              + p3 * (G[c][x-2][y] + A * A * G[c][x][y-2])         p3 = comp_model_value[5]
//              + p1 * G[c-1][x][y]                                  p1 = comp_model_value[2]
//
// with A = comp_model_value[4] the aspect ratio and sigma = comp_model_value[0]. Values not
// sent take p = 0 and A = 1 (1 << L). The spatial part is a causal filter: it is run here
// over a buffer larger than the template, from a zero start, and the 64x64 template is
// cropped away from the start-up edges. sigma scales the template at synthesis, and the
// colour term p1 needs the other component's grain, so both are synthesis stages (see
// reference_stripe); the template is the grain of sigma = 1 without the colour term.
//
// The filter arithmetic is the VersatileFilmGrain reference's (82x73 buffer, 3 samples of
// filter support, crop at (9, 9), weights rounded to 1/2^L, half-amplitude Gaussian noise,
// +-127 clip): the vfgs flavour runs it with its own random source and is bit-exact with
// the reference; the tr flavour runs the same filter with the RDD 5 random source.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "fgc/grain_template.hpp"

namespace filmgrain::fgc {

// Value completion for film_grain_model_id = 1 when `num_values` (1..6) are signalled:
// p0, p1, p2, p3 default to 0 and A to 1, i.e. 1 << log2_scale_factor.
std::array<int, 6> complete_ar_model_values(const std::array<int, 6>& signalled, int num_values,
                                            int log2_scale_factor);

// Weights of the causal neighbours in 1/2^L, from completed model values (TR Figure 18):
// left p0, top p0*A, top-left and top-right p2*A, left-left p3, top-top p3*A*A.
struct ArWeights {
    int left = 0, top = 0, diag = 0, left2 = 0, top2 = 0;
    int log2_scale_factor = 1;
};
ArWeights ar_weights(const std::array<int, 6>& value, int log2_scale_factor);

// Runs the filter with the noise that `next_noise()` returns sample by sample in raster
// order over the work buffer, and crops the template.
template <typename NoiseSource>
GrainTemplate make_ar_template(const ArWeights& w, NoiseSource&& next_noise) {
    constexpr int kW = 82, kH = 73, kMargin = 3, kCrop = 9;
    const int L = w.log2_scale_factor;
    std::vector<int> buf(static_cast<std::size_t>(kW) * kH, 0);
    auto at = [&](int y, int x) { return buf[static_cast<std::size_t>(y) * kW + x]; };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            int g = 0;
            if (y >= kMargin && x >= kMargin && x < kW - kMargin) {
                const int sum = w.left * at(y, x - 1) + w.left2 * at(y, x - 2) + w.top * at(y - 1, x) +
                                w.diag * (at(y - 1, x - 1) + at(y - 1, x + 1)) + w.top2 * at(y - 2, x);
                g = (sum + (1 << (L - 1))) >> L;
            }
            g += next_noise();
            buf[static_cast<std::size_t>(y) * kW + x] = g < -127 ? -127 : (g > 127 ? 127 : g);
        }
    GrainTemplate t{};
    for (int y = 0; y < kTemplateSize; ++y)
        for (int x = 0; x < kTemplateSize; ++x) t[y][x] = static_cast<int8_t>(at(kCrop + y, kCrop + x));
    return t;
}

// The tr flavour's template: the filter driven by the RDD 5 generator (Gaussian_LUT read at
// the 32-bit LFSR state, one step per sample, half amplitude) started from
// Seed_LUT[seed_index]; the flavour uses seed index c for colour component c.
GrainTemplate make_ar_template_rdd5_noise(const std::array<int, 6>& value, int log2_scale_factor, int seed_index);

}  // namespace filmgrain::fgc

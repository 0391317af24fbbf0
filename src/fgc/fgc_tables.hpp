// Constant tables of the FGC frequency-filtering model.
#pragma once
#include <array>
#include <cstdint>

namespace filmgrain::fgc {

extern const int8_t kGaussianLut[2048];
extern const uint32_t kSeedLut[256];
extern const int8_t kRdd5Idct64[64][64];

// Scale applied to the first and last row of each block inside a template, indexed by
// vertical cut-off - 2 (RDD 5 vertical pre-deblocking, in units of 1/128).
inline constexpr uint8_t kDeblockFactor[13] = {64, 71, 77, 84, 90, 96, 103, 109, 116, 122, 128, 128, 128};

// The VVC 64-point DCT-2 integer matrix (H.266 8.7.4.5), row = frequency k, column = n.
// Every entry is +-C(m) for the folded angle m of k(2n+1)pi/128; C lists the coefficients
// the standard gives for cos(m*pi/128) at 64*sqrt(2) scale.
namespace detail {
constexpr std::array<std::array<int16_t, 64>, 64> make_vvc_dct2_64() {
    constexpr int odd64[32] = {91, 90, 90, 90, 88, 87, 86, 84, 83, 81, 79, 77, 73, 71, 69, 65,
                               62, 59, 56, 52, 48, 44, 41, 37, 33, 28, 24, 20, 15, 11, 7,  2};
    constexpr int odd32[16] = {90, 90, 88, 85, 82, 78, 73, 67, 61, 54, 46, 38, 31, 22, 13, 4};
    constexpr int odd16[8] = {90, 87, 80, 70, 57, 43, 25, 9};
    constexpr int odd8[4] = {89, 75, 50, 18};
    int c[65] = {};
    c[0] = 64; c[32] = 64; c[16] = 83; c[48] = 36; c[64] = 0;
    for (int j = 0; j < 4; j++) c[8 * (2 * j + 1)] = odd8[j];
    for (int j = 0; j < 8; j++) c[4 * (2 * j + 1)] = odd16[j];
    for (int j = 0; j < 16; j++) c[2 * (2 * j + 1)] = odd32[j];
    for (int j = 0; j < 32; j++) c[2 * j + 1] = odd64[j];
    std::array<std::array<int16_t, 64>, 64> m{};
    for (int k = 0; k < 64; k++)
        for (int n = 0; n < 64; n++) {
            if (k == 0) { m[k][n] = 64; continue; }
            int t = (k * (2 * n + 1)) % 256;
            int v = t <= 64 ? c[t] : t <= 128 ? -c[128 - t] : t <= 192 ? -c[t - 128] : c[256 - t];
            m[k][n] = int16_t(v);
        }
    return m;
}
}  // namespace detail

inline constexpr std::array<std::array<int16_t, 64>, 64> kVvcDct2_64 = detail::make_vvc_dct2_64();

}  // namespace filmgrain::fgc

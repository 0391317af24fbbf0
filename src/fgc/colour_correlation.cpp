#include "fgc/colour_correlation.hpp"

#include <algorithm>
#include <cstddef>

namespace filmgrain::fgc {

bool has_colour_correlation(const ResolvedFgc& params, int c) {
    if (params.cancelled || params.model_id != 1 || c == 0 || !params.comp[c].present || !params.comp[c - 1].present)
        return false;
    return std::any_of(params.comp[c].intervals.begin(), params.comp[c].intervals.end(),
                       [](const ResolvedInterval& ri) { return ri.ar[2] != 0; });
}

void add_colour_correlation_reference(const PreviousGrain& previous, int log2_scale_factor, int y0, int rows, int width,
                                      int32_t* grain, const int16_t* rho, int stride) {
    const int sx = previous.shift_x, sy = previous.shift_y, n_shift = sx + sy;
    const int L = log2_scale_factor;
    const int pw = previous.width, ph = previous.height;
    for (int l = 0; l < rows; l++) {
        const int y = y0 + l;
        int32_t* g = grain + std::size_t(l) * stride;
        const int16_t* r = rho + std::size_t(l) * stride;
        for (int x = 0; x < width; x++) {
            if (!r[x]) continue;
            int32_t sum = 0;
            for (int j = 0; j < (1 << sy); j++)
                for (int i = 0; i < (1 << sx); i++)
                    sum += previous.grain[std::size_t(std::min((y << sy) + j, ph - 1)) * pw +
                                          std::min((x << sx) + i, pw - 1)];
            const int32_t co = n_shift ? (sum + (1 << (n_shift - 1))) >> n_shift : sum;
            g[x] += (r[x] * co + (1 << (L - 1))) >> L;
        }
    }
}

namespace {

// The term for one subsampling (SX, SY: the previous plane's samples per sample are 2^SX by
// 2^SY). The co-located rows are clamped once per row, the columns only past `inside`.
template <int SX, int SY>
void add_term(const PreviousGrain& previous, int L, int y0, int rows, int width, int32_t* grain, const int16_t* rho,
              int stride) {
    constexpr int n_shift = SX + SY;
    const int pw = previous.width, ph = previous.height;
    // columns whose 2^SX co-located samples all lie inside the previous plane
    const int inside = pw >= (1 << SX) ? std::min(width, (pw - (1 << SX)) / (1 << SX) + 1) : 0;
    for (int l = 0; l < rows; l++) {
        const int y = y0 + l;
        const int32_t* p0 = previous.grain + std::size_t(std::min(y << SY, ph - 1)) * pw;
        const int32_t* p1 = SY ? previous.grain + std::size_t(std::min((y << SY) + 1, ph - 1)) * pw : p0;
        int32_t* g = grain + std::size_t(l) * stride;
        const int16_t* r = rho + std::size_t(l) * stride;
        const auto add = [&](int x, int32_t sum) {
            const int32_t co = n_shift ? (sum + (1 << (n_shift - 1))) >> n_shift : sum;
            g[x] += (r[x] * co + (1 << (L - 1))) >> L;
        };
        for (int x = 0; x < inside; x++) {
            if (!r[x]) continue;
            const int px = x << SX;
            int32_t sum = p0[px];
            if (SX) sum += p0[px + 1];
            if (SY) sum += p1[px];
            if (SX && SY) sum += p1[px + 1];
            add(x, sum);
        }
        for (int x = inside; x < width; x++) {
            if (!r[x]) continue;
            int32_t sum = 0;
            for (int i = 0; i < (1 << SX); i++) {
                const int px = std::min((x << SX) + i, pw - 1);
                sum += p0[px] + (SY ? p1[px] : 0);
            }
            add(x, sum);
        }
    }
}

}  // namespace

void add_colour_correlation(const PreviousGrain& previous, int log2_scale_factor, int y0, int rows, int width,
                            int32_t* grain, const int16_t* rho, int stride) {
    const auto run = [&](auto term) { term(previous, log2_scale_factor, y0, rows, width, grain, rho, stride); };
    switch (previous.shift_x * 2 + previous.shift_y) {
        case 0: return run(add_term<0, 0>);
        case 1: return run(add_term<0, 1>);
        case 2: return run(add_term<1, 0>);
        default: return run(add_term<1, 1>);
    }
}

}  // namespace filmgrain::fgc

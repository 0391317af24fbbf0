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

void add_colour_correlation(const PreviousGrain& previous, int log2_scale_factor, int y0, int rows, int width,
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

}  // namespace filmgrain::fgc

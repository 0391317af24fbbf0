#include "fgc/deblocking.hpp"

#include "fgc/fgc_tables.hpp"

namespace filmgrain::fgc {

void deblock_stripe_vertical_edges(int32_t* grain, int stride, int rows, int width, int block_size,
                                   const uint8_t* right_has_grain) {
    for (int y = 0; y < rows; y++) {
        int32_t* row = grain + std::ptrdiff_t(y) * stride;
        for (int e = block_size, k = 1; e < width; e += block_size, k++) {
            if (right_has_grain && !right_has_grain[k]) continue;
            const int32_t l1 = row[e - 2], l0 = row[e - 1], r0 = row[e], r1 = row[e + 1];
            row[e] = (l0 + (r0 << 1) + r1) >> 2;
            row[e - 1] = (l1 + (l0 << 1) + r0) >> 2;
        }
    }
}

void predeblock_template_rows(GrainTemplate& t, int cutoff_v, int block_size) {
    const int factor = kDeblockFactor[cutoff_v - 2];
    for (int l = 0; l < kTemplateSize; l += block_size)
        for (int k = 0; k < kTemplateSize; k++) {
            t[l][k] = int8_t((t[l][k] * factor) >> 7);
            t[l + block_size - 1][k] = int8_t((t[l + block_size - 1][k] * factor) >> 7);
        }
}

}  // namespace filmgrain::fgc

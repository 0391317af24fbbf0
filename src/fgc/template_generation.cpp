#include "fgc/template_generation.hpp"

#include <algorithm>
#include <cstring>

#include "fgc/fgc_tables.hpp"
#include "fgc/pseudo_random.hpp"

namespace filmgrain::fgc {

void fill_template_coefficients(int cutoff_h, int cutoff_v, int32_t coeff[kTemplateSize][kTemplateSize]) {
    std::memset(coeff, 0, sizeof(int32_t) * kTemplateSize * kTemplateSize);
    const int h = cutoff_h - 2, v = cutoff_v - 2;
    const int last_h = 4 * (h + 3) - 1;  // = 4 * (cutoff_h + 1) - 1
    const int last_v = 4 * (v + 3) - 1;
    uint32_t rnd = kSeedLut[h + 13 * v];
    // coeff[k][l]: k horizontal frequency, l vertical; the LFSR steps once per group of 4.
    for (int l = 0; l <= last_v; l++)
        for (int k = 0; k <= last_h; k += 4) {
            for (int j = 0; j < 4; j++) coeff[k + j][l] = kGaussianLut[(rnd + j) % 2048];
            rnd = lfsr_next(rnd);
        }
    coeff[0][0] = 0;
}

void inverse_transform_template(const int32_t coeff[kTemplateSize][kTemplateSize], TemplateTransform transform,
                                GrainTemplate& out) {
    const bool vvc = transform == TemplateTransform::kVvcDct2;
    const int shift = vvc ? 9 : 8;
    const int32_t round = 1 << (shift - 1);
    auto m = [&](int freq, int pos) -> int32_t {
        return vvc ? kVvcDct2_64[freq][pos] : kRdd5Idct64[freq][pos];
    };
    // First pass over the horizontal frequency index k: tmp[i][j] = sum_k M[k][i] * coeff[k][j].
    static_assert(kTemplateSize == 64);
    std::array<std::array<int32_t, 64>, 64> tmp;
    for (int i = 0; i < 64; i++)
        for (int j = 0; j < 64; j++) {
            int32_t s = 0;
            for (int k = 0; k < 64; k++) s += m(k, i) * coeff[k][j];
            tmp[i][j] = (s + round) >> shift;
        }
    // Second pass over the vertical frequency: grain[i][j] = sum_k tmp[i][k] * M[k][j];
    // i is the horizontal position and j the vertical one, so the template row is j.
    for (int i = 0; i < 64; i++)
        for (int j = 0; j < 64; j++) {
            int32_t s = 0;
            for (int k = 0; k < 64; k++) s += tmp[i][k] * m(k, j);
            s = (s + round) >> shift;
            out[j][i] = int8_t(std::clamp(s, -127, 127));
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

GrainTemplate make_grain_template(int cutoff_h, int cutoff_v, TemplateTransform transform, int block_size) {
    int32_t coeff[kTemplateSize][kTemplateSize];  // 16 KiB on the stack; no shared scratch
    fill_template_coefficients(cutoff_h, cutoff_v, coeff);
    GrainTemplate t;
    inverse_transform_template(coeff, transform, t);
    predeblock_template_rows(t, cutoff_v, block_size);
    return t;
}

const GrainTemplate& TemplateCache::ensure(int h, int v) {
    auto& slot = slots_[index(h, v)];
    if (!slot) slot = std::make_unique<GrainTemplate>(make_grain_template(h, v, transform_, block_size_));
    return *slot;
}

int TemplateCache::built_count() const {
    return int(std::count_if(slots_.begin(), slots_.end(), [](const auto& s) { return s != nullptr; }));
}

void TemplateCache::reconfigure(TemplateTransform transform, int block_size) {
    if (transform == transform_ && block_size == block_size_) return;
    transform_ = transform;
    block_size_ = block_size;
    for (auto& s : slots_) s.reset();
}

}  // namespace filmgrain::fgc

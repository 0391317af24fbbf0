#include "fgc/template_generation.hpp"

#include <algorithm>
#include <cstring>

#include "fgc/deblocking.hpp"
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

void inverse_transform_2d(const int32_t* coeff, int n, TemplateTransform transform, int matrix_step, int first_shift,
                          int second_shift, bool rows_follow_first_index, GrainTemplate& out) {
    const bool vvc = transform == TemplateTransform::kVvcDct2;
    auto m = [&](int freq, int pos) -> int32_t {
        return vvc ? kVvcDct2_64[freq * matrix_step][pos] : kRdd5Idct64[freq * matrix_step][pos];
    };
    static_assert(kTemplateSize == 64);
    // tmp[a][b]: position a along the first index, frequency b along the second.
    std::array<std::array<int32_t, kTemplateSize>, kTemplateSize> tmp;
    const int32_t round1 = 1 << (first_shift - 1), round2 = 1 << (second_shift - 1);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            int32_t s = round1;
            for (int k = 0; k < n; k++) s += m(k, a) * coeff[std::size_t(k) * std::size_t(n) + std::size_t(b)];
            tmp[std::size_t(a)][std::size_t(b)] = s >> first_shift;
        }
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            int32_t s = round2;
            for (int k = 0; k < n; k++) s += tmp[std::size_t(a)][std::size_t(k)] * m(k, b);
            const int8_t v = int8_t(std::clamp(s >> second_shift, -127, 127));
            if (rows_follow_first_index)
                out[std::size_t(a)][std::size_t(b)] = v;
            else
                out[std::size_t(b)][std::size_t(a)] = v;
        }
}

void inverse_transform_template(const int32_t coeff[kTemplateSize][kTemplateSize], TemplateTransform transform,
                                GrainTemplate& out) {
    // coeff[k][l]: k the horizontal frequency, so pass 1 is horizontal and the template row
    // is the second index's (vertical) position. RDD 5 rounds both passes by >> 8, HM's
    // VVC DCT-2 by >> 9.
    const int shift = transform == TemplateTransform::kVvcDct2 ? 9 : 8;
    inverse_transform_2d(&coeff[0][0], kTemplateSize, transform, 1, shift, shift, false, out);
}

GrainTemplate make_grain_template(int cutoff_h, int cutoff_v, TemplateTransform transform, int block_size) {
    int32_t coeff[kTemplateSize][kTemplateSize];  // 16 KiB on the stack; no shared scratch
    fill_template_coefficients(cutoff_h, cutoff_v, coeff);
    GrainTemplate t;
    inverse_transform_template(coeff, transform, t);
    if (block_size > 0) predeblock_template_rows(t, cutoff_v, block_size);  // 0: verify's "no deblocking"
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

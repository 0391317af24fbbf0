#include "fgc/ar_template_generation.hpp"

#include <algorithm>

#include "fgc/fgc_tables.hpp"
#include "fgc/pseudo_random.hpp"

namespace filmgrain::fgc {

std::array<int, 6> complete_ar_model_values(const std::array<int, 6>& signalled, int num_values,
                                            int log2_scale_factor) {
    std::array<int, 6> v = signalled;
    for (int k = std::max(num_values, 1); k < 6; k++) v[k] = 0;
    if (num_values < 5) v[4] = 1 << log2_scale_factor;  // aspect ratio 1: isotropic
    return v;
}

ArWeights ar_weights(const std::array<int, 6>& value, int log2_scale_factor) {
    const int L = log2_scale_factor;
    // 64-bit products: A is not range-limited by the syntax; for in-range values this is
    // the reference's int arithmetic.
    const long long a = value[4];
    ArWeights w;
    w.log2_scale_factor = L;
    w.left = value[1];
    w.top = static_cast<int>((value[1] * a) >> L);
    w.diag = static_cast<int>((value[3] * a) >> L);
    w.left2 = value[5];
    w.top2 = static_cast<int>((value[5] * a * a) >> (2 * L));
    return w;
}

GrainTemplate make_ar_template_rdd5_noise(const std::array<int, 6>& value, int log2_scale_factor, int seed_index) {
    uint32_t r = kSeedLut[seed_index & 0xFF];
    return make_ar_template(ar_weights(value, log2_scale_factor), [&r] {
        const int n = (kGaussianLut[r & 2047u] + 1) >> 1;
        r = lfsr_next(r);
        return n;
    });
}

}  // namespace filmgrain::fgc

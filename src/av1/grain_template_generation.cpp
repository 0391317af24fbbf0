// AV1 spec 7.18.3.3 (generate grain process).
#include "av1/grain_template_generation.hpp"

#include <algorithm>
#include <array>

#include "av1/gaussian_sequence.hpp"
#include "av1/random_number.hpp"

namespace filmgrain::av1 {
namespace {

// Round2 with an arithmetic shift, as the spec defines it for signed values.
inline int round2(int x, int n) { return n == 0 ? x : (x + (1 << (n - 1))) >> n; }

// Fills a template with scaled Gaussian numbers. The Gaussian sequence has
// 12-bit magnitude; shifting by 12 - BitDepth brings it to the frame's bit depth,
// and grain_scale_shift lowers the grain further.
void fill_white_noise(GrainTemplate& t, uint16_t seed, bool enabled, int bit_depth, int grain_scale_shift) {
    const int shift = 12 - bit_depth + grain_scale_shift;
    RandomNumberGenerator rng(seed);
    for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
            const int g = enabled ? kGaussianSequence[static_cast<std::size_t>(rng.get(11))] : 0;
            t.ref(y, x) = static_cast<int16_t>(round2(g, shift));
        }
}

// AV1 7.18.3.3: the causal auto-regressive filter over the white noise, in raster order:
// each sample takes the already-filtered neighbours of the rows above (full width 2*lag+1)
// and those to its left on its own row, weighted by the coefficients in that same scan
// order. `last_term(y, x, pos)` gives the term of coefficient `pos`, the one after them
// (chroma: the co-located luma grain; luma has no such coefficient and returns 0 unread).
template <std::size_t N, typename LastTerm>
void apply_ar_filter(GrainTemplate& t, const std::array<int, N>& coeffs_plus_128, int lag, int shift, int bit_depth,
                     LastTerm last_term) {
    const GrainRange r = grain_range(bit_depth);
    for (int y = kArPadding; y < t.height; ++y)
        for (int x = kArPadding; x < t.width - kArPadding; ++x) {
            int sum = 0, pos = 0;
            for (int dy = -lag; dy <= 0; ++dy)
                for (int dx = -lag; dx <= lag; ++dx) {
                    if (dy == 0 && dx == 0) {
                        sum += last_term(y, x, pos);
                        break;
                    }
                    sum += (coeffs_plus_128[static_cast<std::size_t>(pos++)] - 128) * t.at(y + dy, x + dx);
                }
            t.ref(y, x) = static_cast<int16_t>(std::clamp(t.at(y, x) + round2(sum, shift), r.min, r.max));
        }
}

}  // namespace

GrainTemplate generate_luma_template(const Av1FilmGrainParams& p, int bit_depth) {
    GrainTemplate t;
    generate_luma_template(p, bit_depth, t);
    return t;
}

void generate_luma_template(const Av1FilmGrainParams& p, int bit_depth, GrainTemplate& t) {
    t.width = kLumaTemplateWidth;
    t.height = kLumaTemplateHeight;
    t.samples.resize(static_cast<std::size_t>(kLumaTemplateWidth) * kLumaTemplateHeight);
    const bool enabled = p.num_y_points > 0;
    fill_white_noise(t, luma_template_seed(p.grain_seed), enabled, bit_depth, p.grain_scale_shift);
    if (!enabled) return;

    apply_ar_filter(t, p.ar_coeffs_y_plus_128, p.ar_coeff_lag, p.ar_coeff_shift_minus_6 + 6, bit_depth,
                    [](int, int, int) { return 0; });
}

GrainTemplate generate_chroma_template(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                                       int subsampling_y, const GrainTemplate& luma) {
    GrainTemplate t;
    generate_chroma_template(p, bit_depth, plane, subsampling_x, subsampling_y, luma, t);
    return t;
}

void generate_chroma_template(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                              int subsampling_y, const GrainTemplate& luma, GrainTemplate& t) {
    const int w = subsampling_x ? kSubsampledTemplateWidth : kLumaTemplateWidth;
    const int h = subsampling_y ? kSubsampledTemplateHeight : kLumaTemplateHeight;
    t.width = w;
    t.height = h;
    t.samples.resize(static_cast<std::size_t>(w) * h);

    const int num_points = plane == 1 ? p.num_cb_points : p.num_cr_points;
    const bool enabled = num_points > 0 || p.chroma_scaling_from_luma;
    const uint16_t seed = plane == 1 ? cb_template_seed(p.grain_seed) : cr_template_seed(p.grain_seed);
    fill_white_noise(t, seed, enabled, bit_depth, p.grain_scale_shift);
    if (!enabled) return;

    const auto& coeffs = plane == 1 ? p.ar_coeffs_cb_plus_128 : p.ar_coeffs_cr_plus_128;
    // The last coefficient couples chroma grain to the luma grain at the co-located position
    // (averaged over the subsampled luma samples), so that chroma grain can correlate with
    // luma grain. Absent without luma grain.
    const bool coupled = p.num_y_points > 0;
    apply_ar_filter(t, coeffs, p.ar_coeff_lag, p.ar_coeff_shift_minus_6 + 6, bit_depth, [&](int y, int x, int pos) {
        if (!coupled) return 0;
        int luma_sum = 0;
        const int ly = ((y - kArPadding) << subsampling_y) + kArPadding;
        const int lx = ((x - kArPadding) << subsampling_x) + kArPadding;
        for (int i = 0; i <= subsampling_y; ++i)
            for (int j = 0; j <= subsampling_x; ++j) luma_sum += luma.at(ly + i, lx + j);
        return round2(luma_sum, subsampling_x + subsampling_y) * (coeffs[static_cast<std::size_t>(pos)] - 128);
    });
}

}  // namespace filmgrain::av1

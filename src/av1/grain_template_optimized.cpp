// Optimized AV1 grain templates (7.18.3.3); see grain_template_optimized.hpp.
#include "av1/grain_template_optimized.hpp"

#include <algorithm>
#include <cstddef>

#include "av1/gaussian_sequence.hpp"
#include "av1/random_number.hpp"
#include "av1/simd/grain_ar_filter.hpp"

namespace filmgrain::av1 {
namespace {

// Gaussian_Sequence[get_random_number(11)] rounded by `shift`, for `count` samples in
// raster order. The spec's LFSR (7.18.3.2) feeds back bits 0, 1, 3 and 12: with the
// register holding stream bits b[t..t+15], a step appends b[t+16] = b[t] ^ b[t+1] ^
// b[t+3] ^ b[t+12]. F = r ^ r>>1 ^ r>>3 ^ r>>12 gives the next four bits directly (bits
// 0..3); bits 4..7 lack only their b[t+16..t+19] term, which is F's bits 0..3. So one
// update of a 24-bit window gives eight successive states, and the 11-bit number of the
// k-th of them is bits k + 6 .. k + 16 of the window (state >> 5 after k + 1 steps).
// The table is rounded once up front (2048 entries, a loop the compiler vectorizes) rather
// than per drawn sample: measured cheaper even for the 1672-sample 4:2:0 chroma templates.
void fill_gaussian_batched(int16_t* out, int count, uint16_t seed, int shift) {
    const int round = (1 << shift) >> 1;  // Round2(x, 0) is x
    int16_t table[kGaussianSequenceSize];
    for (int i = 0; i < kGaussianSequenceSize; ++i)
        table[i] = static_cast<int16_t>((kGaussianSequence[static_cast<std::size_t>(i)] + round) >> shift);
    auto scaled = [&](uint32_t index) { return table[index & 0x7ffu]; };
    uint32_t r = seed;
    int i = 0;
    for (; i + 8 <= count; i += 8) {
        const uint32_t f = r ^ (r >> 1) ^ (r >> 3) ^ (r >> 12);
        const uint32_t window = r | (((f ^ (f << 4)) & 0xffu) << 16);
        for (int k = 0; k < 8; ++k) out[i + k] = scaled(window >> (k + 6));
        r = window >> 8;
    }
    RandomNumberGenerator rng(static_cast<uint16_t>(r));
    for (; i < count; ++i) out[i] = scaled(static_cast<uint32_t>(rng.get(11)));
}

// As the reference: 12-bit Gaussian values brought to the bit depth, then lowered by
// grain_scale_shift; all zero (no random numbers drawn) for a plane without grain.
void fill_white_noise(GrainTemplate& t, uint16_t seed, bool enabled, int bit_depth, int grain_scale_shift) {
    const int count = t.width * t.height;
    if (!enabled) {
        std::fill(t.samples.begin(), t.samples.end(), int16_t{0});
        return;
    }
    fill_gaussian_batched(t.samples.data(), count, seed, 12 - bit_depth + grain_scale_shift);
}

void size_template(GrainTemplate& t, int width, int height) {
    t.width = width;
    t.height = height;
    t.samples.resize(static_cast<std::size_t>(width) * height);
}

simd::ArFilterJob ar_job(GrainTemplate& t, const Av1FilmGrainParams& p, int bit_depth, const int* coeffs) {
    simd::ArFilterJob j;
    j.grain = t.samples.data();
    j.width = t.width;
    j.height = t.height;
    j.coeffs = coeffs;
    j.lag = p.ar_coeff_lag;
    j.shift = p.ar_coeff_shift_minus_6 + 6;
    const GrainRange range = grain_range(bit_depth);
    j.grain_min = range.min;
    j.grain_max = range.max;
    return j;
}

}  // namespace

void generate_luma_template_optimized(const Av1FilmGrainParams& p, int bit_depth, GrainTemplate& t) {
    size_template(t, kLumaTemplateWidth, kLumaTemplateHeight);
    const bool enabled = p.num_y_points > 0;
    fill_white_noise(t, luma_template_seed(p.grain_seed), enabled, bit_depth, p.grain_scale_shift);
    if (!enabled) return;
    int coeffs[24];
    const int taps = 2 * p.ar_coeff_lag * (p.ar_coeff_lag + 1);
    for (int i = 0; i < taps; ++i) coeffs[i] = p.ar_coeffs_y_plus_128[static_cast<std::size_t>(i)] - 128;
    simd::ar_filter_template(ar_job(t, p, bit_depth, coeffs));
}

namespace {

// Sizes and fills a chroma template; returns whether the AR filter applies (the plane has
// grain), with its job set up over `coeffs`.
bool prepare_chroma(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x, int subsampling_y,
                    const GrainTemplate& luma, GrainTemplate& t, int (&coeffs)[25], simd::ArFilterJob& job) {
    size_template(t, subsampling_x ? kSubsampledTemplateWidth : kLumaTemplateWidth,
                  subsampling_y ? kSubsampledTemplateHeight : kLumaTemplateHeight);
    const int num_points = plane == 1 ? p.num_cb_points : p.num_cr_points;
    const bool enabled = num_points > 0 || p.chroma_scaling_from_luma;
    const uint16_t seed = plane == 1 ? cb_template_seed(p.grain_seed) : cr_template_seed(p.grain_seed);
    fill_white_noise(t, seed, enabled, bit_depth, p.grain_scale_shift);
    if (!enabled) return false;
    const auto& plus_128 = plane == 1 ? p.ar_coeffs_cb_plus_128 : p.ar_coeffs_cr_plus_128;
    const int taps = 2 * p.ar_coeff_lag * (p.ar_coeff_lag + 1) + 1;  // the last one weights luma
    for (int i = 0; i < taps; ++i) coeffs[i] = plus_128[static_cast<std::size_t>(i)] - 128;
    job = ar_job(t, p, bit_depth, coeffs);
    // The reference adds the luma term only when luma has grain (num_y_points > 0).
    if (p.num_y_points > 0) {
        job.luma = luma.samples.data();
        job.luma_width = luma.width;
        job.subsampling_x = subsampling_x;
        job.subsampling_y = subsampling_y;
    }
    return true;
}

}  // namespace

void generate_chroma_template_optimized(const Av1FilmGrainParams& p, int bit_depth, int plane, int subsampling_x,
                                        int subsampling_y, const GrainTemplate& luma, GrainTemplate& t) {
    int coeffs[25];
    simd::ArFilterJob job;
    if (prepare_chroma(p, bit_depth, plane, subsampling_x, subsampling_y, luma, t, coeffs, job))
        simd::ar_filter_template(job);
}

void generate_chroma_templates_optimized(const Av1FilmGrainParams& p, int bit_depth, int subsampling_x,
                                         int subsampling_y, const GrainTemplate& luma, GrainTemplate& cb,
                                         GrainTemplate& cr) {
    int cb_coeffs[25], cr_coeffs[25];
    simd::ArFilterJob cb_job, cr_job;
    const bool cb_on = prepare_chroma(p, bit_depth, 1, subsampling_x, subsampling_y, luma, cb, cb_coeffs, cb_job);
    const bool cr_on = prepare_chroma(p, bit_depth, 2, subsampling_x, subsampling_y, luma, cr, cr_coeffs, cr_job);
    if (cb_on && cr_on)
        simd::ar_filter_template_pair(cb_job, cr_job);
    else if (cb_on || cr_on)
        simd::ar_filter_template(cb_on ? cb_job : cr_job);
}

}  // namespace filmgrain::av1

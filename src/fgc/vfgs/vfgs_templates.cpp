// Grain templates of the VFGS flavour: see vfgs_templates.hpp.
#include "fgc/vfgs/vfgs_templates.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include "fgc/ar_template_generation.hpp"
#include "fgc/template_generation.hpp"
#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "fgc/vfgs/vfgs_tables.hpp"

namespace filmgrain::vfgs {

namespace {

// VFGS's inverse DCT-2 of an n x n block (n = 64, or 32 with the even rows of the 64-point
// matrix): the shared two-pass transform (fgc/template_generation), vertical pass first,
// since VFGS's coefficient rows are vertical frequencies; HM transforms horizontally first,
// and the rounding between the passes makes the orders differ. The 32-point chroma case
// rounds pass 1 by >> 8 to compensate the sqrt 2 of the even-row basis once; that is VFGS's
// normalisation, kept for bit-exactness.
void inverse_dct(const std::vector<int32_t>& coef, int n, GrainTemplate& out) {
    fgc::inverse_transform_2d(coef.data(), n, fgc::TemplateTransform::kVvcDct2, kTemplateSize / n,
                              n == kTemplateSize ? 9 : 8, 9, true, out);
}

// Fills the low-frequency corner of an n x n coefficient block with Gaussian
// values, `group` at a time along the horizontal frequency. The LFSR steps once
// per group over the whole block, so the values a given frequency receives do
// not depend on the cut-offs (a lower cut-off only removes coefficients).
GrainTemplate frequency_template(int n, int group, uint32_t seed, int h_cutoff, int v_cutoff) {
    const int kmax = group * (h_cutoff + 1);
    const int lmax = group * (v_cutoff + 1);
    std::vector<int32_t> coef(static_cast<size_t>(n) * n, 0);
    uint32_t r = seed;
    for (int l = 0; l < n; ++l)
        for (int k = 0; k < n; k += group) {
            if (k < kmax && l < lmax)
                for (int q = 0; q < group; ++q) coef[l * n + k + q] = kGaussianLut[(r + q) & 2047u];
            r = lfsr_next(r);
        }
    coef[0] = 0;  // no DC: the grain is zero-mean
    GrainTemplate t{};
    inverse_dct(coef, n, t);
    return t;
}

}  // namespace

GrainTemplate make_frequency_template_luma(int h_cutoff, int v_cutoff) {
    return frequency_template(kTemplateSize, 4, kSeedLut[0], h_cutoff, v_cutoff);
}

GrainTemplate make_frequency_template_chroma420(int h_cutoff, int v_cutoff) {
    return frequency_template(kChromaTemplateSize, 2, kSeedLut[1], h_cutoff, v_cutoff);
}

GrainTemplate make_ar_template_luma(const std::array<int, 6>& value, int log2_scale_factor) {
    // The shared AR filter (fgc/ar_template_generation) driven by VFGS's random source:
    // (Gaussian_LUT[r & 2047] + 1) >> 1, r stepping once per sample from Seed_LUT[0].
    uint32_t r = kSeedLut[0];
    return fgc::make_ar_template(fgc::ar_weights(value, log2_scale_factor), [&r] {
        const int n = (kGaussianLut[r & 2047u] + 1) >> 1;
        r = lfsr_next(r);
        return n;
    });
}

namespace {

const std::array<int, 6>& row_values(const ResolvedParams& r, int c, int k) {
    return r.comp[c].intervals[static_cast<size_t>(k)].value;
}

bool slot_matches(const TemplatePools& pools, const TemplatePool& pool, const ResolvedParams& r, int s,
                  const std::array<int, 6>& cand) {
    if (s < pool.count) {
        const auto& v = row_values(r, pool.slot[s].component, pool.slot[s].interval);
        return std::equal(v.begin() + 1, v.end(), cand.begin() + 1);
    }
    return pools.empty_slot_matches_luma_row0 &&
           std::equal(pools.empty_slot_values.begin(), pools.empty_slot_values.end(), cand.begin() + 1);
}

int search(const TemplatePools& pools, const TemplatePool& pool, const ResolvedParams& r,
           const std::array<int, 6>& cand) {
    for (int s = 0; s < kMaxTemplates; ++s)
        if (slot_matches(pools, pool, r, s, cand)) return s;
    return -1;
}

}  // namespace

TemplatePools select_template_pools(const ResolvedParams& r) {
    TemplatePools pools;
    if (r.comp[0].present && !r.comp[0].intervals.empty()) {
        pools.empty_slot_matches_luma_row0 = true;
        const auto& v = r.comp[0].intervals[0].value;
        std::copy(v.begin(), v.begin() + 5, pools.empty_slot_values.begin());
    }
    for (int c = 0; c < 3; ++c) {
        if (!r.comp[c].present) continue;
        TemplatePool& pool = (c == 0) ? pools.luma : pools.chroma;
        for (int k = 0; k < static_cast<int>(r.comp[c].intervals.size()); ++k) {
            if (search(pools, pool, r, row_values(r, c, k)) >= 0) continue;  // shares a template
            if (pool.count >= kMaxTemplates) continue;                      // pool full: dropped
            // Insert keeping the slots sorted by lower bound (stable), so that
            // neighbouring intensity ranges get neighbouring slots.
            const int lower = r.comp[c].intervals[static_cast<size_t>(k)].lower;
            int s = pool.count;
            while (s > 0 && pool.slot[s - 1].lower > lower) {
                pool.slot[s] = pool.slot[s - 1];
                --s;
            }
            pool.slot[s] = PoolSlot{c, k, lower};
            ++pool.count;
        }
    }
    return pools;
}

int find_template_slot(const TemplatePools& pools, const ResolvedParams& r, int component, int interval) {
    const TemplatePool& pool = (component == 0) ? pools.luma : pools.chroma;
    return search(pools, pool, r, row_values(r, component, interval));
}

void build_templates(const ResolvedParams& r, const TemplatePools& pools, TemplateBank& bank) {
    for (int s = 0; s < pools.luma.count; ++s) {
        const auto& v = row_values(r, pools.luma.slot[s].component, pools.luma.slot[s].interval);
        bank.luma[s] = (r.model_id == 0) ? make_frequency_template_luma(v[1], v[2])
                                         : make_ar_template_luma(v, r.log2_scale_factor);
    }
    // Chroma grain exists only for model 0 in 4:2:0 (validated before).
    for (int s = 0; s < pools.chroma.count; ++s) {
        const auto& v = row_values(r, pools.chroma.slot[s].component, pools.chroma.slot[s].interval);
        bank.chroma[s] = make_frequency_template_chroma420(v[1], v[2]);
    }
}

}  // namespace filmgrain::vfgs

// Grain templates of the VFGS flavour (TR 23002-9 clause 7.5, Annex B.2.2).
//
// VFGS synthesises grain by copying 16x16 (chroma 8x8) pieces of a small set of
// pre-computed 64x64 (4:2:0 chroma 32x32) templates, one per distinct set of
// model values, instead of generating noise per block:
//  - model 0 (frequency filtering): band-limited Gaussian noise made with the
//    VVC 64-point integer inverse DCT-2;
//  - model 1 (auto-regression): a causal AR filter run over a 82x73 noise
//    buffer, cropped to 64x64 (luma only, as in VFGS).
// A hardware-minded design keeps at most 8 luma and 8 chroma templates.
#pragma once
#include <array>
#include <cstdint>

#include "fgc/grain_template.hpp"

namespace filmgrain::vfgs {

struct ResolvedParams;

using fgc::GrainTemplate;                      // every flavour's template type
using fgc::kTemplateSize;                      // luma (and storage) size
inline constexpr int kChromaTemplateSize = 32; // 4:2:0 chroma, stored in the top-left corner
inline constexpr int kMaxTemplates = 8;        // per pool (luma; Cb+Cr share the chroma pool)

// Model 0 luma template: coefficients B[l][k] = Gaussian values for
// k < 4(h+1), l < 4(v+1) (groups of 4 along k, one LFSR step per group even
// outside the cut-off, starting from Seed_LUT[0]), B[0][0] = 0, then the
// two-pass integer inverse DCT and a clip to +-127.
GrainTemplate make_frequency_template_luma(int h_cutoff, int v_cutoff);

// Model 0 4:2:0 chroma template (32x32 in the top-left of the returned array):
// Seed_LUT[1], groups of 2, cut-offs 2(h+1) / 2(v+1), the even rows of the
// 64-point matrix, first pass rounded by >> 8 and second by >> 9.
GrainTemplate make_frequency_template_chroma420(int h_cutoff, int v_cutoff);

// Model 1 luma template from the completed model values (see
// vfgs_parameters.hpp) and log2_scale_factor L:
// noise (Gaussian_LUT[r & 2047] + 1) >> 1 with r stepping from Seed_LUT[0]
// once per sample, plus for y >= 3, 3 <= x < 79 the causal filter
// left [1], top ([1]*[4]) >> L, top-left/top-right ([3]*[4]) >> L,
// left-left [5], top-top ([5]*[4]*[4]) >> 2L, rounded by >> L; clip +-127;
// the template is buf[9 + y][9 + x].
GrainTemplate make_ar_template_luma(const std::array<int, 6>& value, int log2_scale_factor);

// Which (component, interval) rows own the template slots of a pool.
struct PoolSlot {
    int component = -1;
    int interval = -1;
    int lower = 0;  // intensity_interval_lower_bound of that interval (slot order key)
};
struct TemplatePool {
    int count = 0;
    std::array<PoolSlot, kMaxTemplates> slot{};
};
struct TemplatePools {
    TemplatePool luma;
    TemplatePool chroma;  // shared by Cb and Cr
    // VFGS compares a candidate with an empty slot as if the slot held luma
    // interval 0's values [0..4] (a pointer one element before the value
    // array). Mirrored when luma is present; no golden depends on it.
    bool empty_slot_matches_luma_row0 = false;
    std::array<int, 5> empty_slot_values{};
};

// Two intervals share a template when model values [1..5] are equal (after
// the chroma conversion). The first kMaxTemplates distinct rows in signalled
// order (Y; then Cb before Cr) are kept; slots are ordered by lower bound
// (stable), so slot 0 is the kept row with the smallest lower bound. Rows that
// do not fit are dropped (their intensities fall back to a neighbour's
// template, see build_luts).
TemplatePools select_template_pools(const ResolvedParams& r);

// Slot of the template for row (component, interval), or -1 when it was dropped.
int find_template_slot(const TemplatePools& pools, const ResolvedParams& r, int component, int interval);

// Template storage. It outlives a parameter set on purpose: VFGS only
// overwrites the slots the new set uses, and an LUT entry can (through the
// empty-slot quirk above) point at a slot left from an earlier set.
struct TemplateBank {
    std::array<GrainTemplate, kMaxTemplates> luma{};
    std::array<GrainTemplate, kMaxTemplates> chroma{};
};

// (Re)builds the slots 0..count-1 of both pools.
void build_templates(const ResolvedParams& r, const TemplatePools& pools, TemplateBank& bank);

}  // namespace filmgrain::vfgs

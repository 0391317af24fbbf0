// Parameter set-up of the VFGS flavour (TR 23002-9 clause 7.5, Annex B.2.2):
// from the FGC SEI syntax (FgcParams) to the values the VFGS synthesis uses.
//
//  1. validation (what VFGS's checks and asserts accept),
//  2. completion of the model values that were not signalled,
//  3. the 4:2:0 chroma conversion of cut-offs and scale,
//  4. the --gain option (a global strength factor outside the SEI),
//  5. the per-component 256-entry scale and template-index LUTs.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "fgc/vfgs/vfgs_templates.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::vfgs {

struct ResolvedInterval {
    int lower = 0;
    int upper = 255;
    std::array<int, 6> value{};  // comp_model_value[0..5], completed and converted
};

struct ResolvedComponent {
    bool present = false;
    std::vector<ResolvedInterval> intervals;  // in signalled order
};

struct ResolvedParams {
    int model_id = 0;
    int signalled_log2_scale_factor = 0;
    int log2_scale_factor = 0;  // after --gain
    std::array<ResolvedComponent, 3> comp;
};

// Checks that do not depend on the picture format. gain_percent is needed
// because VFGS range-checks log2_scale_factor after --gain has changed it.
// Throws filmgrain::Error naming the field, the value and the allowed range.
void validate_params(const FgcParams& p, int gain_percent);

// Checks that depend on the picture format (bit depth and chroma format).
void validate_params_for_format(const FgcParams& p, ChromaFormat format, int bit_depth);

// Value completion for an interval that signals `num_values` (1..6) values.
// Unsent values become, as in VFGS: [1] = 8 (model 0) / 0 (model 1);
// [2] = [1] (model 0) / 0; [3] = 0; [4] = model_id << log2_scale_factor
// (the signalled one, i.e. 1 << L for model 1); [5] = 0.
std::array<int, 6> complete_model_values(const std::array<int, 6>& signalled, int num_values, int model_id,
                                         int log2_scale_factor);

// The --gain rule: while gain > 100 halve it and decrement log2_scale_factor;
// while 0 < gain < 50 double it and increment; then every scale becomes
// scale * gain / 100 (integer division). Returns the reduced gain and updates L.
int reduce_gain(int gain_percent, int& log2_scale_factor);

// Steps 2..4. Call validate_params* first.
ResolvedParams resolve_params(const FgcParams& p, ChromaFormat format, int gain_percent);

// Per-component LUTs indexed by the 8-bit intensity (sample >> (bitdepth-8)).
struct ComponentLuts {
    std::array<uint8_t, 256> scale{};     // comp_model_value[0] inside an interval, 0 outside
    std::array<uint8_t, 256> tmpl{};      // template index into the component's pool
    // Pattern interpolation only (Options::pattern_interpolation): second template
    // and blend weight in 1/16 (0 = tmpl only). All zero when it is off.
    std::array<uint8_t, 256> tmpl_next{};
    std::array<uint8_t, 256> frac{};
};

// Builds the LUTs of all three components from the pools chosen by
// select_template_pools(). Mirrors VFGS: intensities outside every interval,
// and intervals whose template did not fit in the pool, take the template of
// the nearest lower intensity (index 0 below the first interval); Cr starts
// from Cb's scale LUT (VFGS fills them in one buffer), which only shows where
// Cr has no interval of its own.
std::array<ComponentLuts, 3> build_luts(const ResolvedParams& r, const TemplatePools& pools);

// Adds pattern-interpolation ramps to `luts` (TR 23002-9 7.2.4.2 / 7.5.4):
// around every intensity where the template index changes between two
// adjacent intervals, the two templates are blended over up to 16 intensity
// steps, so that the grain texture changes gradually with intensity.
// VFGS has the per-sample blend (P*(16-f) + Pn*f + 8) >> 4 behind a disabled
// switch but never fills in a weight; the ramp shape here (half-width
// min(8, half of either interval), weight 8/16 at the boundary) is this
// implementation's choice. Scale values are not interpolated.
void add_interpolation_ramps(const ResolvedParams& r, std::array<ComponentLuts, 3>& luts);

// Right shift applied after scaling: log2_scale_factor - model_id + 6 - (bitdepth - 8).
// (Model 1 templates already carry one bit of the noise scaling.)
int scale_shift(const ResolvedParams& r, int bit_depth);

}  // namespace filmgrain::vfgs

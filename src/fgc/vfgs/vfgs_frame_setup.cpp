// Parameter set to synthesis set-up: see vfgs_frame_setup.hpp.
#include "fgc/vfgs/vfgs_frame_setup.hpp"

#include <algorithm>

#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"

namespace filmgrain::vfgs {

SynthesisSetup prepare_setup(const FgcParams& p, ChromaFormat format, int bit_depth, const Options& options,
                             TemplateBank& bank) {
    validate_params_for_format(p, format, bit_depth);
    const ResolvedParams r = resolve_params(p, format, options.gain_percent);
    const TemplatePools pools = select_template_pools(r);
    build_templates(r, pools, bank);
    SynthesisSetup setup;
    setup.bank = &bank;
    setup.luts = build_luts(r, pools);
    if (options.pattern_interpolation) add_interpolation_ramps(r, setup.luts);
    setup.pattern_interpolation = options.pattern_interpolation;
    setup.scale_shift = scale_shift(r, bit_depth);
    for (size_t c = 0; c < 3; ++c) {
        setup.runs[c] = intensity_runs(setup.luts[c]);
        setup.has_grain[c] = std::any_of(setup.luts[c].scale.begin(), setup.luts[c].scale.end(),
                                         [](uint8_t s) { return s != 0; });
    }
    return setup;
}

}  // namespace filmgrain::vfgs

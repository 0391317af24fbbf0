// From a parameter set and a picture format to what the per-frame synthesis reads
// (SynthesisSetup): validation against the format, the resolved model values, the
// template pools and templates, the look-up tables and the scaling shift.
#pragma once
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"
#include "filmgrain/vfgs.hpp"

namespace filmgrain::vfgs {

// (Re)builds the templates of `params` in `bank` (the slots it uses; the others keep what
// earlier sets left, as the reference's template memory) and returns the setup pointing
// at `bank`. Throws Error for parameters the format does not allow.
SynthesisSetup prepare_setup(const FgcParams& params, ChromaFormat format, int bit_depth, const Options& options,
                             TemplateBank& bank);

}  // namespace filmgrain::vfgs

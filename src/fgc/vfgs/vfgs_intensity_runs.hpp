// The per-sample look-ups of the VFGS flavour in the form a vector kernel can evaluate.
//
// VFGS takes every sample's template and scale from two 256-entry tables indexed by the
// sample's own 8-bit intensity (ComponentLuts). Vector units have no 256-entry byte
// look-up, but the tables are piecewise constant: intervals, the gaps between them
// (scale 0, the template of the nearest lower intensity) and nothing else. As a list of
// runs [start, next start) with one (template, scale) each, a lane's entry is the last
// run whose start is at or below its intensity: a few compares and selects per vector.
#pragma once
#include <array>
#include <cstdint>

#include "fgc/vfgs/vfgs_parameters.hpp"

namespace filmgrain::vfgs {

struct IntensityRun {
    int start = 0;  // first intensity of the run
    int tmpl = 0;   // template index into the component's pool
    int scale = 0;  // comp_model_value[0] (0 = no grain)
};

// At most 256 runs (one per intensity); a component whose tables change more often than
// kMaxVectorRuns times goes through the scalar kernels, where a look-up is one load.
inline constexpr int kMaxVectorRuns = 32;

struct IntensityRuns {
    int count = 0;
    std::array<IntensityRun, 256> run{};
};

// The runs of `lut`'s template and scale tables (pattern interpolation's tables are not
// represented: that option takes the scalar kernels).
IntensityRuns intensity_runs(const ComponentLuts& lut);

}  // namespace filmgrain::vfgs

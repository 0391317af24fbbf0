// The look-up tables as runs: see vfgs_intensity_runs.hpp.
#include "fgc/vfgs/vfgs_intensity_runs.hpp"

namespace filmgrain::vfgs {

IntensityRuns intensity_runs(const ComponentLuts& lut) {
    IntensityRuns r;
    for (int i = 0; i < 256; ++i) {
        const int t = lut.tmpl[static_cast<size_t>(i)], s = lut.scale[static_cast<size_t>(i)];
        if (r.count > 0 && r.run[static_cast<size_t>(r.count - 1)].tmpl == t &&
            r.run[static_cast<size_t>(r.count - 1)].scale == s)
            continue;
        r.run[static_cast<size_t>(r.count++)] = IntensityRun{i, t, s};
    }
    return r;
}

}  // namespace filmgrain::vfgs

// Which implementation of a model's per-stripe stages runs, for both models: the scalar
// reference (the standard's process, kept as the bit-exact reference every optimized path is
// tested against) or the optimized twin (vector kernels chosen at run time for the CPU,
// see simd_targets.hpp). Both give identical output.
#pragma once

namespace filmgrain {

enum class Kernels { kOptimized, kReference };

}  // namespace filmgrain

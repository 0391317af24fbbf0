// The vector instruction sets the optimized kernels were compiled for and the CPU runs,
// and a switch to force one of them (for tests, benchmarks and the FILMGRAIN_SIMD_TARGET
// variable of the tool). Dispatch itself is Highway's (HWY_DYNAMIC_DISPATCH).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace filmgrain::simd {

struct Target {
    int64_t bits;      // Highway's HWY_* target bit
    std::string name;  // e.g. "AVX2", "SSE4", "EMU128"
};

// Every compiled target this CPU can run, best first.
std::vector<Target> available_targets();

// Restricts dispatch to `bits` (one target), or back to the best one with 0. This is
// process-wide (Highway keeps the choice), so call it before starting synthesis, not
// while other threads synthesize. Returns false when `bits` is not available.
bool force_target(int64_t bits);
// Forces the target named `name` (case-insensitive, as available_targets() lists it).
bool force_target(const std::string& name);

// The target the kernels dispatch to right now.
std::string dispatched_target();

}  // namespace filmgrain::simd

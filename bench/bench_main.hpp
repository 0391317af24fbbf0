// The main() of every benchmark program in bench/: FILMGRAIN_SIMD_TARGET forces one vector
// target of the optimized kernels (the run fails if the CPU lacks it), and the target in use
// is recorded in the output's context.
#pragma once
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/simd_targets.hpp"

namespace filmgrain::bench {

inline int run_benchmarks(int argc, char** argv) {
    if (const char* t = std::getenv("FILMGRAIN_SIMD_TARGET"); t && !simd::force_target(std::string(t))) {
        std::fprintf(stderr, "FILMGRAIN_SIMD_TARGET=%s is not available on this CPU\n", t);
        return 2;
    }
    benchmark::AddCustomContext("simd_target", simd::dispatched_target());
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

}  // namespace filmgrain::bench

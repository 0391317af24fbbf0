// Time to build the three AV1 grain templates of one frame (AV1 spec 7.18.3.3: Gaussian
// fill and auto-regressive filter), scalar reference vs optimized twin. Paid once per
// frame whatever the resolution, because grain_seed changes every frame; the seed is
// varied here too. Not part of the test suite.
//
//   build/filmgrain_template_bench [--benchmark_repetitions=9]
//   FILMGRAIN_SIMD_TARGET=SSE4 build/filmgrain_template_bench   # force a vector target
#include <benchmark/benchmark.h>

#include "bench_main.hpp"
#include "bench_params.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/grain_template_optimized.hpp"
#include "core/simd_targets.hpp"

using namespace filmgrain;

namespace {

// The synthesis benchmark's parameter set with a configurable lag.
Av1FilmGrainParams params(int lag) {
    Av1FilmGrainParams p = bench::av1_params();
    p.ar_coeff_lag = lag;
    return p;
}

// args: bit depth, subsampling (0 = 4:4:4, 1 = 4:2:0), lag, optimized (0/1)
void BM_Av1Templates(benchmark::State& state) {
    const int bd = int(state.range(0)), sub = int(state.range(1));
    const bool optimized = state.range(3) != 0;
    Av1FilmGrainParams p = params(int(state.range(2)));
    av1::GrainTemplate t[3];
    for (auto _ : state) {
        p.grain_seed = (p.grain_seed + 7919) & 0xffff;
        if (optimized) {
            av1::generate_luma_template_optimized(p, bd, t[0]);
            av1::generate_chroma_templates_optimized(p, bd, sub, sub, t[0], t[1], t[2]);
        } else {
            av1::generate_luma_template(p, bd, t[0]);
            for (int pl = 1; pl <= 2; pl++) av1::generate_chroma_template(p, bd, pl, sub, sub, t[0], t[pl]);
        }
        benchmark::DoNotOptimize(t[2].samples.data());
    }
    state.SetLabel(optimized ? simd::dispatched_target() : "reference");
}
BENCHMARK(BM_Av1Templates)
    ->ArgNames({"bd", "sub", "lag", "opt"})
    ->ArgsProduct({{8, 10}, {1, 0}, {3, 0}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) { return bench::run_benchmarks(argc, argv); }

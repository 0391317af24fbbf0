// Per-frame synthesis time of both models (Google Benchmark): 1280x720, 1920x1080 and
// 3840x2160, 8- and 10-bit 4:2:0, 1 and 2 threads, scalar reference vs optimized kernels,
// one frame copy of each size (the bound synthesis is compared with), and two threads over
// one timed in paired frames (BM_ThreadScaling). Contexts are
// created once and reused, as a decoder would, so the numbers are the steady state
// (templates built, buffers grown). Not part of the test suite; tools/bench-compare runs it.
//
//   build/filmgrain_bench [--benchmark_filter=Av1/1920] [--benchmark_repetitions=5]
//   FILMGRAIN_SIMD_TARGET=SSE4 build/filmgrain_bench   # force a vector target
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <optional>
#include <vector>

#include "bench_main.hpp"
#include "bench_params.hpp"
#include "bench_pictures.hpp"
#include "core/frame_buffer.hpp"
#include "core/simd_targets.hpp"
#include "filmgrain/session.hpp"

using namespace filmgrain;

namespace {

// The FGC SEI tools/bench-compare inserts into its HEVC stream: luma in three intensity
// intervals, each chroma component in one (model values scaled to the bit depth).
FgcParams fgc_params(int bd) {
    FgcParams p;
    p.log2_scale_factor = 5;
    const int luma[3][5] = {{0, 89, 110, 8, 8}, {90, 169, 90, 10, 6}, {170, 255, 70, 12, 12}};
    const int chroma[2][3] = {{60, 6, 6}, {50, 7, 5}};
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        if (c == 0)
            for (const auto& i : luma) p.comp[c].intervals.push_back({i[0], i[1], {i[2] << (bd - 8), i[3], i[4]}});
        else
            p.comp[c].intervals = {{0, 255, {chroma[c - 1][0] << (bd - 8), chroma[c - 1][1], chroma[c - 1][2]}}};
    }
    return p;
}


// Every benchmark drives the stream session, as every entry point does (the C API, the tool,
// GStreamer, Python): what a decoder pays per picture, session checks included. The parameter
// set arrives once and persists (FGC: the picture order count advances) or arrives with every
// picture and a new seed (AV1), as in streams.
class BenchStream {
public:
    BenchStream(FgcFlavour flavour, int threads, bool reference_kernels, const std::optional<FgcParams>& fgc)
        : session_(options(flavour, threads, reference_kernels)), av1_(bench::av1_params()), fgc_(fgc.has_value()) {
        if (fgc) session_.receive_fgc_params(*fgc, FgcCodec::kHevc);
    }
    void frame(FrameBuffer& in, FrameBuffer& out) {
        if (fgc_) {
            info_.ids.poc = (info_.ids.poc + 1) & 255;
            session_.apply(in.view(), out.view(), &info_);
        } else {
            av1_.grain_seed = (av1_.grain_seed + 7391) & 0xFFFF;  // encoders change the seed every frame
            session_.receive_av1_params(av1_, 0, 1);
            session_.apply(in.view(), out.view());
        }
        benchmark::DoNotOptimize(out.bytes());
    }

private:
    static SessionOptions options(FgcFlavour flavour, int threads, bool reference_kernels) {
        SessionOptions o;
        o.flavour = flavour;
        o.threads = threads;
        o.reference_kernels = reference_kernels;
        return o;
    }
    Session session_;
    Av1FilmGrainParams av1_;
    FrameInfo info_;
    bool fgc_;
};

// args: width, height, bit depth, threads, optimized (0/1). The first picture's set-up
// (templates, vfgs tables and stripe states) is outside the timing for FGC.
void run_stream(benchmark::State& state, FgcFlavour flavour, const std::optional<FgcParams>& fgc) {
    const int w = int(state.range(0)), h = int(state.range(1)), bd = int(state.range(2));
    BenchStream stream(flavour, int(state.range(3)), state.range(4) == 0, fgc);
    FrameBuffer in = bench::test_picture(w, h, bd), out(w, h, in.format());
    if (fgc) stream.frame(in, out);
    for (auto _ : state) stream.frame(in, out);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

// args: width, height, bit depth, threads, optimized (0/1), flavour (0 rdd5, 1 vtm)
void BM_Fgc(benchmark::State& state) {
    run_stream(state, state.range(5) ? FgcFlavour::kVtm : FgcFlavour::kRdd5, fgc_params(int(state.range(2))));
}

// args: width, height, bit depth, threads, optimized (0/1). The vfgs flavour (VFGS-exact).
// VFGS's scale is 8 bits at every bit depth, so the 8-bit parameter set serves both.
void BM_Vfgs(benchmark::State& state) { run_stream(state, FgcFlavour::kVfgs, fgc_params(8)); }

// args: width, height, bit depth, threads, optimized (0/1)
void BM_Av1(benchmark::State& state) { run_stream(state, FgcFlavour::kRdd5, std::nullopt); }

// args: width, height, bit depth. Copying every row of every plane once: what a decoder
// that hands out a separate output frame pays at least, grain or not.
void BM_FrameCopy(benchmark::State& state) {
    const int w = int(state.range(0)), h = int(state.range(1)), bd = int(state.range(2));
    FrameBuffer in = bench::test_picture(w, h, bd), out(w, h, in.format());
    const FrameView s = in.view(), d = out.view();
    for (auto _ : state) {
        for (int p = 0; p < s.plane_count(); p++)
            for (int y = 0; y < s.planes[p].height; y++)
                std::memcpy(d.planes[p].data + d.planes[p].stride * y, s.planes[p].data + s.planes[p].stride * y,
                            std::size_t(s.planes[p].width) * std::size_t(s.bytes_per_sample()));
        benchmark::DoNotOptimize(out.bytes());
        benchmark::ClobberMemory();
    }
}

// args: model (0 FGC rdd5, 1 FGC vfgs, 2 AV1, 3 FGC vtm), width, height, bit depth. The model's
// name is the benchmark's label, which tools/bench-compare reads (so the indices are mapped
// here only).
// Two-thread over one-thread throughput measured in pairs: each iteration runs a few frames
// on a one-thread session and as many on a two-thread session right after (the order
// alternating), and the ratio of the two elapsed times is one sample. On a shared machine
// whose speed changes over seconds, BM_Fgc's 1- and 2-thread repetitions fall in different
// states (their ratio moved from 1.35 to 2.5 within a minute on a Zen 3); frames a
// millisecond apart see the same one. The first frame of each side is not timed: it wakes
// the side's pool, idle while the other side ran, as in the back-to-back frames the other
// benchmarks time.
void BM_ThreadScaling(benchmark::State& state) {
    // vfgs scales in 8 bits at every bit depth (as BM_Vfgs); AV1 takes no FGC set
    struct Model {
        const char* name;
        FgcFlavour flavour;
        bool fgc, fgc_params_8bit;
    };
    static constexpr Model kModels[] = {{"FGC rdd5", FgcFlavour::kRdd5, true, false},
                                        {"FGC vfgs", FgcFlavour::kVfgs, true, true},
                                        {"AV1", FgcFlavour::kRdd5, false, false},
                                        {"FGC vtm", FgcFlavour::kVtm, true, false}};
    const Model& model = kModels[state.range(0)];
    state.SetLabel(model.name);
    const int w = int(state.range(1)), h = int(state.range(2)), bd = int(state.range(3));
    const std::optional<FgcParams> fgc =
        model.fgc ? std::optional<FgcParams>(fgc_params(model.fgc_params_8bit ? 8 : bd)) : std::nullopt;
    BenchStream streams[2] = {BenchStream(model.flavour, 1, false, fgc), BenchStream(model.flavour, 2, false, fgc)};
    FrameBuffer in = bench::test_picture(w, h, bd), out(w, h, in.format());
    for (BenchStream& stream : streams) stream.frame(in, out);
    constexpr int kTimedFrames = 4;
    std::vector<double> ratios;
    for (auto _ : state) {
        double seconds[2] = {};
        for (int k = 0; k < 2; ++k) {
            const int side = k ^ int(ratios.size() % 2);  // 0: one thread, 1: two
            streams[side].frame(in, out);
            const auto t0 = std::chrono::steady_clock::now();
            for (int f = 0; f < kTimedFrames; ++f) streams[side].frame(in, out);
            seconds[side] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
        ratios.push_back(seconds[0] / seconds[1]);
        state.SetIterationTime(seconds[0] + seconds[1]);
    }
    std::sort(ratios.begin(), ratios.end());
    state.counters["speedup"] = ratios[ratios.size() / 2];
    state.counters["speedup_q1"] = ratios[ratios.size() / 4];
    state.counters["speedup_q3"] = ratios[ratios.size() * 3 / 4];
}

void sizes(benchmark::internal::Benchmark* b, bool flavours) {
    const int dims[3][2] = {{1280, 720}, {1920, 1080}, {3840, 2160}};
    for (auto& d : dims)
        for (int bd : {8, 10})
            for (int threads : {1, 2})
                for (int optimized : {0, 1})
                    for (int flavour = 0; flavour <= (flavours ? 1 : 0); flavour++) {
                        if (flavours)
                            b->Args({d[0], d[1], bd, threads, optimized, flavour});
                        else
                            b->Args({d[0], d[1], bd, threads, optimized});
                    }
    b->ArgNames(flavours ? std::vector<std::string>{"w", "h", "bd", "threads", "optimized", "vtm"}
                         : std::vector<std::string>{"w", "h", "bd", "threads", "optimized"});
    b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_Fgc)->Apply([](benchmark::internal::Benchmark* b) { sizes(b, true); });
BENCHMARK(BM_Av1)->Apply([](benchmark::internal::Benchmark* b) { sizes(b, false); });
BENCHMARK(BM_Vfgs)->Apply([](benchmark::internal::Benchmark* b) { sizes(b, false); });
// Every model at 1080p; at 4K the models issue 6's two-thread targets name (vfgs has its
// target at 1080p only).
BENCHMARK(BM_ThreadScaling)
    ->ArgsProduct({{0, 3, 1, 2}, {1920}, {1080}, {8, 10}})
    ->ArgsProduct({{0, 3, 2}, {3840}, {2160}, {8, 10}})
    ->ArgNames({"model", "w", "h", "bd"})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();
BENCHMARK(BM_FrameCopy)
    ->ArgsProduct({{1280}, {720}, {8, 10}})
    ->ArgsProduct({{1920}, {1080}, {8, 10}})
    ->ArgsProduct({{3840}, {2160}, {8, 10}})
    ->ArgNames({"w", "h", "bd"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) { return bench::run_benchmarks(argc, argv); }

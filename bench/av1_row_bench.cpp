// The AV1 noise application kernels alone (av1/simd/av1_kernels.hpp: scaling look-up,
// chroma scaling index, overlap fade and blend), 1920x1080 4:2:0, per plane kind and bit
// depth, out of place, on two pictures: smooth (a ramp with noise of up to 16 8-bit codes,
// so at 8 bits most 32-sample vectors take the LUT's three-row path, while at 10 bits the
// noise spans several rows of the full-range table) and blocky (the synthesis benchmark's
// picture, a random level per 8x8 block: most take the 16-step chain). Each row's noise is read from a real grain template at random block offsets, as
// in synthesis. Reports seconds per sample; not part of the test suite.
//
//   build/filmgrain_av1_row_bench [--benchmark_repetitions=5]
//   FILMGRAIN_SIMD_TARGET=SSE4 build/filmgrain_av1_row_bench   # force a vector target
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "bench_main.hpp"
#include "bench_params.hpp"
#include "bench_pictures.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/scaling_lookup.hpp"
#include "av1/stripe_block_origins.hpp"
#include "av1/simd/av1_kernels.hpp"
#include "core/simd_targets.hpp"

using namespace filmgrain;

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

// Random block origins per stripe of 32 luma rows, within the template as 7.18.3.5 draws
// them (room for the block and its two overlap columns / rows).
struct BlockOrigins {
    int stripes = 0, blocks = 0;
    std::vector<const int16_t*> starts;  // [stripe][block]: the block's top-left sample
    BlockOrigins(const av1::GrainTemplate& t, int plane_width, int block_w, int block_h, int seed) {
        stripes = (kHeight + 31) / 32;
        blocks = (plane_width + block_w - 1) / block_w;
        std::mt19937 rng{uint32_t(seed)};
        for (int i = 0; i < stripes * blocks; i++) {
            const int ox = int(rng() % uint32_t(t.width - block_w - 2 + 1));
            const int oy = int(rng() % uint32_t(t.height - block_h - 2 + 1));
            starts.push_back(t.samples.data() + std::ptrdiff_t(oy) * t.width + ox);
        }
    }
};

// args: bit depth, plane (0 luma, 1 chroma), picture (0 smooth, 1 blocky), byte noise (8-bit
// luma: the noise also as the synthesis's int8 copy of the template, BlockNoiseRow::byte_blocks)
void BM_Av1Rows(benchmark::State& state) {
    const int bd = int(state.range(0));
    const bool chroma = state.range(1) != 0;
    const Av1FilmGrainParams p = bench::av1_params();
    FrameBuffer in = bench::test_picture(kWidth, kHeight, bd, state.range(2) != 0);
    FrameBuffer out(kWidth, kHeight, in.format());
    const av1::GrainTemplate luma_t = av1::generate_luma_template(p, bd);
    const av1::GrainTemplate t = chroma ? av1::generate_chroma_template(p, bd, 1, 1, 1, luma_t) : luma_t;
    const av1::ScalingLookup scaling = chroma ? av1::ScalingLookup(p.point_cb_value.data(), p.point_cb_scaling.data(),
                                                                   p.num_cb_points, bd)
                                              : av1::ScalingLookup(p.point_y_value.data(), p.point_y_scaling.data(),
                                                                   p.num_y_points, bd);
    const int pl = chroma ? 1 : 0;
    const FrameView src = in.view(), dst = out.view();
    const int pw = src.planes[pl].width, ph = src.planes[pl].height;
    const int block_w = chroma ? 16 : 32, block_h = block_w;
    const BlockOrigins origins(t, pw, block_w, block_h, 7);
    std::vector<const int16_t*> rows(std::size_t(origins.blocks));
    av1::simd::BlockNoiseRow row = av1::kernel_faded_row(chroma ? 1 : 0, bd);
    row.blocks = rows.data();
    std::vector<int8_t> bytes;
    std::vector<const int8_t*> byte_rows(std::size_t(origins.blocks));
    if (state.range(3)) {
        av1::simd::copy_noise_as_bytes(t.samples, bytes);
        row.byte_blocks = byte_rows.data();
    }
    av1::ChromaScalingIndex index;
    index.mult = p.cb_mult - 128, index.luma_mult = p.cb_luma_mult - 128, index.offset = p.cb_offset - 256;
    const int shift = p.grain_scaling_minus_8 + 8, max_value = (1 << bd) - 1;
    for (auto _ : state) {
        for (int y = 0; y < ph; y++) {
            const int stripe = y / block_h, i = y % block_h;
            // the blocks' first rows once per stripe, then a row offset down them, as the synthesis does
            if (i == 0)
                for (int b = 0; b < origins.blocks; b++) {
                    rows[std::size_t(b)] = origins.starts[std::size_t(stripe * origins.blocks + b)];
                    if (row.byte_blocks)
                        byte_rows[std::size_t(b)] = bytes.data() + (rows[std::size_t(b)] - t.samples.data());
                }
            row.row_offset = std::ptrdiff_t(i) * t.width;
            if (bd == 8 && !chroma)
                av1::simd::blend_luma_row_u8(src.planes[0].row<uint8_t>(y), dst.planes[0].row<uint8_t>(y), row, pw,
                                             scaling, shift, 0, max_value);
            else if (!chroma)
                av1::simd::blend_luma_row_u16(src.planes[0].row<uint16_t>(y), dst.planes[0].row<uint16_t>(y), row, pw,
                                              scaling, shift, bd, 0, max_value);
            else if (bd == 8)
                av1::simd::blend_chroma_row_u8(src.planes[1].row<uint8_t>(y), dst.planes[1].row<uint8_t>(y),
                                               src.planes[0].row<uint8_t>(2 * y), kWidth, row, pw, 1, index,
                                               scaling, shift, bd, 0, max_value);
            else
                av1::simd::blend_chroma_row_u16(src.planes[1].row<uint16_t>(y), dst.planes[1].row<uint16_t>(y),
                                                src.planes[0].row<uint16_t>(2 * y), kWidth, row, pw, 1, index,
                                                scaling, shift, bd, 0, max_value);
        }
        benchmark::DoNotOptimize(out.bytes());
        benchmark::ClobberMemory();
    }
    state.counters["s_per_sample"] =
        benchmark::Counter(double(pw) * ph, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetLabel(simd::dispatched_target());
}
BENCHMARK(BM_Av1Rows)
    ->ArgNames({"bd", "chroma", "blocky", "bytes"})
    ->Apply([](benchmark::internal::Benchmark* b) {
        for (int bd : {8, 10})
            for (int chroma : {0, 1})
                for (int blocky : {0, 1})
                    for (int bytes = 0; bytes <= (bd == 8 && !chroma); bytes++) b->Args({bd, chroma, blocky, bytes});
    })
    ->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) { return bench::run_benchmarks(argc, argv); }

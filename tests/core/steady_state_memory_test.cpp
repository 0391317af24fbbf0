// Steady state: once a stream's first frames have built templates and grown the stripe
// buffers, synthesizing further frames allocates nothing on the heap, with any thread count,
// and the working memory stays bounded by the templates plus a few stripes per thread.
// A counting replacement of the global operator new (this test binary only) checks it.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "av1/av1_picture_synthesis.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace filmgrain;

namespace {

FgcParams fgc_params() {
    FgcParams p;
    p.log2_scale_factor = 5;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {{0, 127, {100, 8, 8}}, {128, 255, {60, 11, 5}}};
    }
    return p;
}

FrameBuffer ramp(int w, int h, int bd) {
    FrameBuffer b(w, h, PixelFormat{ChromaFormat::k420, bd});
    for (std::size_t i = 0; i < b.byte_size(); i++) b.bytes()[i] = uint8_t(i * 7 % 251);
    if (bd > 8)
        for (std::size_t i = 1; i < b.byte_size(); i += 2) b.bytes()[i] &= 3;
    return b;
}

TEST(SteadyStateMemory, FgcFramesAfterTheFirstAllocateNothing) {
    for (int threads : {1, 2})
        for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm})
            for (int bd : {8, 10}) {
                FgcOptions o;
                o.flavour = flavour;
                o.threads = threads;
                FgcStreamSynthesis s(o);
                FrameBuffer in = ramp(1280, 720, bd), out(1280, 720, in.format());
                const FgcParams params = fgc_params();
                for (int k = 0; k < 2; k++) {  // warm-up: templates, stripe buffers
                    s.receive_sei(params);
                    s.apply(in.view(), out.view(), FgcPictureIds{k, 0});
                }
                const long before = g_allocations.load();
                const int templates = s.templates_built();
                for (int k = 2; k < 6; k++) {
                    if (k % 2) s.receive_sei(params);  // the same SEI again, as encoders repeat it
                    const FgcFrameResult r = s.apply(in.view(), out.view(), FgcPictureIds{k, 0});
                    ASSERT_TRUE(r.grain_applied);
                }
                EXPECT_EQ(g_allocations.load() - before, 0)
                    << "threads " << threads << " flavour " << int(flavour) << " bd " << bd;
                // Bounded: block states and a 32-row stripe per thread, far below a frame.
                EXPECT_LT(s.scratch_bytes(), std::size_t(threads) * 1280 * 32 * 8 + 1280 * 720 / 16 * 4);
                EXPECT_EQ(s.templates_built(), templates) << "the template cache must not grow";
            }
}

TEST(SteadyStateMemory, Av1FramesAfterTheFirstAllocateNothing) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.num_y_points = 2;
    p.point_y_value = {0, 255};
    p.point_y_scaling = {50, 80};
    p.num_cb_points = 1;
    p.point_cb_value = {128};
    p.point_cb_scaling = {40};
    p.num_cr_points = 1;
    p.point_cr_value = {128};
    p.point_cr_scaling = {30};
    p.ar_coeff_lag = 3;
    p.overlap_flag = 1;
    for (int threads : {1, 2})
        for (int bd : {8, 10})
            for (auto kernels : {av1::Kernels::kOptimized}) {
                av1::Av1PictureSynthesis s(threads, kernels);
                FrameBuffer in = ramp(1280, 720, bd), out(1280, 720, in.format());
                for (int k = 0; k < 2; k++) {
                    p.grain_seed = 100 + k;
                    s.apply(p, in.view(), out.view(), 1);
                }
                const long before = g_allocations.load();
                for (int k = 2; k < 6; k++) {
                    p.grain_seed = 100 + k;  // new templates every frame, built in place
                    s.apply(p, in.view(), out.view(), 1);
                }
                EXPECT_EQ(g_allocations.load() - before, 0) << "threads " << threads << " bd " << bd;
                // templates and scaling tables, plus per thread the four noise rows of a
                // stripe's vertical overlap (no noise stripe is copied any more) and the
                // co-sited luma of a stripe's chroma rows above 8 bits (16 rows of 640 samples)
                const std::size_t co_sited = bd > 8 ? std::size_t(16) * 640 * 2 : 0;
                EXPECT_LT(s.working_bytes(), std::size_t(threads) * (1400 * 4 * 2 + co_sited) + 64 * 1024);
            }
}

}  // namespace

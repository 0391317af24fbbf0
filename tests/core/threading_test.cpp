// Stripe-parallel synthesis: the thread pool runs every task once and reports failures,
// and both models give the same bytes for every thread count.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <random>
#include <stdexcept>
#include <vector>

#include "av1/av1_picture_synthesis.hpp"
#include "core/frame_buffer.hpp"
#include "core/thread_pool.hpp"
#include "fgc/fgc_stream_synthesis.hpp"

using namespace filmgrain;

namespace {

TEST(ThreadPool, RunsEveryTaskExactlyOnceOnValidWorkers) {
    for (int threads : {1, 2, 3, 8}) {
        ThreadPool pool(threads);
        ASSERT_EQ(pool.size(), threads);
        for (int round = 0; round < 20; round++) {
            const int tasks = round * 7 % 41;
            std::vector<std::atomic<int>> hits(std::size_t(tasks) + 1);
            std::atomic<int> bad_worker{0};
            pool.parallel_for(tasks, [&](int t, int w) {
                hits[std::size_t(t)]++;
                if (w < 0 || w >= threads) bad_worker++;
            });
            for (int t = 0; t < tasks; t++) ASSERT_EQ(hits[std::size_t(t)].load(), 1) << "task " << t;
            EXPECT_EQ(hits[std::size_t(tasks)].load(), 0);
            EXPECT_EQ(bad_worker.load(), 0);
        }
    }
}

TEST(ThreadPool, RethrowsTheFailureAndStaysUsable) {
    ThreadPool pool(3);
    EXPECT_THROW(pool.parallel_for(50, [](int t, int) {
        if (t == 17) throw std::runtime_error("stripe 17");
    }),
                 std::runtime_error);
    std::atomic<int> n{0};
    pool.parallel_for(10, [&](int, int) { n++; });
    EXPECT_EQ(n.load(), 10);
}

TEST(ThreadPool, ZeroMeansEveryHardwareThread) {
    EXPECT_GE(resolve_thread_count(0), 1);
    EXPECT_EQ(resolve_thread_count(5), 5);
    EXPECT_EQ(resolve_thread_count(-2), 1);
}

FrameBuffer noise_frame(int w, int h, PixelFormat f, unsigned seed) {
    FrameBuffer b(w, h, f);
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < b.byte_size(); i++) b.bytes()[i] = uint8_t(rng());
    if (f.bit_depth > 8)
        for (std::size_t i = 1; i < b.byte_size(); i += 2) b.bytes()[i] &= uint8_t((1 << (f.bit_depth - 8)) - 1);
    return b;
}

FgcParams fgc_params(int bd) {
    FgcParams p;
    p.log2_scale_factor = 4;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {{0, 90, {(150 - 30 * c) << (bd - 8), 6 + c, 9}}, {100, 255, {90 << (bd - 8), 12, 4}}};
    }
    return p;
}

TEST(StripeThreads, FgcOutputIsTheSameForEveryThreadCount) {
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm})
        for (int bd : {8, 10})
            for (bool reference : {false, true}) {
                const PixelFormat fmt{ChromaFormat::k420, bd};
                const FrameBuffer src = noise_frame(1000, 532, fmt, 7);
                std::vector<uint8_t> first;
                for (int threads : {1, 2, 3, 5}) {
                    FgcOptions o;
                    o.flavour = flavour;
                    o.threads = threads;
                    o.reference_kernels = reference;
                    FgcStreamSynthesis s(o);
                    s.receive_sei(fgc_params(bd));
                    FrameBuffer in = src, out(src.width(), src.height(), fmt);
                    s.apply(in.view(), out.view(), FgcPictureIds{3, 1});
                    std::vector<uint8_t> bytes(out.bytes(), out.bytes() + out.byte_size());
                    if (first.empty()) {
                        first = bytes;
                        ASSERT_NE(0, std::memcmp(bytes.data(), src.bytes(), bytes.size())) << "no grain was added";
                    } else {
                        ASSERT_EQ(bytes, first) << "threads " << threads << " flavour " << int(flavour) << " bd " << bd;
                    }
                }
            }
}

TEST(StripeThreads, Av1OutputIsTheSameForEveryThreadCount) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 4711;
    p.num_y_points = 2;
    p.point_y_value = {0, 255};
    p.point_y_scaling = {60, 90};
    p.num_cb_points = 1;
    p.point_cb_value = {128};
    p.point_cb_scaling = {70};
    p.num_cr_points = 1;
    p.point_cr_value = {64};
    p.point_cr_scaling = {50};
    p.ar_coeff_lag = 2;
    for (int i = 0; i < 12; i++) p.ar_coeffs_y_plus_128[std::size_t(i)] = 128 + (i % 5) - 2;
    p.overlap_flag = 1;
    for (int bd : {8, 10})
        for (auto kernels : {av1::Kernels::kOptimized, av1::Kernels::kReference}) {
            const PixelFormat fmt{ChromaFormat::k420, bd};
            const FrameBuffer src = noise_frame(1000, 530, fmt, 9);
            std::vector<uint8_t> first;
            for (int threads : {1, 2, 3, 5}) {
                av1::Av1PictureSynthesis s(threads, kernels);
                FrameBuffer in = src, out(src.width(), src.height(), fmt);
                s.apply(p, in.view(), out.view(), 1);
                std::vector<uint8_t> bytes(out.bytes(), out.bytes() + out.byte_size());
                if (first.empty())
                    first = bytes;
                else
                    ASSERT_EQ(bytes, first) << "threads " << threads << " bd " << bd;
            }
        }
}

}  // namespace

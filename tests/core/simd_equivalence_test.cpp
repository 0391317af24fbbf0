// Checkasm-style equivalence of the optimized kernels with their scalar references, for
// every vector target this CPU runs (each forced in turn through simd::force_target):
// random parameters, sizes, strides (negative too) and bit depths, kernel by kernel and
// for whole frames of both models. Any difference is reported with its position.
#include <algorithm>
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "random_av1_params.hpp"
#include "av1/av1_picture_synthesis.hpp"
#include "av1/block_synthesis.hpp"
#include "av1/grain_blending.hpp"
#include "av1/stripe_block_origins.hpp"
#include "av1/simd/av1_kernels.hpp"
#include "core/simd_targets.hpp"
#include "forced_simd_target.hpp"
#include "prefetched_rows.hpp"
#include "fgc/blending.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "fgc/grain_scaling.hpp"
#include "fgc/local_adaptation.hpp"
#include "fgc/simd/fgc_kernels.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;

namespace {

class SimdEquivalence : public test_support::ForcedSimdTarget<20261122u> {};

// A frame with its own row padding, optionally stored bottom-up (negative stride).
struct StridedFrame {
    std::vector<uint8_t> storage;
    FrameView view;
    StridedFrame(int w, int h, ChromaFormat cf, int bd, int pad, bool bottom_up, std::mt19937& rng) {
        view.format = cf;
        view.bit_depth = bd;
        view.width = w;
        view.height = h;
        const int bps = bd > 8 ? 2 : 1;
        std::size_t offsets[3] = {0, 0, 0}, total = 0;
        std::ptrdiff_t strides[3] = {0, 0, 0};
        for (int p = 0; p < num_planes(cf); p++) {
            strides[p] = std::ptrdiff_t(plane_width(cf, p, w)) * bps + pad * bps;
            offsets[p] = total;
            total += std::size_t(strides[p]) * plane_height(cf, p, h);
        }
        storage.resize(total + 64);
        std::uniform_int_distribution<int> sample(0, (1 << bd) - 1);
        for (std::size_t i = 0; i + 1 < storage.size(); i += 2) {
            const int v = sample(rng);
            if (bps == 2) {
                std::memcpy(&storage[i], &v, 2);
            } else {
                storage[i] = uint8_t(v);
                storage[i + 1] = uint8_t(sample(rng));
            }
        }
        for (int p = 0; p < num_planes(cf); p++) {
            PlaneView& pv = view.planes[p];
            pv.width = plane_width(cf, p, w);
            pv.height = plane_height(cf, p, h);
            pv.stride = bottom_up ? -strides[p] : strides[p];
            pv.data = storage.data() + offsets[p] + (bottom_up ? std::size_t(strides[p]) * (pv.height - 1) : 0);
        }
    }
    StridedFrame(const StridedFrame& o) : storage(o.storage), view(o.view) {
        for (int p = 0; p < 3; p++)
            if (view.planes[p].data) view.planes[p].data = storage.data() + (o.view.planes[p].data - o.storage.data());
    }
    // First differing sample of the visible area, or "" when equal.
    std::string diff(const StridedFrame& o) const {
        const int bps = view.bit_depth > 8 ? 2 : 1;
        for (int p = 0; p < view.plane_count(); p++)
            for (int y = 0; y < view.planes[p].height; y++)
                if (std::memcmp(view.planes[p].row<uint8_t>(y), o.view.planes[p].row<uint8_t>(y),
                                std::size_t(view.planes[p].width) * bps) != 0)
                    return "plane " + std::to_string(p) + " row " + std::to_string(y);
        return "";
    }
};

TEST_P(SimdEquivalence, FgcScaleTemplateBlocks) {
    for (int iter = 0; iter < 300; iter++) {
        const int bs = 8 << uniform(0, 2), bd = uniform(8, 16);
        std::vector<int8_t> tmpl(64 * 64);
        for (auto& v : tmpl) v = int8_t(uniform(-127, 127));
        const int shift = uniform(2, 7) + 6;
        const int count = uniform(1, 6);
        const int stride = count * bs + 5;
        std::vector<int16_t> got(std::size_t(stride) * bs, 0), want(got.size(), 0);
        std::vector<fgc::simd::BlockCopy> copies;
        for (int b = 0; b < count; b++) {
            const int ox = uniform(0, 64 - bs), oy = uniform(0, 64 - bs);
            const int32_t scale = uniform(-(255 << (bd - 8)), 255 << (bd - 8));
            const int cols = uniform(0, 3) ? bs : uniform(1, bs);
            copies.push_back({tmpl.data() + oy * 64 + ox, got.data() + b * bs, scale, cols});
            // the scaling stage the reference stripe runs
            for (int l = 0; l < bs; l++) {
                int32_t row[32];
                fgc::scale_template_row(tmpl.data() + (oy + l) * 64 + ox, scale, shift, row, cols);
                for (int k = 0; k < cols; k++) want[std::size_t(l) * stride + b * bs + k] = int16_t(row[k]);
            }
        }
        fgc::simd::scale_template_blocks(copies.data(), count, bs, shift, stride);
        ASSERT_EQ(got, want) << "iteration " << iter << " bs " << bs << " bd " << bd;
    }
}

TEST_P(SimdEquivalence, FgcDeblockAndBlend) {
    for (int iter = 0; iter < 400; iter++) {
        const int bs = 8 << uniform(0, 2), width = uniform(1, 300);
        const int bd = uniform(0, 2) ? 8 : uniform(9, 16);
        const int gmax = bd == 8 ? 126 : (32385 >> (16 - bd));
        std::vector<int16_t> g16(std::size_t(width) + 2);
        for (auto& v : g16) v = int16_t(uniform(-gmax, gmax));
        std::vector<int32_t> g32(g16.begin(), g16.end());
        fgc::deblock_stripe_vertical_edges(g32.data(), width + 2, 1, width, bs);
        if (bd == 8) {
            std::vector<uint8_t> src(static_cast<std::size_t>(width)), want(src.size()), got(src.size());
            for (auto& v : src) v = uint8_t(uniform(0, 255));
            fgc::blend_row_additive<uint8_t>(src.data(), want.data(), g32.data(), width, 8);
            // rows to prefetch (the next stripe's in the synthesis), each half the time: no effect
            test_support::PrefetchedRows<uint8_t> ahead(src.size());
            const auto next = ahead.pick([&] { return uniform(0, 1) == 1; });
            fgc::simd::deblock_blend_row_u8(src.data(), got.data(), g16.data(), width, bs, next);
            ASSERT_TRUE(ahead.untouched()) << "a prefetched row was written";
            ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " bs " << bs;
        } else {
            std::vector<uint16_t> src(static_cast<std::size_t>(width)), want(src.size()), got(src.size());
            // samples of any 16-bit value in a quarter of the rows (bad input above the bit depth)
            const int top = uniform(0, 3) == 0 ? 65535 : (1 << bd) - 1;
            for (auto& v : src) v = uint16_t(uniform(0, top));
            fgc::blend_row_additive<uint16_t>(src.data(), want.data(), g32.data(), width, bd);
            // rows to prefetch (the next stripe's in the synthesis), each half the time: no effect
            test_support::PrefetchedRows<uint16_t> ahead(src.size());
            const auto next = ahead.pick([&] { return uniform(0, 1) == 1; });
            fgc::simd::deblock_blend_row_u16(src.data(), got.data(), g16.data(), width, bs, bd, next);
            ASSERT_TRUE(ahead.untouched()) << "a prefetched row was written";
            ASSERT_EQ(got, want) << "iteration " << iter << " width " << width << " bs " << bs << " bd " << bd;
        }
    }
}

TEST_P(SimdEquivalence, FgcBlockSums) {
    for (int iter = 0; iter < 200; iter++) {
        const int bs = 8 << uniform(0, 2), bd = uniform(9, 16);  // 16-bit planes; 8-bit below
        const int w = uniform(1, 200), rows = uniform(1, bs);
        StridedFrame f(w, rows, ChromaFormat::k400, bd, uniform(0, 9), uniform(0, 1), rng);
        const PlaneView& p = f.view.planes[0];
        std::vector<uint32_t> sums(std::size_t(w / bs) + 1, 0xdeadbeef);
        fgc::simd::block_sums_u16(p.row<const uint16_t>(0), p.stride, rows, w, bs, sums.data());
        for (int b = 0; b < w / bs; b++) {
            // The average the reference computes must follow from the sum.
            const uint32_t avg = std::min<uint32_t>((sums[b] / uint32_t(bs * rows)) >> (bd - 8), 255);
            ASSERT_EQ(int(avg), fgc::block_average_inside<uint16_t>(p, b * bs, 0, bs, bd)) << "iteration " << iter;
        }
        ASSERT_EQ(sums[std::size_t(w / bs)], 0xdeadbeefu) << "wrote past the whole blocks";
    }
}

// The exact sums, against the element-wise sum, over the whole 16-bit range (samples beyond
// a bit depth are bad input the sums must still add exactly: the averages clamp them), often
// all 65535 or all 0, the widths past a multiple of four blocks and every row count.
TEST_P(SimdEquivalence, FgcBlockSums16BitExact) {
    for (int iter = 0; iter < 400; iter++) {
        const int bs = uniform(0, 2) ? 8 : 8 << uniform(1, 2);
        const int w = uniform(0, 1) ? uniform(1, 300) : 32 * uniform(1, 8) + uniform(-9, 9);
        const int rows = uniform(1, bs);
        const std::ptrdiff_t pitch = w + uniform(0, 40);
        const int extreme = uniform(0, 3);  // 0: all 0, 1: all 65535, else random
        std::vector<uint16_t> plane(std::size_t(pitch) * std::size_t(rows));
        for (auto& v : plane) v = uint16_t(extreme == 0 ? 0 : extreme == 1 ? 65535 : uniform(0, 65535));
        const int blocks = std::max(w, 1) / bs;
        std::vector<uint32_t> sums(std::size_t(blocks) + 1, 0xdeadbeef);
        fgc::simd::block_sums_u16(plane.data(), pitch * std::ptrdiff_t(sizeof(uint16_t)), rows, w, bs, sums.data());
        for (int b = 0; b < blocks; b++) {
            uint32_t want = 0;
            for (int y = 0; y < rows; y++)
                for (int x = b * bs; x < (b + 1) * bs; x++) want += plane[std::size_t(y * pitch + x)];
            ASSERT_EQ(sums[std::size_t(b)], want) << "iteration " << iter << " block " << b << " bs " << bs << " rows "
                                                  << rows << " width " << w;
        }
        ASSERT_EQ(sums[std::size_t(blocks)], 0xdeadbeefu) << "wrote past the whole blocks";
    }
}

// block_average_inside<uint16_t> above is only right for 16-bit planes; 8-bit planes are
// checked with their own reference.
TEST_P(SimdEquivalence, FgcBlockSums8Bit) {
    for (int iter = 0; iter < 200; iter++) {
        const int bs = 8 << uniform(0, 2), w = uniform(1, 300), rows = uniform(1, bs);
        StridedFrame f(w, bs, ChromaFormat::k400, 8, uniform(0, 9), uniform(0, 1), rng);
        const PlaneView& p = f.view.planes[0];
        std::vector<uint32_t> sums(std::size_t(w / bs));
        fgc::simd::block_sums_u8(p.row<const uint8_t>(0), p.stride, rows, w, bs, sums.data());
        PlaneView top = p;
        top.height = rows;
        for (int b = 0; b < w / bs; b++) {
            const uint32_t avg = std::min<uint32_t>(sums[b] / uint32_t(bs * rows), 255);
            ASSERT_EQ(int(avg), fgc::block_average_inside<uint8_t>(top, b * bs, 0, bs, 8)) << "iteration " << iter;
            if (rows == bs) {
                const int log2_area = bs == 8 ? 6 : bs == 16 ? 8 : 10;
                ASSERT_EQ(int(std::min<uint32_t>(sums[b] >> log2_area, 255)),
                          fgc::block_average_replicated<uint8_t>(p, b * bs, 0, bs, 8));
            }
        }
    }
}

av1::ScalingLookup random_scaling(std::mt19937& rng, int bd) {
    std::uniform_int_distribution<int> count_d(0, 14), scale_d(0, 255);
    int values[14], scalings[14];
    const int count = count_d(rng);
    int v = 0;
    int n = 0;
    for (; n < count && v < 256; n++) {
        v += std::uniform_int_distribution<int>(n == 0 ? 0 : 1, 40)(rng);
        if (v > 255) break;
        values[n] = v;
        scalings[n] = scale_d(rng);
    }
    return av1::ScalingLookup(values, scalings, n, bd);
}

// A row's noise as the optimized blends take it: each block's samples in its own buffer (as
// they lie at scattered template offsets), seams or not; `flat` is the same row contiguous,
// as the reference blends take it.
struct RandomBlockNoise {
    std::vector<std::vector<int16_t>> storage;
    std::vector<const int16_t*> blocks;
    std::vector<uint32_t> seams;
    av1::simd::BlockNoiseRow row;
    std::vector<int16_t> flat;

    RandomBlockNoise(int width, int block_width, int bd, std::mt19937& rng) {
        const int gmax = (128 << (bd - 8)) - 1;
        auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
        const int count = (width + block_width - 1) / block_width;
        for (int b = 0; b < count; b++) {
            // a random lead-in so that the blocks are not at any particular alignment
            std::vector<int16_t> buf(std::size_t(block_width + 2 + u(0, 7)));
            for (auto& v : buf) v = int16_t(u(-gmax - 1, gmax));
            storage.push_back(std::move(buf));
        }
        for (int b = 0; b < count; b++) blocks.push_back(storage[std::size_t(b)].data() + (storage[std::size_t(b)].size() - std::size_t(block_width) - 2));
        row.blocks = blocks.data();
        row.block_width = block_width;
        // no overlap, precomputed seams, or (up to 10 bits) the fade done in the kernel
        const int mode = u(0, bd <= 10 ? 2 : 1);
        if (mode == 1) {
            for (int b = 0; b < count; b++)
                seams.push_back(uint32_t(uint16_t(u(-gmax - 1, gmax))) | uint32_t(uint16_t(u(-gmax - 1, gmax))) << 16);
            row.seams = seams.data();
        } else if (mode == 2) {
            const bool subsampled = block_width == 16;
            row.fade = true;
            row.fade_old[0] = int16_t(subsampled ? 23 : 27), row.fade_old[1] = int16_t(subsampled ? 0 : 17);
            row.fade_new[0] = int16_t(subsampled ? 22 : 17), row.fade_new[1] = int16_t(subsampled ? 32 : 27);
            row.gmin = int16_t(-gmax - 1), row.gmax = int16_t(gmax);
        }
        for (int x = 0; x < width; x++) flat.push_back(row.at(x));
    }
};

TEST_P(SimdEquivalence, Av1BlendLumaAndChroma) {
    for (int iter = 0; iter < 300; iter++) {
        const int bd = std::array<int, 3>{8, 10, 12}[std::size_t(uniform(0, 2))];
        // widths past 256 cross the kernels' look-up chunks
        const int width = uniform(0, 3) ? uniform(1, 150) : uniform(240, 700), subx = uniform(0, 1);
        const int luma_width = subx ? width * 2 - uniform(0, 1) : width;
        const av1::ScalingLookup scaling = random_scaling(rng, bd);
        const int shift = uniform(8, 11);
        const av1::ClipLimits clip = av1::clip_limits(uniform(0, 1), bd, uniform(0, 2));
        const RandomBlockNoise luma_noise(width, 32, bd, rng);
        const RandomBlockNoise chroma_noise(width, 32 >> subx, bd, rng);
        av1::ChromaScalingIndex index{uniform(0, 3) == 0, uniform(-128, 127), uniform(-128, 127), uniform(-256, 255)};
        auto run = [&](auto zero) {
            using Pixel = decltype(zero);
            std::vector<Pixel> src(static_cast<std::size_t>(width)), luma(static_cast<std::size_t>(luma_width)), want(src.size()), got(src.size());
            // Uniform samples, or smooth ones (a level wandering by small steps), which the
            // 8-bit look-up serves from three LUT rows instead of all sixteen.
            const bool smooth = uniform(0, 1);
            auto fill = [&](std::vector<Pixel>& v) {
                int level = uniform(0, (1 << bd) - 1);
                for (auto& s : v) {
                    if (smooth)
                        level = std::clamp(level + uniform(-(2 << (bd - 8)), 2 << (bd - 8)), 0, (1 << bd) - 1);
                    s = Pixel(smooth ? level : uniform(0, (1 << bd) - 1));
                }
            };
            fill(src);
            fill(luma);
            av1::blend_luma_row<Pixel>(src.data(), want.data(), luma_noise.flat.data(), width, scaling, shift,
                                       clip.min_value, clip.max_luma);
            if constexpr (sizeof(Pixel) == 1)
                av1::simd::blend_luma_row_u8(src.data(), got.data(), luma_noise.row, width, scaling,
                                             shift, clip.min_value, clip.max_luma);
            else
                av1::simd::blend_luma_row_u16(src.data(), got.data(), luma_noise.row, width,
                                              scaling, shift, bd, clip.min_value, clip.max_luma);
            ASSERT_EQ(got, want) << "luma, iteration " << iter << " bd " << bd << " width " << width;
            av1::blend_chroma_row<Pixel>(src.data(), want.data(), luma.data(), luma_width, chroma_noise.flat.data(),
                                         width, subx, index, scaling, shift, bd, clip.min_value, clip.max_chroma);
            if constexpr (sizeof(Pixel) == 1)
                av1::simd::blend_chroma_row_u8(src.data(), got.data(), luma.data(), luma_width, chroma_noise.row,
                                               width, subx, index, scaling, shift, bd,
                                               clip.min_value, clip.max_chroma);
            else
                av1::simd::blend_chroma_row_u16(src.data(), got.data(), luma.data(), luma_width, chroma_noise.row,
                                                width, subx, index, scaling, shift, bd,
                                                clip.min_value, clip.max_chroma);
            ASSERT_EQ(got, want) << "chroma, iteration " << iter << " bd " << bd << " width " << width << " subx "
                                 << subx << " luma width " << luma_width;
            // in place, as the synthesizer runs on a decoder's picture
            std::vector<Pixel> in_place = src;
            if constexpr (sizeof(Pixel) == 1)
                av1::simd::blend_luma_row_u8(in_place.data(), in_place.data(), luma_noise.row, width,
                                             scaling, shift, clip.min_value, clip.max_luma);
            else
                av1::simd::blend_luma_row_u16(in_place.data(), in_place.data(), luma_noise.row, width,
                                              scaling, shift, bd, clip.min_value, clip.max_luma);
            av1::blend_luma_row<Pixel>(src.data(), want.data(), luma_noise.flat.data(), width, scaling, shift,
                                       clip.min_value, clip.max_luma);
            ASSERT_EQ(in_place, want) << "luma in place, iteration " << iter;
        };
        if (bd == 8)
            run(uint8_t{});
        else
            run(uint16_t{});
    }
}

// The 8-bit chroma scaling index where luma * luma_mult + chroma * mult leaves int16 (the
// AVX2 kernel's saturating multiply-add must still give the clipped index of the spec):
// extreme multipliers and offsets on all-bright, all-dark and alternating samples.
TEST_P(SimdEquivalence, Av1ChromaIndexAtExtremeMultipliers8Bit) {
    const int width = 300, luma_width = 2 * width;
    const av1::ScalingLookup scaling = random_scaling(rng, 8);
    const RandomBlockNoise noise(width, 16, 8, rng);
    for (int lm : {-128, -127, -1, 0, 127})
        for (int m : {-128, -64, 0, 100, 127})
            for (int offset : {-256, -1, 0, 255})
                for (int pattern = 0; pattern < 4; ++pattern) {
                    std::vector<uint8_t> src(width), luma(luma_width), want(width), got(width);
                    for (int i = 0; i < width; ++i)
                        src[std::size_t(i)] = uint8_t(pattern == 0 ? 255 : pattern == 1 ? 0 : pattern == 2 ? (i & 1) * 255 : uniform(0, 255));
                    for (int i = 0; i < luma_width; ++i)
                        luma[std::size_t(i)] = uint8_t(pattern == 0 ? 255 : pattern == 1 ? 0 : pattern == 2 ? ((i >> 1) & 1) * 255 : uniform(0, 255));
                    const av1::ChromaScalingIndex index{false, lm, m, offset};
                    av1::blend_chroma_row<uint8_t>(src.data(), want.data(), luma.data(), luma_width, noise.flat.data(),
                                                   width, 1, index, scaling, 9, 8, 0, 255);
                    av1::simd::blend_chroma_row_u8(src.data(), got.data(), luma.data(), luma_width, noise.row, width, 1,
                                                   index, scaling, 9, 8, 0, 255);
                    ASSERT_EQ(got, want) << "luma_mult " << lm << " mult " << m << " offset " << offset << " pattern "
                                         << pattern;
                }
}


TEST_P(SimdEquivalence, Av1NoiseStripeRows) {
    for (int iter = 0; iter < 60; iter++) {
        const int bd = std::array<int, 3>{8, 10, 12}[std::size_t(uniform(0, 2))];
        const int sx = uniform(0, 1), sy = uniform(0, 1);
        Av1FilmGrainParams p = test_support::random_av1_params(rng, false);
        p.num_y_points = std::max(p.num_y_points, 0);
        const av1::GrainTemplate luma = av1::generate_luma_template(p, bd);
        const int luma_width = uniform(1, 200), stripe = uniform(0, 40);
        const bool overlap = uniform(0, 1);
        const int blocks = av1::num_blocks_across(luma_width);
        const av1::NoiseStripe want = av1::build_noise_stripe(
            sx || sy ? av1::generate_chroma_template(p, bd, 1, sx, sy, luma) : luma,
            av1::stripe_block_offsets(p.grain_seed, stripe, blocks), sx, sy, overlap, bd);
        ASSERT_EQ(want.width, av1::noise_stripe_width(luma_width, sx));
        // The optimized path's rows: every block's template origin, then each row assembled
        // block by block with the horizontal overlap faded in the kernel (up to 10 bits) or
        // from precomputed seams.
        const av1::GrainTemplate tmpl = sx || sy ? av1::generate_chroma_template(p, bd, 1, sx, sy, luma) : luma;
        std::vector<int32_t> origins(std::size_t(blocks), 0);
        av1::stripe_block_origins(tmpl, av1::stripe_block_offsets(p.grain_seed, stripe, blocks).data(), blocks, sx, sy,
                                  origins.data());
        const int bw = 32 >> sx, width = blocks * bw;
        std::vector<const int16_t*> block_rows(static_cast<std::size_t>(blocks));
        std::vector<uint32_t> seams(static_cast<std::size_t>(blocks));
        std::vector<int16_t> got(static_cast<std::size_t>(width));
        for (int y = 0; y < want.height; y++) {
            for (int b = 0; b < blocks; b++)
                block_rows[std::size_t(b)] = tmpl.samples.data() + std::ptrdiff_t(y) * tmpl.width + origins[std::size_t(b)];
            av1::simd::BlockNoiseRow row = av1::kernel_faded_row(sx, bd);
            row.blocks = block_rows.data();
            row.fade = overlap && bd <= 10 && uniform(0, 1);
            if (overlap && !row.fade) {
                av1::overlap_seams(block_rows.data(), blocks, sx, bd, seams.data());
                row.seams = seams.data();
            }
            av1::simd::assemble_noise_row(row, width, got.data());
            for (int x = 0; x < width; x++)
                ASSERT_EQ(got[std::size_t(x)], want.at(y, x)) << "row " << y << " x " << x << " bd " << bd;
        }
    }
    // cross_fade_row against the overlap formula of build_stripe_noise
    for (int iter = 0; iter < 100; iter++) {
        const int bd = uniform(8, 12), width = uniform(1, 100);
        const int gmin = -(128 << (bd - 8)), gmax = (128 << (bd - 8)) - 1;
        std::vector<int16_t> old_row(static_cast<std::size_t>(width)), cur(old_row.size());
        for (auto& v : old_row) v = int16_t(uniform(gmin, gmax));
        for (auto& v : cur) v = int16_t(uniform(gmin, gmax));
        const int wo = std::array<int, 3>{27, 17, 23}[std::size_t(uniform(0, 2))], wn = uniform(17, 27);
        std::vector<int16_t> want = cur;
        for (int x = 0; x < width; x++)
            want[std::size_t(x)] = int16_t(std::clamp((old_row[std::size_t(x)] * wo + cur[std::size_t(x)] * wn + 16) >> 5, gmin, gmax));
        av1::simd::cross_fade_row(old_row.data(), cur.data(), width, wo, wn, gmin, gmax);
        ASSERT_EQ(cur, want);
    }
}

// The rows a stripe shares with the one above, assembled and cross-faded in one pass (up to
// 10 bits), against the reference's whole stripe with the vertical overlap.
TEST_P(SimdEquivalence, Av1CrossFadedStripeRows) {
    for (int iter = 0; iter < 60; iter++) {
        const int bd = uniform(0, 1) ? 10 : 8;
        const int sx = uniform(0, 1), sy = uniform(0, 1);
        Av1FilmGrainParams p = test_support::random_av1_params(rng, false);
        const av1::GrainTemplate luma = av1::generate_luma_template(p, bd);
        const av1::GrainTemplate tmpl = sx || sy ? av1::generate_chroma_template(p, bd, 1, sx, sy, luma) : luma;
        const int luma_width = uniform(1, 200), stripe = uniform(1, 40);
        const int pw = (luma_width + sx) >> sx, ph = ((stripe + 1) * 32 + sy) >> sy;
        const av1::StripeNoise want =
            av1::build_stripe_noise(tmpl, p.grain_seed, stripe, luma_width, pw, ph, sx, sy, true, bd);
        const int blocks = av1::num_blocks_across(luma_width);
        std::vector<int32_t> above_origins(std::size_t(blocks), 0), own_origins(above_origins.size(), 0);
        av1::stripe_block_origins(tmpl, av1::stripe_block_offsets(p.grain_seed, stripe - 1, blocks).data(), blocks, sx,
                                  sy, above_origins.data());
        av1::stripe_block_origins(tmpl, av1::stripe_block_offsets(p.grain_seed, stripe, blocks).data(), blocks, sx,
                                  sy, own_origins.data());
        std::vector<const int16_t*> above_rows(static_cast<std::size_t>(blocks)), own_rows(above_rows.size());
        for (int i = 0; i < (2 >> sy); i++) {
            auto row_of = [&](const std::vector<int32_t>& origins, int y, std::vector<const int16_t*>& pointers) {
                for (int b = 0; b < blocks; b++)
                    pointers[std::size_t(b)] = tmpl.samples.data() + std::ptrdiff_t(y) * tmpl.width + origins[std::size_t(b)];
                av1::simd::BlockNoiseRow row = av1::kernel_faded_row(sx, bd);
                row.blocks = pointers.data();
                return row;
            };
            const av1::OverlapWeights w = av1::overlap_weights(i, sy);
            std::vector<int16_t> got(std::size_t(pw) + 3, int16_t(0x7777));
            av1::simd::assemble_cross_faded_row(row_of(above_origins, (32 >> sy) + i, above_rows),
                                                row_of(own_origins, i, own_rows), pw, w.old_weight, w.new_weight,
                                                got.data());
            for (int x = 0; x < pw; x++)
                ASSERT_EQ(got[std::size_t(x)], want.row(i)[x]) << "row " << i << " x " << x << " bd " << bd << " sx " << sx;
            for (std::size_t x = std::size_t(pw); x < got.size(); x++) ASSERT_EQ(got[x], int16_t(0x7777)) << "wrote past the row";
        }
    }
}

// The co-sited luma averages both chroma planes share above 8 bits: odd luma widths (the last
// column pairs the last sample with itself), widths around the vector steps, the largest
// samples of each depth (sums at the top of int16 at 12 bits), samples of any 16-bit value
// in some rows (bad input), and nothing written past the row.
TEST_P(SimdEquivalence, Av1CoSitedLumaRow) {
    for (int iter = 0; iter < 400; iter++) {
        const int bd = uniform(0, 1) ? 10 : 12;
        const int luma_width = uniform(0, 2) ? uniform(1, 140) : uniform(140, 2000);
        const int width = (luma_width + 1) / 2;
        const int top = uniform(0, 7) == 0 ? 65535 : (1 << bd) - 1;
        const bool all_top = uniform(0, 3) == 0;
        std::vector<uint16_t> luma(std::size_t(luma_width) + 64);
        std::vector<uint16_t> want(static_cast<std::size_t>(width));
        std::vector<uint16_t> got(std::size_t(width) + 40, uint16_t(0x7777));
        for (auto& v : luma) v = uint16_t(all_top ? top : uniform(0, top));
        av1::co_sited_luma_row<uint16_t>(luma.data(), luma_width, width, want.data());
        av1::simd::co_sited_luma_row_u16(luma.data(), luma_width, width, got.data());
        for (int x = 0; x < width; x++)
            ASSERT_EQ(got[std::size_t(x)], want[std::size_t(x)]) << "x " << x << " bd " << bd << " luma width " << luma_width;
        for (std::size_t x = std::size_t(width); x < got.size(); x++)
            ASSERT_EQ(got[x], uint16_t(0x7777)) << "wrote past the row, luma width " << luma_width;
        // the reference against the spec's per-sample form
        av1::ChromaScalingIndex from_luma;
        from_luma.from_luma = true;
        for (int x = 0; x < width; x++)
            ASSERT_EQ(int(want[std::size_t(x)]), av1::chroma_scaling_index(luma.data(), luma_width, x, 1, 0, from_luma, bd));
    }
}

TEST_P(SimdEquivalence, Av1WholeFrames) {
    const ChromaFormat formats[] = {ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444, ChromaFormat::k400};
    av1::Av1PictureSynthesis optimized(3, av1::Kernels::kOptimized);
    for (int iter = 0; iter < 24; iter++) {
        const int bd = std::array<int, 3>{8, 10, 12}[std::size_t(uniform(0, 2))];
        const ChromaFormat cf = formats[uniform(0, 3)];
        const int w = uniform(1, 180), h = uniform(1, 150);
        Av1FilmGrainParams p;
        for (;;) {  // draw until the set is valid for the format (e.g. 4:2:0 chroma point rules)
            p = test_support::random_av1_params(rng, cf == ChromaFormat::k400);
            try {
                av1::Av1SynthesisContext check(p, cf, bd, 16, 16, 1);
                break;
            } catch (const Error&) {
            }
        }
        const int mc = uniform(0, 2);
        StridedFrame src(w, h, cf, bd, uniform(0, 17), uniform(0, 1), rng);
        StridedFrame want = src, got = src, in_place = src;
        av1::apply_film_grain(p, src.view, want.view, mc);  // scalar reference, one thread
        optimized.apply(p, src.view, got.view, mc);
        ASSERT_EQ(got.diff(want), "") << "iteration " << iter << " " << w << "x" << h << " bd " << bd;
        optimized.apply(p, in_place.view, in_place.view, mc);
        ASSERT_EQ(in_place.diff(want), "") << "in place, iteration " << iter;
    }
}

FgcParams random_fgc_params(std::mt19937& rng, int bd) {
    auto u = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    FgcParams p;
    p.log2_scale_factor = u(2, 7);
    for (int c = 0; c < 3; c++) {
        auto& m = p.comp[std::size_t(c)];
        m.comp_model_present_flag = u(0, 4) != 0;
        if (!m.comp_model_present_flag) continue;
        m.num_model_values_minus1 = 2;
        const int n = u(1, 3);
        int lo = u(0, 40);
        m.intervals.clear();
        for (int i = 0; i < n && lo < 255; i++) {
            const int hi = std::min(255, lo + u(10, 120));
            m.intervals.push_back({lo, hi, {u(0, 255) << (bd - 8) >> u(0, bd - 8), u(2, 14), u(2, 14)}});
            lo = hi + 1 + u(0, 20);
        }
    }
    return p;
}

TEST_P(SimdEquivalence, FgcWholeFrames) {
    const ChromaFormat formats[] = {ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444, ChromaFormat::k400};
    int synthesized = 0;
    for (int iter = 0; iter < 30; iter++) {
        const int bd = std::array<int, 4>{8, 8, 10, 12}[std::size_t(uniform(0, 3))];
        const ChromaFormat cf = formats[uniform(0, 3)];
        const int w = uniform(1, 200), h = uniform(1, 140);
        FgcOptions o;
        o.flavour = uniform(0, 1) ? FgcFlavour::kVtm : FgcFlavour::kRdd5;
        o.block_size = o.flavour == FgcFlavour::kVtm ? 8 << uniform(0, 2) : 0;
        o.threads = uniform(1, 3);
        FgcOptions ref = o;
        ref.reference_kernels = true;
        ref.threads = 1;
        FgcStreamSynthesis fast(o), slow(ref);
        const FgcParams params = random_fgc_params(rng, bd);
        StridedFrame src(w, h, cf, bd, uniform(0, 17), uniform(0, 1), rng);
        StridedFrame want = src, got = src, in_place = src;
        const FgcPictureIds ids{uniform(0, 300), uniform(0, 3)};
        slow.receive_sei(params);
        fast.receive_sei(params);
        try {
            slow.apply(src.view, want.view, ids);
        } catch (const Error&) {
            EXPECT_THROW(fast.apply(src.view, got.view, ids), Error);  // same validation either way
            continue;
        }
        fast.apply(src.view, got.view, ids);
        ASSERT_EQ(got.diff(want), "") << "iteration " << iter << " " << w << "x" << h << " bd " << bd << " flavour "
                                      << int(o.flavour) << " block " << o.block_size;
        fast.apply(in_place.view, in_place.view, ids);
        ASSERT_EQ(in_place.diff(want), "") << "in place, iteration " << iter;
        synthesized++;
    }
    EXPECT_GE(synthesized, 15) << "too few random parameter sets were valid to prove anything";
}

// Many narrow intervals (more than ScaledTemplates::kMaxIntervals, so blocks are scaled as
// they are used) and few wide ones (scaled tables) alternate through one optimized
// synthesizer: the tables must follow every change of the parameter set.
TEST_P(SimdEquivalence, FgcChangingSetsAndManyIntervals) {
    auto many_intervals = [&](int bd) {
        // at most 10 distinct cut-off pairs in a set (RDD 5 / HM): draw from four
        const int cutoffs[4][2] = {{uniform(2, 14), uniform(2, 14)}, {8, 8}, {uniform(2, 14), 4}, {14, uniform(2, 14)}};
        FgcParams p;
        p.log2_scale_factor = uniform(3, 6);
        for (int c = 0; c < 3; c++) {
            auto& m = p.comp[std::size_t(c)];
            m.comp_model_present_flag = true;
            m.num_model_values_minus1 = 2;
            for (int lo = 0; lo <= 255;) {
                const int hi = std::min(255, lo + uniform(0, 11));
                const auto& cut = cutoffs[uniform(0, 3)];
                m.intervals.push_back({lo, hi, {uniform(0, 255) << (bd - 8) >> uniform(0, bd - 8), cut[0], cut[1]}});
                lo = hi + 1;
            }
        }
        return p;
    };
    int synthesized = 0, scaled_as_used = 0;
    for (int iter = 0; iter < 8; iter++) {
        const int bd = uniform(0, 1) ? 8 : 10;
        FgcOptions o;
        o.flavour = uniform(0, 1) ? FgcFlavour::kVtm : FgcFlavour::kRdd5;
        // vtm takes HM's picture sizes only (128.. samples, multiples of 4)
        const bool vtm = o.flavour == FgcFlavour::kVtm;
        const int w = vtm ? 4 * uniform(32, 50) : uniform(17, 150), h = vtm ? 4 * uniform(32, 40) : uniform(9, 90);
        o.block_size = o.flavour == FgcFlavour::kVtm ? 8 << uniform(0, 2) : 0;
        o.threads = uniform(1, 2);
        FgcStreamSynthesis fast(o);
        FgcParams params;
        for (int frame = 0; frame < 6; frame++) {
            // a new set, then the same set with one value changed (the tables must notice), ...
            if (frame == 2)
                params = many_intervals(bd);
            else if (frame % 3 == 0)
                params = random_fgc_params(rng, bd);
            else if (frame == 1)
                params.log2_scale_factor = params.log2_scale_factor == 7 ? 2 : params.log2_scale_factor + 1;
            else
                for (auto& m : params.comp)
                    if (!m.intervals.empty()) m.intervals[0].comp_model_value[0] ^= 1;
            for (auto& m : params.comp) scaled_as_used += m.intervals.size() > 16;
            FgcOptions ref = o;
            ref.reference_kernels = true;
            ref.threads = 1;
            FgcStreamSynthesis slow(ref);
            StridedFrame src(w, h, ChromaFormat::k420, bd, uniform(0, 9), false, rng);
            StridedFrame want = src, got = src;
            const FgcPictureIds ids{frame, 0};
            slow.receive_sei(params);
            fast.receive_sei(params);
            try {
                slow.apply(src.view, want.view, ids);
            } catch (const Error&) {
                EXPECT_THROW(fast.apply(src.view, got.view, ids), Error);
                continue;
            }
            fast.apply(src.view, got.view, ids);
            ASSERT_EQ(got.diff(want), "") << "iteration " << iter << " frame " << frame << " " << w << "x" << h
                                          << " bd " << bd << " flavour " << int(o.flavour);
            synthesized++;
        }
    }
    EXPECT_GE(synthesized, 24);
    EXPECT_GT(scaled_as_used, 0);
}

INSTANTIATE_TEST_SUITE_P(Targets, SimdEquivalence, ::testing::ValuesIn(simd::available_targets()),
                         [](const ::testing::TestParamInfo<simd::Target>& i) { return i.param.name; });

TEST(SimdTargets, SomeTargetIsAvailableAndForcingWorks) {
    const auto targets = simd::available_targets();
    ASSERT_FALSE(targets.empty());
    EXPECT_FALSE(simd::force_target(targets.front().bits | targets.back().bits | (int64_t(1) << 40)))
        << "anything but one available target must be refused";
    EXPECT_FALSE(simd::force_target(std::string("no-such-target")));
    EXPECT_TRUE(simd::force_target(targets.back().name));
    EXPECT_EQ(simd::dispatched_target(), targets.back().name);
    simd::force_target(0);
    EXPECT_EQ(simd::dispatched_target(), targets.front().name);
}

}  // namespace

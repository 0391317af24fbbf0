// The ffmpeg flavour: FFmpeg's departures from RDD 5, stage by stage (parameters, block
// average, deblocking), and rdd5's output wherever none of them applies. The goldens
// (conformance/ffmpeg71-*) check the whole against FFmpeg 7.1 itself.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <vector>

#include "error_message.hpp"
#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "fgc/deblocking.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "fgc/local_adaptation.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;
using namespace filmgrain::fgc;

namespace {

using filmgrain::test_support::error_of;

FgcParams one_component(int nmv, std::vector<FgcIntensityInterval> intervals) {
    FgcParams p;
    p.log2_scale_factor = 5;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = nmv - 1;
    p.comp[0].intervals = std::move(intervals);
    p.comp[1] = p.comp[0];
    return p;
}

const PictureFormat k420{ChromaFormat::k420, 8, 64, 64};

TEST(FgcFfmpegFlavour, CutOffsNotSignalledAreZeroClippedToTwo) {
    // one value: RDD 5 infers 8 and 8; FFmpeg leaves 0, clipped to 2 (chroma: 0 << 1, clipped)
    ResolvedFgc r = resolve_fgc_params(one_component(1, {{0, 255, {40}}}), FgcFlavour::kFfmpeg, k420);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_h, 2);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_v, 2);
    EXPECT_EQ(r.comp[1].intervals[0].cutoff_h, 2);
    EXPECT_EQ(r.comp[1].intervals[0].scale, 20);
    ResolvedFgc rdd5 = resolve_fgc_params(one_component(1, {{0, 255, {40}}}), FgcFlavour::kRdd5, k420);
    EXPECT_EQ(rdd5.comp[0].intervals[0].cutoff_h, 8);
    EXPECT_EQ(rdd5.comp[0].intervals[0].cutoff_v, 8);
    // two values: the vertical one is 0 (RDD 5: equal to the horizontal one)
    r = resolve_fgc_params(one_component(2, {{0, 255, {40, 6}}}), FgcFlavour::kFfmpeg, k420);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_h, 6);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_v, 2);
    EXPECT_EQ(r.comp[1].intervals[0].cutoff_h, 12);
    EXPECT_EQ(r.comp[1].intervals[0].cutoff_v, 2);
}

TEST(FgcFfmpegFlavour, CutOffsOutsideTwoToFourteenAreClippedNotRefused) {
    const FgcParams p = one_component(3, {{0, 255, {40, 1, 20}}});
    EXPECT_NE(error_of([&] { resolve_fgc_params(p, FgcFlavour::kRdd5, k420); }).find("comp_model_value[0][0][1] = 1"),
              std::string::npos);
    const ResolvedFgc r = resolve_fgc_params(p, FgcFlavour::kFfmpeg, k420);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_h, 2);
    EXPECT_EQ(r.comp[0].intervals[0].cutoff_v, 14);
}

TEST(FgcFfmpegFlavour, FirstSignalledIntervalWinsAndEmptyOnesHoldNothing) {
    const FgcParams p = one_component(3, {{50, 40, {10, 8, 8}}, {0, 100, {20, 8, 8}}, {90, 200, {30, 8, 8}}});
    EXPECT_NE(error_of([&] { resolve_fgc_params(p, FgcFlavour::kRdd5, k420); }), "");
    const ResolvedFgc r = resolve_fgc_params(p, FgcFlavour::kFfmpeg, k420);
    EXPECT_EQ(r.comp[0].interval_of_intensity[45], 1);   // not the empty [50, 40]
    EXPECT_EQ(r.comp[0].interval_of_intensity[95], 1);   // the overlap goes to the earlier
    EXPECT_EQ(r.comp[0].interval_of_intensity[150], 2);
    EXPECT_EQ(r.comp[0].interval_of_intensity[201], -1);  // a gap: no grain
}

TEST(FgcFfmpegFlavour, WhatFfmpegIgnoresIsAcceptedAndWhatItRefusesIsNamed) {
    FgcParams p = one_component(3, {{0, 255, {40, 8, 8}}});
    p.blending_mode_id = 1;
    p.separate_colour_description_present_flag = true;
    p.film_grain_bit_depth_luma_minus8 = 2;
    const ResolvedFgc r = resolve_fgc_params(p, FgcFlavour::kFfmpeg, k420);
    EXPECT_EQ(r.blending_mode_id, 0);
    EXPECT_EQ(r.grain_bit_depth[0], 8);
    p.film_grain_model_id = 1;
    const std::string e = error_of([&] { resolve_fgc_params(p, FgcFlavour::kFfmpeg, k420); });
    EXPECT_NE(e.find("film_grain_model_id = 1"), std::string::npos) << e;
    EXPECT_NE(e.find("ffmpeg flavour"), std::string::npos) << e;
    p.film_grain_model_id = 0;
    p.log2_scale_factor = 1;
    EXPECT_NE(error_of([&] { resolve_fgc_params(p, FgcFlavour::kFfmpeg, k420); }).find("log2_scale_factor = 1"),
              std::string::npos);
}

TEST(FgcFfmpegFlavour, PartialBlocksAverageZeroPastThePlane) {
    FrameBuffer f(12, 10, PixelFormat{ChromaFormat::k400, 8});
    FrameView v = f.view();
    for (int y = 0; y < 10; y++)
        for (int x = 0; x < 12; x++) v.planes[0].row<uint8_t>(y)[x] = 200;
    EXPECT_EQ(block_average_zero_outside<uint8_t>(v.planes[0], 0, 0, 8, 8), 200);
    // 4 x 2 samples of 200 inside, the rest of the 64 read as zero
    EXPECT_EQ(block_average_zero_outside<uint8_t>(v.planes[0], 8, 8, 8, 8), (8 * 200) >> 6);
    EXPECT_EQ(block_average_inside<uint8_t>(v.planes[0], 8, 8, 8, 8), 200);
}

TEST(FgcFfmpegFlavour, OnlyEdgesBeforeABlockWithGrainAreDeblocked) {
    const int stride = 34, width = 32;
    std::mt19937 rng(3);
    for (int trial = 0; trial < 200; trial++) {
        std::vector<int32_t> g(std::size_t(stride) * 2), all, masked;
        for (auto& x : g) x = int32_t(rng() % 255) - 127;
        const uint8_t every[4] = {1, 1, 1, 1};
        all = g;
        deblock_stripe_vertical_edges(all.data(), stride, 2, width, 8);
        masked = g;
        deblock_stripe_vertical_edges(masked.data(), stride, 2, width, 8, every);
        ASSERT_EQ(masked, all);
        const uint8_t mask[4] = {1, 0, 1, uint8_t(trial & 1)};
        masked = g;
        deblock_stripe_vertical_edges(masked.data(), stride, 2, width, 8, mask);
        for (int y = 0; y < 2; y++) {
            const int32_t* m = masked.data() + y * stride;
            const int32_t* a = all.data() + y * stride;
            const int32_t* o = g.data() + y * stride;
            EXPECT_EQ(m[7], o[7]);  // the block at 8 has no grain: edge 8 untouched
            EXPECT_EQ(m[8], o[8]);
            EXPECT_EQ(m[15], a[15]);  // edge 16 filtered as always
            EXPECT_EQ(m[16], a[16]);
            EXPECT_EQ(m[24], (trial & 1) ? a[24] : o[24]);
        }
    }
}

// Without any departure in play (intervals cover every average, three values, a picture of
// whole blocks), the ffmpeg flavour is rdd5 bit for bit.
TEST(FgcFfmpegFlavour, EqualsRdd5WhereNoDepartureApplies) {
    std::mt19937 rng(11);
    FrameBuffer src(96, 64, PixelFormat{ChromaFormat::k420, 8});
    for (std::size_t i = 0; i < src.byte_size(); i++) src.bytes()[i] = uint8_t(rng());
    FgcParams p = one_component(3, {{0, 120, {50, 6, 9}}, {121, 255, {90, 11, 4}}});
    p.comp[2] = p.comp[0];
    std::string md5[2];
    int k = 0;
    for (FgcFlavour f : {FgcFlavour::kRdd5, FgcFlavour::kFfmpeg}) {
        FgcOptions o;
        o.flavour = f;
        o.threads = 2;
        FgcStreamSynthesis s(o);
        s.receive_sei(p);
        FrameBuffer dst(96, 64, src.format());
        s.apply(src.view(), dst.view(), FgcPictureIds{5, 0});
        md5[k++] = md5_hex(dst.bytes(), dst.byte_size());
    }
    EXPECT_EQ(md5[0], md5[1]);
}

TEST(FgcFfmpegFlavour, BlockSizeOtherThanEightIsRefused) {
    FgcOptions o;
    o.flavour = FgcFlavour::kFfmpeg;
    o.block_size = 16;
    const std::string e = error_of([&] { FgcStreamSynthesis s(o); });
    EXPECT_NE(e.find("block_size = 16"), std::string::npos) << e;
}

}  // namespace

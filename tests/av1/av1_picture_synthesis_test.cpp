// Whole-frame AV1 synthesis: block/stripe structure, formats, aliasing,
// stripe independence and parameter validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "av1/av1_picture_synthesis.hpp"
#include "av1/block_synthesis.hpp"
#include "av1/params_validation.hpp"
#include "core/frame_buffer.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;
using namespace filmgrain::av1;

namespace {

Av1FilmGrainParams full_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 777;
    p.num_y_points = 3;
    p.point_y_value = {0, 128, 255};
    p.point_y_scaling = {60, 120, 40};
    p.num_cb_points = 2;
    p.point_cb_value = {0, 255};
    p.point_cb_scaling = {80, 80};
    p.num_cr_points = 2;
    p.point_cr_value = {16, 200};
    p.point_cr_scaling = {30, 90};
    p.grain_scaling_minus_8 = 1;
    p.ar_coeff_lag = 2;
    for (int i = 0; i < 24; ++i) p.ar_coeffs_y_plus_128[i] = 128 + (i % 5) * 3 - 6;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cb_plus_128[i] = 128 + (i % 7) - 3;
    for (int i = 0; i < 25; ++i) p.ar_coeffs_cr_plus_128[i] = 128 - (i % 4) + 1;
    p.ar_coeff_shift_minus_6 = 1;
    p.cb_mult = 140;
    p.cb_luma_mult = 180;
    p.cb_offset = 250;
    p.cr_mult = 100;
    p.cr_luma_mult = 200;
    p.cr_offset = 270;
    p.overlap_flag = 1;
    return p;
}

FrameBuffer random_frame(int w, int h, ChromaFormat cf, int bd, unsigned seed = 1) {
    FrameBuffer f(w, h, PixelFormat{cf, bd});
    std::mt19937 rng(seed);
    if (bd == 8) {
        for (std::size_t i = 0; i < f.byte_size(); ++i) f.bytes()[i] = static_cast<uint8_t>(rng());
    } else {
        auto* s = reinterpret_cast<uint16_t*>(f.bytes());
        for (std::size_t i = 0; i < f.byte_size() / 2; ++i) s[i] = static_cast<uint16_t>(rng() & ((1u << bd) - 1));
    }
    return f;
}

std::vector<uint8_t> bytes_of(const FrameBuffer& f) { return {f.bytes(), f.bytes() + f.byte_size()}; }

std::string error_message(const Av1FilmGrainParams& p, ChromaFormat cf = ChromaFormat::k420, int bd = 8) {
    try {
        validate_params(p, cf, bd);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Av1BlockSynthesis, StripeCounts) {
    EXPECT_EQ(num_blocks_across(1), 1);
    EXPECT_EQ(num_blocks_across(32), 1);
    EXPECT_EQ(num_blocks_across(33), 2);
    EXPECT_EQ(num_stripes(61), 2);
    EXPECT_EQ(num_stripes(1080), 34);
}

TEST(Av1BlockSynthesis, NoOverlapCopiesTemplateWindows) {
    const auto p = full_params();
    const auto t = generate_luma_template(p, 8);
    const auto offs = stripe_block_offsets(p.grain_seed, 2, 3);
    const auto s = build_noise_stripe(t, offs, 0, 0, false, 8);
    EXPECT_EQ(s.width, 3 * 32 + 2);
    EXPECT_EQ(s.height, 34);
    for (int b = 0; b < 3; ++b) {
        const int ox = 9 + 2 * (offs[b] >> 4), oy = 9 + 2 * (offs[b] & 15);
        for (int y = 0; y < 34; ++y)
            for (int x = 0; x < 32; ++x) ASSERT_EQ(s.at(y, b * 32 + x), t.at(oy + y, ox + x));
    }
    // 4:2:0 chroma: 16x16 blocks plus one overlap column/row, offsets 6 + o.
    const auto c = generate_chroma_template(p, 8, 1, 1, 1, t);
    const auto sc = build_noise_stripe(c, offs, 1, 1, false, 8);
    EXPECT_EQ(sc.width, 3 * 16 + 1);
    EXPECT_EQ(sc.height, 17);
    EXPECT_EQ(sc.at(5, 16 + 7), c.at(6 + (offs[1] & 15) + 5, 6 + (offs[1] >> 4) + 7));
}

TEST(Av1BlockSynthesis, HorizontalOverlapWeights) {
    const auto p = full_params();
    const auto t = generate_luma_template(p, 8);
    const auto offs = stripe_block_offsets(p.grain_seed, 0, 2);
    const auto plain = build_noise_stripe(t, offs, 0, 0, false, 8);
    const auto blended = build_noise_stripe(t, offs, 0, 0, true, 8);
    const int ox0 = 9 + 2 * (offs[0] >> 4), oy0 = 9 + 2 * (offs[0] & 15);
    for (int y = 0; y < 34; ++y) {
        const int old0 = t.at(oy0 + y, ox0 + 32), old1 = t.at(oy0 + y, ox0 + 33);
        const int new0 = plain.at(y, 32), new1 = plain.at(y, 33);
        EXPECT_EQ(blended.at(y, 32), std::clamp((old0 * 27 + new0 * 17 + 16) >> 5, -128, 127));
        EXPECT_EQ(blended.at(y, 33), std::clamp((old1 * 17 + new1 * 27 + 16) >> 5, -128, 127));
        EXPECT_EQ(blended.at(y, 34), plain.at(y, 34));
    }
}

TEST(Av1BlockSynthesis, VerticalOverlapUsesPreviousStripe) {
    const auto p = full_params();
    const auto t = generate_luma_template(p, 8);
    const int w = 70, h = 100;
    const auto s1 = build_stripe_noise(t, p.grain_seed, 1, w, w, h, 0, 0, true, 8);
    const auto prev = build_noise_stripe(t, stripe_block_offsets(p.grain_seed, 0, 3), 0, 0, true, 8);
    const auto cur = build_noise_stripe(t, stripe_block_offsets(p.grain_seed, 1, 3), 0, 0, true, 8);
    EXPECT_EQ(s1.rows, 32);
    for (int x = 0; x < w; ++x) {
        EXPECT_EQ(s1.row(0)[x], std::clamp((prev.at(32, x) * 27 + cur.at(0, x) * 17 + 16) >> 5, -128, 127));
        EXPECT_EQ(s1.row(1)[x], std::clamp((prev.at(33, x) * 17 + cur.at(1, x) * 27 + 16) >> 5, -128, 127));
        EXPECT_EQ(s1.row(2)[x], cur.at(2, x));
    }
    // The last stripe is cut to the picture.
    EXPECT_EQ(build_stripe_noise(t, p.grain_seed, 3, w, w, h, 0, 0, true, 8).rows, 4);
}

TEST(Av1Synthesis, ApplyGrainZeroCopies) {
    Av1FilmGrainParams p;  // apply_grain = 0
    p.num_y_points = 99;   // ignored when apply_grain is 0
    auto src = random_frame(50, 30, ChromaFormat::k420, 10);
    FrameBuffer dst(50, 30, src.format());
    apply_film_grain(p, src.view(), dst.view(), 2);
    EXPECT_EQ(bytes_of(src), bytes_of(dst));
}

TEST(Av1Synthesis, PlanesWithoutPointsAreUntouched) {
    auto p = full_params();
    p.num_cb_points = p.num_cr_points = 0;
    auto src = random_frame(64, 64, ChromaFormat::k420, 8);
    FrameBuffer dst(64, 64, src.format());
    std::memset(dst.bytes(), 0xAB, dst.byte_size());
    apply_film_grain(p, src.view(), dst.view(), 2);
    EXPECT_NE(0, std::memcmp(dst.bytes(), src.bytes(), dst.plane_bytes(0)));
    for (int pl = 1; pl < 3; ++pl)
        EXPECT_EQ(0, std::memcmp(dst.bytes() + dst.plane_offset(pl), src.bytes() + src.plane_offset(pl),
                                 dst.plane_bytes(pl)));
    // No luma points (4:4:4, where chroma points may still be signalled).
    auto q = full_params();
    q.num_y_points = 0;
    auto src444 = random_frame(40, 40, ChromaFormat::k444, 8);
    FrameBuffer dst444(40, 40, src444.format());
    apply_film_grain(q, src444.view(), dst444.view(), 2);
    EXPECT_EQ(0, std::memcmp(dst444.bytes(), src444.bytes(), dst444.plane_bytes(0)));
    EXPECT_NE(0, std::memcmp(dst444.bytes() + dst444.plane_offset(1), src444.bytes() + src444.plane_offset(1),
                             dst444.plane_bytes(1)));
}

TEST(Av1Synthesis, InPlaceStripesAndNegativeStrideAgree) {
    struct Fmt {
        ChromaFormat cf;
        int bd;
    } fmts[] = {{ChromaFormat::k420, 8}, {ChromaFormat::k422, 10}, {ChromaFormat::k444, 12}, {ChromaFormat::k400, 8}};
    for (auto f : fmts)
        for (auto [w, h] : {std::pair{97, 61}, std::pair{33, 95}, std::pair{1, 1}, std::pair{64, 64}}) {
            auto p = full_params();
            if (f.cf == ChromaFormat::k400) p.num_cb_points = p.num_cr_points = 0;
            if (f.cf == ChromaFormat::k420 && w == 1) p.chroma_scaling_from_luma = 0;
            auto src = random_frame(w, h, f.cf, f.bd, static_cast<unsigned>(w * h));
            const auto orig = bytes_of(src);
            FrameBuffer ref(w, h, src.format());
            apply_film_grain(p, src.view(), ref.view(), 2);
            EXPECT_EQ(bytes_of(src), orig);

            auto inplace = src;
            apply_film_grain(p, inplace.view(), inplace.view(), 2);
            EXPECT_EQ(bytes_of(inplace), bytes_of(ref)) << w << "x" << h;

            // Stripes one at a time in reverse order.
            FrameBuffer striped(w, h, src.format());
            Av1SynthesisContext ctx(p, f.cf, f.bd, w, h, 2);
            for (int s = ctx.stripe_count() - 1; s >= 0; --s) ctx.apply_stripes(src.view(), striped.view(), s, s + 1);
            EXPECT_EQ(bytes_of(striped), bytes_of(ref));

            // Bottom-up views (negative strides) of the same frames.
            auto flip = [](FrameView v) {
                for (int pl = 0; pl < v.plane_count(); ++pl) {
                    const int ph = plane_height(v.format, pl, v.height);
                    v.planes[pl].data += v.planes[pl].stride * (ph - 1);
                    v.planes[pl].stride = -v.planes[pl].stride;
                }
                return v;
            };
            // Flipping both views reverses row order, which changes the
            // picture; instead flip the rows of the data and compare flipped.
            auto src_flipped = src;
            FrameView sv = src_flipped.view(), fv = flip(src.view());
            for (int pl = 0; pl < sv.plane_count(); ++pl) {
                const int ph = plane_height(sv.format, pl, h);
                const std::size_t rb = static_cast<std::size_t>(plane_width(sv.format, pl, w)) * sv.bytes_per_sample();
                for (int y = 0; y < ph; ++y) std::memcpy(sv.planes[pl].row<uint8_t>(y), fv.planes[pl].row<uint8_t>(y), rb);
            }
            // src_flipped holds the picture stored bottom-up; viewing it with a
            // negative stride shows the original picture again.
            FrameBuffer out_flipped(w, h, src.format());
            apply_film_grain(p, flip(src_flipped.view()), flip(out_flipped.view()), 2);
            FrameView ov = flip(out_flipped.view()), rv = ref.view();
            for (int pl = 0; pl < ov.plane_count(); ++pl) {
                const int ph = plane_height(ov.format, pl, h);
                const std::size_t rb = static_cast<std::size_t>(plane_width(ov.format, pl, w)) * ov.bytes_per_sample();
                for (int y = 0; y < ph; ++y)
                    ASSERT_EQ(0, std::memcmp(ov.planes[pl].row<uint8_t>(y), rv.planes[pl].row<uint8_t>(y), rb));
            }
        }
}

TEST(Av1Synthesis, RestrictedRangeKeepsSamplesInside) {
    auto p = full_params();
    p.clip_to_restricted_range = 1;
    for (int mc : {0, 1}) {
        auto src = random_frame(80, 48, ChromaFormat::k444, 10);
        FrameBuffer dst(80, 48, src.format());
        apply_film_grain(p, src.view(), dst.view(), mc);
        const auto* s = reinterpret_cast<const uint16_t*>(dst.bytes());
        const std::size_t n = static_cast<std::size_t>(80) * 48;
        for (std::size_t i = 0; i < 3 * n; ++i) {
            ASSERT_GE(s[i], 64);
            ASSERT_LE(s[i], i < n ? 940 : (mc == 0 ? 940 : 960));
        }
    }
}

// A picture whose samples exceed its declared bit depth (16-bit data labelled 10-bit, say)
// is bad input the library cannot afford to scan for; it must still never read outside its
// tables (the sanitizer build checks), must write samples within the range, and the optimized
// kernels must write what the reference's do, out of place and in place: on a picture of such
// samples only, and on one where a few lie among valid ones (the vector forms leave the steps
// or rows holding one to their scalar forms).
TEST(Av1Synthesis, SamplesAboveTheBitDepthStayInBounds) {
    const auto p = full_params();
    for (int bd : {10, 12}) {
        for (bool few : {false, true}) {
            std::vector<uint8_t> reference_output;
            for (Kernels k : {Kernels::kReference, Kernels::kOptimized}) {
                FrameBuffer src(288, 64, PixelFormat{ChromaFormat::k420, bd}), dst(288, 64, src.format());
                auto* in = reinterpret_cast<uint16_t*>(src.bytes());
                std::mt19937 rng(5);
                for (std::size_t i = 0; i < src.byte_size() / 2; ++i) {
                    const uint32_t r = rng();
                    in[i] = uint16_t(few && r % 300 != 0 ? r % (1u << bd)
                                     : i % 3 == 0        ? 0xFFFF
                                                         : (1 << bd) + r % 60000);
                }
                Av1PictureSynthesis s(1, k);
                s.apply(p, src.view(), dst.view(), 1);
                const auto* out = reinterpret_cast<const uint16_t*>(dst.bytes());
                for (std::size_t i = 0; i < dst.byte_size() / 2; ++i) ASSERT_LT(out[i], 1 << bd) << "sample " << i;
                if (k == Kernels::kReference)
                    reference_output.assign(dst.bytes(), dst.bytes() + dst.byte_size());
                else
                    EXPECT_TRUE(std::equal(reference_output.begin(), reference_output.end(), dst.bytes()))
                        << "bit depth " << bd << (few ? ", a few samples above it" : "")
                        << ": the optimized kernels differ from the reference";
                // in place too (where the kernels' output overwrites the input they check)
                FrameBuffer same(288, 64, src.format());
                std::copy(src.bytes(), src.bytes() + src.byte_size(), same.bytes());
                s.apply(p, same.view(), same.view(), 1);
                EXPECT_TRUE(std::equal(reference_output.begin(), reference_output.end(), same.bytes()))
                    << "bit depth " << bd << " in place, " << (k == Kernels::kReference ? "reference" : "optimized")
                    << (few ? ", a few samples above the bit depth" : "");
            }
        }
    }
}

TEST(Av1Synthesis, FrameViewErrors) {
    auto p = full_params();
    auto src = random_frame(16, 16, ChromaFormat::k420, 8);
    FrameBuffer other(16, 16, PixelFormat{ChromaFormat::k420, 10});
    EXPECT_THROW(apply_film_grain(p, src.view(), other.view(), 2), Error);
    FrameView bad = src.view();
    bad.planes[1].data = nullptr;
    try {
        apply_film_grain(p, bad, src.view(), 2);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
        EXPECT_NE(std::string(e.what()).find("planes[1]"), std::string::npos);
    }
    FrameBuffer f9(16, 16, PixelFormat{ChromaFormat::k420, 8});
    FrameView v9 = f9.view();
    v9.bit_depth = 9;
    EXPECT_THROW(apply_film_grain(p, v9, v9, 2), Error);
}

TEST(Av1Validation, AcceptsValid) {
    EXPECT_EQ(error_message(full_params()), "");
    EXPECT_EQ(error_message(full_params(), ChromaFormat::k444, 12), "");
    Av1FilmGrainParams off;
    off.num_y_points = 1000;  // not looked at
    EXPECT_EQ(error_message(off), "");
}

// AFGS1 signals num_cb/cr_points where AV1's film_grain_params() infers them 0 (4:2:0 without
// luma points): such a set carries chroma-only grain (AFGS1 text, FFmpeg 7.1; conformance
// afgs1-352x288-420p8-chroma picture 6). The AV1 rule stays for sets that did not signal them.
TEST(Av1Validation, ChromaOnlyGrainIn420NeedsSignalledCounts) {
    Av1FilmGrainParams p = full_params();
    p.num_y_points = 0;
    EXPECT_NE(error_message(p).find("num_cb_points (4:2:0 with num_y_points = 0) = 2"), std::string::npos);
    p.chroma_point_counts_signalled = true;
    EXPECT_EQ(error_message(p), "");
    // and it synthesizes chroma grain without luma grain
    FrameBuffer in(64, 48, PixelFormat{ChromaFormat::k420, 8}), out = in;
    std::fill(in.bytes(), in.bytes() + in.byte_size(), uint8_t(128));
    av1::apply_film_grain(p, in.view(), out.view(), 2);
    const std::size_t luma = 64 * 48;
    EXPECT_TRUE(std::equal(in.bytes(), in.bytes() + luma, out.bytes()));
    EXPECT_FALSE(std::equal(in.bytes() + luma, in.bytes() + in.byte_size(), out.bytes() + luma));
}

TEST(Av1Validation, MessagesNameFieldValueAndRange) {
    struct Case {
        std::function<void(Av1FilmGrainParams&)> mutate;
        std::string expected;
        ChromaFormat cf = ChromaFormat::k420;
    };
    const std::vector<Case> cases = {
        {[](auto& p) { p.apply_grain = 2; }, "apply_grain = 2 is out of range (allowed 0..1)"},
        {[](auto& p) { p.grain_seed = 65536; }, "grain_seed = 65536 is out of range (allowed 0..65535)"},
        {[](auto& p) { p.update_grain = -1; }, "update_grain = -1 is out of range (allowed 0..1)"},
        {[](auto& p) { p.film_grain_params_ref_idx = 8; }, "film_grain_params_ref_idx = 8"},
        {[](auto& p) { p.num_y_points = 15; }, "num_y_points = 15 is out of range (allowed 0..14)"},
        {[](auto& p) { p.point_y_value[1] = 0; }, "point_y_value[1] = 0 is out of range (allowed 1..255)"},
        {[](auto& p) { p.point_y_value[2] = 300; }, "point_y_value[2] = 300 is out of range (allowed 129..255)"},
        {[](auto& p) { p.point_y_scaling[0] = 256; }, "point_y_scaling[0] = 256 is out of range (allowed 0..255)"},
        {[](auto& p) { p.chroma_scaling_from_luma = 2; }, "chroma_scaling_from_luma = 2 is out of range (allowed 0..1)"},
        {[](auto& p) { p.num_cb_points = 11; }, "num_cb_points = 11 is out of range (allowed 0..10)"},
        {[](auto& p) { p.num_cr_points = -1; }, "num_cr_points = -1 is out of range (allowed 0..10)"},
        {[](auto& p) { p.point_cb_value[1] = 0; }, "point_cb_value[1] = 0 is out of range (allowed 1..255)"},
        {[](auto& p) { p.point_cr_scaling[1] = -5; }, "point_cr_scaling[1] = -5 is out of range (allowed 0..255)"},
        {[](auto& p) { p.chroma_scaling_from_luma = 1; },
         "num_cb_points (chroma_scaling_from_luma = 1) = 2 is out of range (allowed 0..0)"},
        {[](auto& p) { p.num_y_points = 0; },
         "num_cb_points (4:2:0 with num_y_points = 0) = 2 is out of range (allowed 0..0)"},
        {[](auto& p) { p.num_cr_points = 0; }, "num_cb_points = 2 and num_cr_points = 0 are inconsistent"},
        {[](auto& p) { p.num_cb_points = 0; }, "num_cb_points = 0 and num_cr_points = 2 are inconsistent"},
        {[](auto& p) { p.grain_scaling_minus_8 = 4; }, "grain_scaling_minus_8 = 4 is out of range (allowed 0..3)"},
        {[](auto& p) { p.ar_coeff_lag = 4; }, "ar_coeff_lag = 4 is out of range (allowed 0..3)"},
        {[](auto& p) { p.ar_coeffs_y_plus_128[11] = 256; },
         "ar_coeffs_y_plus_128[11] = 256 is out of range (allowed 0..255)"},
        {[](auto& p) { p.ar_coeffs_cb_plus_128[12] = -1; },
         "ar_coeffs_cb_plus_128[12] = -1 is out of range (allowed 0..255)"},
        {[](auto& p) { p.ar_coeffs_cr_plus_128[0] = 999; },
         "ar_coeffs_cr_plus_128[0] = 999 is out of range (allowed 0..255)"},
        {[](auto& p) { p.ar_coeff_shift_minus_6 = 4; }, "ar_coeff_shift_minus_6 = 4 is out of range (allowed 0..3)"},
        {[](auto& p) { p.grain_scale_shift = -1; }, "grain_scale_shift = -1 is out of range (allowed 0..3)"},
        {[](auto& p) { p.cb_mult = 256; }, "cb_mult = 256 is out of range (allowed 0..255)"},
        {[](auto& p) { p.cb_luma_mult = -1; }, "cb_luma_mult = -1 is out of range (allowed 0..255)"},
        {[](auto& p) { p.cb_offset = 512; }, "cb_offset = 512 is out of range (allowed 0..511)"},
        {[](auto& p) { p.cr_mult = 256; }, "cr_mult = 256 is out of range (allowed 0..255)"},
        {[](auto& p) { p.cr_luma_mult = 256; }, "cr_luma_mult = 256 is out of range (allowed 0..255)"},
        {[](auto& p) { p.cr_offset = -1; }, "cr_offset = -1 is out of range (allowed 0..511)"},
        {[](auto& p) { p.overlap_flag = 2; }, "overlap_flag = 2 is out of range (allowed 0..1)"},
        {[](auto& p) { p.clip_to_restricted_range = 3; }, "clip_to_restricted_range = 3 is out of range (allowed 0..1)"},
        {[](auto& p) { p.chroma_scaling_from_luma = 1; p.num_cb_points = p.num_cr_points = 0; },
         "chroma_scaling_from_luma (monochrome frame) = 1 is out of range (allowed 0..0)", ChromaFormat::k400},
        {[](auto& p) { p.num_cr_points = 0; }, "num_cb_points (monochrome frame) = 2 is out of range (allowed 0..0)",
         ChromaFormat::k400},
    };
    for (const auto& c : cases) {
        auto p = full_params();
        c.mutate(p);
        const std::string msg = error_message(p, c.cf);
        EXPECT_NE(msg.find(c.expected), std::string::npos) << "got: '" << msg << "', expected: '" << c.expected << "'";
    }
    EXPECT_NE(error_message(full_params(), ChromaFormat::k420, 9).find("bit_depth = 9"), std::string::npos);
}

TEST(Av1Validation, SpecInferenceCases) {
    // 4:2:2 / 4:4:4: one chroma plane may have points without the other.
    auto p = full_params();
    p.num_cr_points = 0;
    EXPECT_EQ(error_message(p, ChromaFormat::k422), "");
    // 4:4:4 with no luma points may still carry chroma points.
    p = full_params();
    p.num_y_points = 0;
    EXPECT_EQ(error_message(p, ChromaFormat::k444), "");
    // Unsignalled chroma mult/offset are not checked.
    p = full_params();
    p.num_cb_points = p.num_cr_points = 0;
    p.cb_mult = p.cr_offset = -7;
    EXPECT_EQ(error_message(p), "");
    // chroma_scaling_from_luma without luma points is legal (no grain results).
    p.chroma_scaling_from_luma = 1;
    p.num_y_points = 0;
    EXPECT_EQ(error_message(p), "");
}

TEST(Av1Synthesis, ConcurrentStripesMatchSerial) {
    const auto p = full_params();
    for (int bd : {8, 10}) {
        auto src = random_frame(333, 301, ChromaFormat::k420, bd, 99);
        FrameBuffer serial(333, 301, src.format());
        apply_film_grain(p, src.view(), serial.view(), 2);

        const Av1SynthesisContext ctx(p, ChromaFormat::k420, bd, 333, 301, 2);
        for (bool in_place : {false, true}) {
            FrameBuffer out = in_place ? src : FrameBuffer(333, 301, src.format());
            const FrameView in_view = in_place ? out.view() : src.view();
            std::vector<std::thread> pool;
            for (int t = 0; t < 4; ++t)
                pool.emplace_back([&, t] {
                    for (int s = t; s < ctx.stripe_count(); s += 4) ctx.apply_stripes(in_view, out.view(), s, s + 1);
                });
            for (auto& th : pool) th.join();
            EXPECT_EQ(bytes_of(out), bytes_of(serial)) << "bd " << bd << " in_place " << in_place;
        }
    }
}

TEST(Av1Synthesis, StrideTooSmallIsRejected) {
    auto f = random_frame(40, 8, ChromaFormat::k420, 8);
    FrameView v = f.view();
    v.planes[0].stride = 39;
    try {
        apply_film_grain(full_params(), v, v, 2);
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
        EXPECT_NE(std::string(e.what()).find("strides[0] = 39"), std::string::npos) << e.what();
    }
}

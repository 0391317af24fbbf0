// Issue 24 (hardening), library level: every comp_model_value against the range its syntax
// element can carry (one check for every path and flavour), and the seed derivation for
// any int32 POC / idr_pic_id. Each case was a reproducer: a negative scale factor went
// through rdd5, vtm and tr (destroying the picture, signed overflow in the chroma
// conversion and the tr synthesis), an unbounded aspect ratio overflowed the vfgs AR
// filter, and POC = INT32_MAX overflowed the seed look-up.
#include <gtest/gtest.h>

#include <climits>
#include <functional>
#include <string>

#include "core/frame_buffer.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/vfgs.hpp"
#include "metadata/fgc_sei.hpp"

using namespace filmgrain;

namespace {

// Luma and chroma, one interval each, frequency filtering.
FgcParams ff_params(int luma_scale) {
    FgcParams p;
    p.log2_scale_factor = 5;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {FgcIntensityInterval{0, 255, {c == 0 ? luma_scale : 60, 8, 8}}};
    }
    return p;
}

// Luma only, auto-regressive, all six values signalled.
FgcParams ar_params(std::array<int, 6> v) {
    FgcParams p;
    p.film_grain_model_id = 1;
    p.log2_scale_factor = 5;
    p.comp[0].comp_model_present_flag = true;
    p.comp[0].num_model_values_minus1 = 5;
    p.comp[0].intervals = {FgcIntensityInterval{0, 255, v}};
    return p;
}

FrameBuffer grey(int bit_depth, ChromaFormat f = ChromaFormat::k420, int w = 256, int h = 192) {
    FrameBuffer b(w, h, PixelFormat{f, bit_depth});
    FrameView v = b.view();
    for (int c = 0; c < v.plane_count(); c++)
        for (int y = 0; y < v.planes[c].height; y++)
            for (int x = 0; x < v.planes[c].width; x++) {
                if (bit_depth > 8) v.planes[c].row<uint16_t>(y)[x] = uint16_t(128 << (bit_depth - 8));
                else v.planes[c].row<uint8_t>(y)[x] = 128;
            }
    return b;
}

Error error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    return Error(ErrorCode::kOk, "no error");
}

// Applies `p` to a grey picture with one flavour (vfgs through its own synthesizer).
void apply(FgcFlavour flavour, const FgcParams& p, int bit_depth, ChromaFormat f = ChromaFormat::k420) {
    FrameBuffer in = grey(bit_depth, f), out = grey(bit_depth, f);
    if (flavour == FgcFlavour::kVfgs) {
        vfgs::Synthesizer s(vfgs::Options{});
        s.set_params(p);
        s.apply(in.view(), out.view());
        return;
    }
    FgcOptions o;
    o.flavour = flavour;
    FgcStreamSynthesis s(o);
    s.receive_sei(p);
    s.apply(in.view(), out.view(), {0, 0});
}


constexpr FgcFlavour kAll[] = {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kVfgs, FgcFlavour::kTr,
                               FgcFlavour::kFfmpeg};

}  // namespace

TEST(FgcValueRanges, NegativeScaleFactorIsRefusedByEveryFlavourOnEveryPath) {
    // -1, -2^30 and INT32_MIN (the JSON reader once wrapped 2^64 - 1 to -1); at 8 and 10 bits,
    // 4:2:0 (chroma halves the scale) and 4:2:2 (scale * 181 overflowed for -2^30).
    for (int value : {-1, -(1 << 30), INT_MIN})
        for (int bd : {8, 10})
            for (ChromaFormat cf : {ChromaFormat::k420, ChromaFormat::k422})
                for (FgcFlavour fl : kAll)
                    for (int component : {0, 1}) {
                        if (fl == FgcFlavour::kVfgs && cf != ChromaFormat::k420) continue;  // luma-only there
                        FgcParams p = ff_params(100);
                        p.comp[component].intervals[0].comp_model_value[0] = value;
                        // vfgs checks at set_params, before it knows the picture: the widest
                        // range, that of a 16-bit picture
                        const std::string hi = std::to_string(fl == FgcFlavour::kVfgs ? 65535 : (1 << bd) - 1);
                        const std::string want = "comp_model_value[" + std::to_string(component) + "][0][0] = " +
                                                 std::to_string(value) + " is out of range (allowed 0.." + hi + ")";
                        // Typed FgcParams (C++, and what the JSON reader produces)
                        Error e = error_of([&] { apply(fl, p, bd, cf); });
                        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams) << fgc_flavour_name(fl) << ": " << e.what();
                        EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << fgc_flavour_name(fl) << ": " << e.what();
                        // SEI payload bytes: se(v) carries the value, synthesis refuses it;
                        // INT32_MIN is the one int se(v) cannot code (code number 2^32): the
                        // writer refuses it rather than write 0
                        if (value == INT_MIN) {
                            e = error_of([&] { (void)write_fgc_sei_payload(p, FgcCodec::kHevc); });
                            EXPECT_EQ(e.code(), ErrorCode::kInvalidParams) << e.what();
                            EXPECT_NE(std::string(e.what()).find("-2147483648 is out of range (allowed -2147483647..2147483647)"),
                                      std::string::npos)
                                << e.what();
                            continue;
                        }
                        const FgcParams from_sei =
                            parse_fgc_sei_payload(write_fgc_sei_payload(p, FgcCodec::kHevc), FgcCodec::kHevc);
                        e = error_of([&] { apply(fl, from_sei, bd, cf); });
                        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams) << fgc_flavour_name(fl) << ": " << e.what();
                        EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << fgc_flavour_name(fl) << ": " << e.what();
                    }
}

TEST(FgcValueRanges, NegativeSigmaOfTheAutoRegressiveModelIsRefused) {
    // tr synthesized sigma * template in int32: -2^30 overflowed (the reference stripe, reference_stripe.cpp).
    for (FgcFlavour fl : {FgcFlavour::kTr, FgcFlavour::kVfgs})
        for (int value : {-1, -(1 << 30)}) {
            // vfgs checks at set_params, before the picture's bit depth is known (16 bits)
            const Error e = error_of([&] { apply(fl, ar_params({value, 4, 0, 0, 32, 0}), 8); });
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParams) << e.what();
            EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = " + std::to_string(value) +
                                                 " is out of range (allowed 0.." + (fl == FgcFlavour::kVfgs ? "65535" : "255") +
                                                 ") (film_grain_model_id 1"),
                      std::string::npos)
                << e.what();
        }
}

TEST(FgcValueRanges, AutoRegressiveValuesKeepTheSeiRange) {
    // Model 1 values other than sigma: -2^(B-1)..2^(B-1)-1. The aspect ratio (index 4) was
    // not checked by vfgs, and 2^31 - 1 overflowed its AR filter's int weights.
    for (FgcFlavour fl : {FgcFlavour::kTr, FgcFlavour::kVfgs})
        for (int j : {1, 2, 3, 4, 5})
            for (int value : {128, -129, INT_MAX, INT_MIN}) {
                std::array<int, 6> v{100, 1, 0, 1, 32, 1};
                v[std::size_t(j)] = value;
                const Error e = error_of([&] { apply(fl, ar_params(v), 8); });
                // vfgs refuses what no picture allows at set_params, the rest when it meets the picture
                const bool widest = fl == FgcFlavour::kVfgs && (value == INT_MAX || value == INT_MIN);
                const std::string range = widest ? "-32768..32767" : "-128..127";
                EXPECT_EQ(e.code(), ErrorCode::kInvalidParams) << fgc_flavour_name(fl) << " j=" << j << ": " << e.what();
                EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][" + std::to_string(j) + "] = " +
                                                     std::to_string(value) + " is out of range (allowed " + range + ")"),
                          std::string::npos)
                    << fgc_flavour_name(fl) << ": " << e.what();
            }
    // at 10 bits the range is -512..511: 128 passes the syntax check (vfgs takes it)
    std::array<int, 6> v{100, 1, 0, 1, 128, 1};
    EXPECT_NO_THROW(apply(FgcFlavour::kVfgs, ar_params(v), 10));
}

#if 0  // BASELINE-ONLY
TEST(FgcValueRanges, SyntaxCheckWithAndWithoutThePictureBitDepth) {
    // Without the picture (the JSON reader, a parser): the deepest picture, 16 bits.
    FgcParams p = ff_params(65535);
    EXPECT_NO_THROW(fgc::check_fgc_syntax_ranges(p));
    p.comp[0].intervals[0].comp_model_value[0] = 65536;
    Error e = error_of([&] { fgc::check_fgc_syntax_ranges(p); });
    EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
    EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = 65536 is out of range (allowed 0..65535)"),
              std::string::npos)
        << e.what();
    p.comp[0].intervals[0].comp_model_value[0] = -1;
    e = error_of([&] { fgc::check_fgc_syntax_ranges(p); });
    EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = -1 is out of range (allowed 0..65535)"),
              std::string::npos)
        << e.what();
    // cut-offs too: model 0 values are all 0..2^B - 1
    p = ff_params(100);
    p.comp[2].intervals[0].comp_model_value[2] = -3;
    e = error_of([&] { fgc::check_fgc_syntax_ranges(p, 12); });
    EXPECT_NE(std::string(e.what()).find("comp_model_value[2][0][2] = -3 is out of range (allowed 0..4095)"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("filmGrainBitDepth[2] = 12 from the picture's bit depth"), std::string::npos)
        << e.what();
    // The SEI's own film grain bit depth, when it signals one.
    p = ff_params(1024);
    p.separate_colour_description_present_flag = true;
    p.film_grain_bit_depth_luma_minus8 = 2;
    e = error_of([&] { fgc::check_fgc_syntax_ranges(p, 16); });
    EXPECT_NE(std::string(e.what()).find("comp_model_value[0][0][0] = 1024 is out of range (allowed 0..1023)"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("film_grain_bit_depth_luma_minus8 + 8"), std::string::npos) << e.what();
    // Only the signalled values are checked (the others are inferred).
    p = ff_params(100);
    p.comp[0].num_model_values_minus1 = 0;
    p.comp[0].intervals[0].comp_model_value[1] = -5;
    EXPECT_NO_THROW(fgc::check_fgc_syntax_ranges(p, 8));
    // A cancel carries nothing to check.
    p.film_grain_characteristics_cancel_flag = true;
    p.comp[0].intervals[0].comp_model_value[0] = -1;
    EXPECT_NO_THROW(fgc::check_fgc_syntax_ranges(p, 8));

    EXPECT_EQ(fgc::comp_model_value_range(0, 3, 10).hi, 1023);
    EXPECT_EQ(fgc::comp_model_value_range(1, 0, 10).lo, 0);
    EXPECT_EQ(fgc::comp_model_value_range(1, 4, 10).lo, -512);
    EXPECT_EQ(fgc::comp_model_value_range(1, 4, 10).hi, 511);
}

#endif  // BASELINE-ONLY
TEST(FgcValueRanges, LargestScaleTheReferencesTakeStillWorks) {
    // 255 << (B - 8) at 8, 10 and 16 bits, luma and 4:2:2 chroma (x 181 / 256), every flavour
    // that takes the format.
    for (int bd : {8, 10, 16})
        for (FgcFlavour fl : kAll) {
            if (fl == FgcFlavour::kVfgs && bd != 8) continue;  // vfgs: 8 bits of scale
            FgcParams p = ff_params(255 << (bd - 8));
            for (auto& c : p.comp) c.intervals[0].comp_model_value[0] = 255 << (bd - 8);
            EXPECT_NO_THROW(apply(fl, p, bd, fl == FgcFlavour::kVfgs ? ChromaFormat::k420 : ChromaFormat::k422))
                << fgc_flavour_name(fl) << " " << bd;
        }
}

TEST(FgcSeed, AnyInt32PictureIdsWrapAsTheReferenceSeedDoes) {
    // The seed is Seed_LUT[(POC + (idr_pic_id << 5) + colour offset) mod 256]: POC = INT32_MAX
    // (legal) overflowed int32 on the way. Computed modulo 2^32 it selects what POC 255 does.
    EXPECT_EQ(fgc::component_seed(INT32_MAX, 2), fgc::component_seed(255, 2));
    EXPECT_EQ(fgc::component_seed(INT32_MIN, 1), fgc::component_seed(0, 1));
    EXPECT_EQ(fgc::component_seed(-1, 0), fgc::component_seed(255, 0));
    for (FgcFlavour fl : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kTr, FgcFlavour::kFfmpeg}) {
        FgcOptions o;
        o.flavour = fl;
        auto run = [&](int poc, int idr) {
            FgcStreamSynthesis s(o);
            s.receive_sei(ff_params(100));
            FrameBuffer in = grey(8), out = grey(8);
            s.apply(in.view(), out.view(), {poc, idr});
            return std::vector<uint8_t>(out.bytes(), out.bytes() + out.byte_size());
        };
        EXPECT_EQ(run(INT32_MAX, 0), run(255, 0)) << fgc_flavour_name(fl);
        EXPECT_EQ(run(INT32_MIN, 0), run(0, 0)) << fgc_flavour_name(fl);
        EXPECT_NE(run(INT32_MAX, 0), run(0, 0)) << fgc_flavour_name(fl);
        // idr_pic_id << 5 wraps too (rdd5, tr; vtm ignores it): 0x7FFFFFFF << 5 = 0xFFFFFFE0
        if (fl != FgcFlavour::kVtm) {
            EXPECT_EQ(run(INT32_MAX, INT32_MAX), run(255 + 0xE0, 0)) << fgc_flavour_name(fl);
            EXPECT_EQ(run(0, INT32_MIN), run(0, 0)) << fgc_flavour_name(fl);
        } else {
            EXPECT_EQ(run(INT32_MAX, INT32_MAX), run(255, 0));
        }
    }
}

// The FGC synthesizer as a decoder uses it: persistence, cancel, in place, strides,
// formats and bit depths the references do not cover.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <thread>

#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain;

namespace {
FgcParams params(int scale = 80, bool persist = true) {
    FgcParams p;
    p.log2_scale_factor = 5;
    p.film_grain_characteristics_persistence_flag = persist;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {{0, 255, {scale, 8, 8}}};
    }
    return p;
}

FrameBuffer flat(int w, int h, PixelFormat f, int value) {
    FrameBuffer b(w, h, f);
    FrameView v = b.view();
    for (int c = 0; c < v.plane_count(); c++)
        for (int y = 0; y < v.planes[c].height; y++)
            for (int x = 0; x < v.planes[c].width; x++) {
                if (f.bit_depth > 8) v.planes[c].row<uint16_t>(y)[x] = uint16_t(value << (f.bit_depth - 8));
                else v.planes[c].row<uint8_t>(y)[x] = uint8_t(value);
            }
    return b;
}

std::string md5(const FrameBuffer& b) { return md5_hex(b.bytes(), b.byte_size()); }

double plane_sd(const FrameBuffer& a, const FrameBuffer& b, int plane) {
    FrameView va = const_cast<FrameBuffer&>(a).view(), vb = const_cast<FrameBuffer&>(b).view();
    double s = 0, s2 = 0;
    const int n = va.planes[plane].width * va.planes[plane].height;
    for (int y = 0; y < va.planes[plane].height; y++)
        for (int x = 0; x < va.planes[plane].width; x++) {
            double d = a.format().bit_depth > 8
                           ? double(vb.planes[plane].row<uint16_t>(y)[x]) - va.planes[plane].row<uint16_t>(y)[x]
                           : double(vb.planes[plane].row<uint8_t>(y)[x]) - va.planes[plane].row<uint8_t>(y)[x];
            s += d;
            s2 += d * d;
        }
    return std::sqrt(s2 / n - (s / n) * (s / n));
}
}  // namespace

// Samples beyond the declared bit depth (16-bit data labelled 10-bit, say) are bad input the
// library cannot afford to scan for: the block averages that pick an intensity interval must
// still never index past their tables (the sanitizer build checks), the output must stay
// within the range, and the optimized kernels must give the reference stages' output (whose
// blend clips the 32-bit sum), so that bad input does not depend on the kernels either.
TEST(FgcStreamSynthesis, SamplesAboveTheBitDepthStayInBounds) {
    for (int bd : {10, 12})
        for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kTr, FgcFlavour::kFfmpeg}) {
            std::string reference_md5;
            for (bool reference : {true, false}) {
                FrameBuffer src(288, 144, PixelFormat{ChromaFormat::k420, bd}), dst(288, 144, src.format());
                auto* in = reinterpret_cast<uint16_t*>(src.bytes());
                std::mt19937 rng(5);
                for (std::size_t i = 0; i < src.byte_size() / 2; ++i)
                    in[i] = uint16_t(i % 3 == 0 ? 0xFFFF : (1 << bd) + rng() % 60000);
                FgcOptions o;
                o.flavour = flavour;
                o.threads = 1;
                o.reference_kernels = reference;
                FgcStreamSynthesis s(o);
                FgcParams p = params();
                p.comp[0].intervals = {{0, 99, {80, 8, 8}}, {100, 255, {120, 10, 10}}};
                s.receive_sei(p);
                s.apply(src.view(), dst.view(), FgcPictureIds{3, 0});
                const auto* out = reinterpret_cast<const uint16_t*>(dst.bytes());
                for (std::size_t i = 0; i < dst.byte_size() / 2; ++i) ASSERT_LT(out[i], 1 << bd) << "sample " << i;
                if (reference)
                    reference_md5 = md5(dst);
                else
                    EXPECT_EQ(md5(dst), reference_md5) << "bit depth " << bd << " flavour " << int(flavour);
                // in place too
                s.apply(src.view(), src.view(), FgcPictureIds{3, 0});
                EXPECT_EQ(md5(src), reference_md5) << "in place, bit depth " << bd << " flavour " << int(flavour)
                                                    << (reference ? " (reference)" : " (optimized)");
            }
        }
}

TEST(FgcStreamSynthesis, PersistenceReferenceVersusSemantic) {
    const PixelFormat f{ChromaFormat::k420, 8};
    FrameBuffer in = flat(176, 144, f, 128), out(176, 144, f);
    for (auto mode : {FgcPersistence::kReference, FgcPersistence::kSemantic}) {
        FgcOptions o;
        o.persistence = mode;
        FgcStreamSynthesis s(o);
        s.receive_sei(params(80, /*persist=*/false));
        EXPECT_TRUE(s.apply(in.view(), out.view(), {0, 0}).grain_applied);
        EXPECT_NE(md5(out), md5(in));
        const auto r = s.apply(in.view(), out.view(), {1, 0});  // no SEI for picture 1
        EXPECT_EQ(r.grain_applied, mode == FgcPersistence::kReference);
        EXPECT_EQ(md5(out) == md5(in), mode == FgcPersistence::kSemantic);
    }
}

TEST(FgcStreamSynthesis, CancelStopsGrainAndPersists) {
    const PixelFormat f{ChromaFormat::k420, 8};
    FrameBuffer in = flat(176, 144, f, 100), out(176, 144, f);
    FgcStreamSynthesis s(FgcOptions{});
    s.receive_sei(params());
    s.apply(in.view(), out.view(), {0, 0});
    EXPECT_NE(md5(out), md5(in));
    FgcParams cancel;
    cancel.film_grain_characteristics_cancel_flag = true;
    s.receive_sei(cancel);
    EXPECT_FALSE(s.apply(in.view(), out.view(), {1, 0}).grain_applied);
    EXPECT_EQ(md5(out), md5(in));
    EXPECT_FALSE(s.apply(in.view(), out.view(), {2, 0}).grain_applied);
    EXPECT_EQ(md5(out), md5(in));
}

TEST(FgcStreamSynthesis, InvalidSetThrowsOrPassesThrough) {
    const PixelFormat f{ChromaFormat::k420, 8};
    FrameBuffer in = flat(176, 144, f, 100), out(176, 144, f);
    FgcParams bad = params();
    bad.log2_scale_factor = 1;
    FgcStreamSynthesis strict(FgcOptions{});
    strict.receive_sei(bad);
    try {
        strict.apply(in.view(), out.view(), {0, 0});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
        EXPECT_NE(std::string(e.what()).find("log2_scale_factor = 1"), std::string::npos);
    }
    FgcOptions o;
    o.passthrough_invalid = true;
    FgcStreamSynthesis lenient(o);
    lenient.receive_sei(bad);
    const auto r = lenient.apply(in.view(), out.view(), {0, 0});
    EXPECT_FALSE(r.grain_applied);
    EXPECT_NE(r.message.find("log2_scale_factor"), std::string::npos);
    EXPECT_EQ(md5(out), md5(in));
}

TEST(FgcStreamSynthesis, InPlaceNegativeStrideAndSeparateOutputAgree) {
    for (auto flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm}) {
        const PixelFormat f{ChromaFormat::k420, 10};
        FrameBuffer in(352, 288, f);
        std::mt19937 rng(1);
        uint16_t* s = reinterpret_cast<uint16_t*>(in.bytes());
        for (std::size_t i = 0; i < in.byte_size() / 2; i++) s[i] = uint16_t(rng() % 1024);
        FgcOptions o;
        o.flavour = flavour;
        FgcStreamSynthesis a(o), b(o), c(o);
        FrameBuffer out(352, 288, f), inplace = in;
        a.receive_sei(params(300));
        a.apply(in.view(), out.view(), {3, 0});
        b.receive_sei(params(300));
        b.apply(inplace.view(), inplace.view(), {3, 0});
        EXPECT_EQ(md5(out), md5(inplace));
        // bottom-up views of the same buffers
        FrameBuffer flipped_out(352, 288, f);
        FrameView vi = in.view(), vo = flipped_out.view();
        for (int p = 0; p < 3; p++) {
            vi.planes[p].data += vi.planes[p].stride * (vi.planes[p].height - 1);
            vi.planes[p].stride = -vi.planes[p].stride;
            vo.planes[p].data += vo.planes[p].stride * (vo.planes[p].height - 1);
            vo.planes[p].stride = -vo.planes[p].stride;
        }
        c.receive_sei(params(300));
        c.apply(vi, vo, {3, 0});
        // a flipped picture is a different picture; it must still be written entirely and
        // equal a top-down synthesis of the flipped input
        FrameBuffer flipped_in(352, 288, f), expect(352, 288, f);
        FrameView fi = flipped_in.view();
        FrameView src = in.view();
        for (int p = 0; p < 3; p++)
            for (int y = 0; y < fi.planes[p].height; y++)
                std::memcpy(fi.planes[p].row<uint8_t>(y), src.planes[p].row<uint8_t>(fi.planes[p].height - 1 - y),
                            fi.planes[p].width * 2);
        FgcStreamSynthesis d(o);
        d.receive_sei(params(300));
        d.apply(flipped_in.view(), expect.view(), {3, 0});
        FrameBuffer unflipped(352, 288, f);
        FrameView fo = flipped_out.view(), uo = unflipped.view();
        for (int p = 0; p < 3; p++)
            for (int y = 0; y < uo.planes[p].height; y++)
                std::memcpy(uo.planes[p].row<uint8_t>(y), fo.planes[p].row<uint8_t>(uo.planes[p].height - 1 - y),
                            uo.planes[p].width * 2);
        EXPECT_EQ(md5(unflipped), md5(expect));
    }
}

TEST(FgcStreamSynthesis, Chroma444UsesUnconvertedParameters) {
    // HM crashes on 4:4:4; by the semantics chroma is at luma resolution, so it takes the
    // signalled scale and cut-offs unchanged and gets grain as strong as luma's.
    const PixelFormat f{ChromaFormat::k444, 8};
    FrameBuffer in = flat(352, 288, f, 128), out(352, 288, f);
    FgcOptions o;
    o.flavour = FgcFlavour::kVtm;
    FgcStreamSynthesis s(o);
    s.receive_sei(params(120));
    s.apply(in.view(), out.view(), {0, 0});
    const double y = plane_sd(in, out, 0), u = plane_sd(in, out, 1);
    EXPECT_GT(y, 1.0);
    EXPECT_NEAR(u / y, 1.0, 0.25);
}

TEST(FgcStreamSynthesis, SixteenBitAndOddSizesStayInRange) {
    for (int bd : {8, 9, 12, 16})
        for (auto [w, h] : {std::pair{97, 61}, std::pair{1, 1}, std::pair{17, 130}}) {
            const PixelFormat f{ChromaFormat::k420, bd};
            FrameBuffer in = flat(w, h, f, 250), out(w, h, f);
            FgcStreamSynthesis s(FgcOptions{});
            FgcParams p = params(255 << (bd - 8));
            p.log2_scale_factor = 2;
            s.receive_sei(p);
            EXPECT_NO_THROW(s.apply(in.view(), out.view(), {0, 0})) << bd << " " << w << "x" << h;
            if (bd > 8) {
                const uint16_t* o = reinterpret_cast<const uint16_t*>(out.bytes());
                for (std::size_t i = 0; i < out.byte_size() / 2; i++) ASSERT_LE(o[i], (1 << bd) - 1);
            }
        }
}

TEST(FgcStreamSynthesis, ContextsAreIndependentAcrossThreads) {
    const PixelFormat f{ChromaFormat::k420, 8};
    FrameBuffer in = flat(352, 288, f, 90);
    auto run = [&](int poc) {
        FgcStreamSynthesis s(FgcOptions{});
        s.receive_sei(params());
        FrameBuffer out(352, 288, f);
        s.apply(in.view(), out.view(), {poc, 0});
        return md5(out);
    };
    std::vector<std::string> serial, parallel(8);
    for (int i = 0; i < 8; i++) serial.push_back(run(i));
    std::vector<std::thread> ts;
    for (int i = 0; i < 8; i++) ts.emplace_back([&, i] { parallel[i] = run(i); });
    for (auto& t : ts) t.join();
    EXPECT_EQ(serial, parallel);
    EXPECT_NE(serial[0], serial[1]) << "the POC changes the seed";
}

TEST(FgcStreamSynthesis, MismatchedFramesAreRejected) {
    FrameBuffer a(64, 64, {ChromaFormat::k420, 8}), b(64, 32, {ChromaFormat::k420, 8});
    FgcStreamSynthesis s(FgcOptions{});
    s.receive_sei(params());
    EXPECT_THROW(s.apply(a.view(), b.view(), {0, 0}), Error);
}

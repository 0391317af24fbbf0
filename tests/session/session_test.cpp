// The stream session (include/filmgrain/session.hpp) with the options the tool offers: each
// option gives, through the session, exactly what the model's own synthesizer gives with it,
// and a bad option or combination is refused naming the field.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "filmgrain/session.hpp"
#include "filmgrain/vfgs.hpp"
#include "av1/av1_picture_synthesis.hpp"

using namespace filmgrain;

namespace {

FrameBuffer noise_picture(int w, int h, PixelFormat fmt, uint32_t seed) {
    FrameBuffer f(w, h, fmt);
    std::mt19937 rng(seed);
    FrameView v = f.view();
    for (int c = 0; c < v.plane_count(); c++)
        for (int y = 0; y < v.planes[c].height; y++)
            for (int x = 0; x < v.planes[c].width; x++) {
                const int s = 16 + int(rng() % 200);
                if (fmt.bit_depth > 8) v.planes[c].row<uint16_t>(y)[x] = uint16_t(s << (fmt.bit_depth - 8));
                else v.planes[c].row<uint8_t>(y)[x] = uint8_t(s);
            }
    return f;
}

FgcParams fgc_params() {
    FgcParams p;
    p.log2_scale_factor = 5;
    for (int c = 0; c < 3; c++) {
        p.comp[c].comp_model_present_flag = true;
        p.comp[c].num_model_values_minus1 = 2;
        p.comp[c].intervals = {FgcIntensityInterval{0, 120, {c ? 70 : 110, 9, 10}},
                               FgcIntensityInterval{121, 255, {c ? 50 : 80, 12, 7}}};
    }
    return p;
}

Av1FilmGrainParams av1_params() {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.update_grain = 1;
    p.grain_seed = 4711;
    p.num_y_points = 2;
    p.point_y_value = {0, 255};
    p.point_y_scaling = {40, 90};
    p.chroma_scaling_from_luma = 1;
    p.grain_scaling_minus_8 = 2;
    p.ar_coeff_lag = 1;
    p.ar_coeffs_y_plus_128 = {130, 120, 140, 125};
    p.ar_coeffs_cb_plus_128 = {128, 128, 128, 128, 140};
    p.ar_coeffs_cr_plus_128 = {128, 128, 128, 128, 120};
    p.ar_coeff_shift_minus_6 = 1;
    p.overlap_flag = 1;
    p.clip_to_restricted_range = 0;
    return p;
}

// Three pictures through the session, FgcParams given with the first only.
std::vector<uint8_t> through_session(const SessionOptions& so, const FrameBuffer& in, int out_bit_depth = 0) {
    Session s(so);
    s.receive_fgc_params(fgc_params(), FgcCodec::kHevc);
    std::vector<uint8_t> all;
    PixelFormat of = in.format();
    if (out_bit_depth) of.bit_depth = out_bit_depth;
    for (int k = 0; k < 3; k++) {
        FrameBuffer out(in.width(), in.height(), of);
        FrameInfo fi;
        fi.ids.poc = k;
        s.apply(const_cast<FrameBuffer&>(in).view(), out.view(), &fi);
        all.insert(all.end(), out.bytes(), out.bytes() + out.byte_size());
    }
    return all;
}

std::vector<uint8_t> through_fgc_stream_synthesis(const FgcOptions& fo, const FrameBuffer& in) {
    FgcStreamSynthesis s(fo);
    s.receive_sei(fgc_params());
    std::vector<uint8_t> all;
    for (int k = 0; k < 3; k++) {
        FrameBuffer out(in.width(), in.height(), in.format());
        s.apply(const_cast<FrameBuffer&>(in).view(), out.view(), FgcPictureIds{k, 0});
        all.insert(all.end(), out.bytes(), out.bytes() + out.byte_size());
    }
    return all;
}

std::string error_of(const SessionOptions& so) {
    try {
        Session s(so);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
        return e.what();
    }
    return "no error";
}

}  // namespace

TEST(Session, FgcOptionsGiveWhatTheSynthesizerGivesWithThem) {
    const FrameBuffer in = noise_picture(200, 136, PixelFormat{ChromaFormat::k420, 8}, 3);
    struct Case {
        FgcFlavour flavour;
        int block_size, single_line_blocks;
    };
    for (const Case c : {Case{FgcFlavour::kRdd5, 0, 0}, Case{FgcFlavour::kRdd5, 32, 0}, Case{FgcFlavour::kTr, 0, 0},
                         Case{FgcFlavour::kTr, 16, 0}, Case{FgcFlavour::kTr, 0, 8}, Case{FgcFlavour::kVtm, 0, 32}}) {
        SessionOptions so;
        so.flavour = c.flavour;
        so.block_size = c.block_size;
        so.single_line_blocks = c.single_line_blocks;
        so.persistence = FgcPersistence::kReference;
        FgcOptions fo;
        fo.flavour = c.flavour;
        fo.block_size = c.block_size;
        fo.single_line_blocks = c.single_line_blocks;
        const std::vector<uint8_t> a = through_session(so, in), b = through_fgc_stream_synthesis(fo, in);
        EXPECT_EQ(a, b) << int(c.flavour) << " block " << c.block_size << " single-line " << c.single_line_blocks;
        // and the option does something: square default blocks differ
        if (c.block_size || c.single_line_blocks) {
            FgcOptions plain;
            plain.flavour = c.flavour;
            EXPECT_NE(a, through_fgc_stream_synthesis(plain, in));
        }
    }
}

TEST(Session, VfgsOptionsGiveWhatItsSynthesizerGives) {
    const FrameBuffer in = noise_picture(160, 128, PixelFormat{ChromaFormat::k420, 10}, 5);
    SessionOptions so;
    so.flavour = FgcFlavour::kVfgs;
    so.vfgs_seed = 77;
    so.vfgs_gain_percent = 150;
    so.vfgs_output_bit_depth = 8;
    so.pattern_interpolation = true;
    const std::vector<uint8_t> a = through_session(so, in, 8);
    vfgs::Options vo;
    vo.seed = 77;
    vo.gain_percent = 150;
    vo.output_bit_depth = 8;
    vo.pattern_interpolation = true;
    vfgs::Synthesizer v(vo);
    v.set_params(fgc_params());
    std::vector<uint8_t> b;
    for (int k = 0; k < 3; k++) {
        FrameBuffer out(in.width(), in.height(), PixelFormat{ChromaFormat::k420, 8});
        v.apply(const_cast<FrameBuffer&>(in).view(), out.view());
        b.insert(b.end(), out.bytes(), out.bytes() + out.byte_size());
    }
    EXPECT_EQ(a, b);
    // a 10-bit dst is refused while the output depth is 8, naming both
    Session s(so);
    FrameBuffer in2 = in, out10(in.width(), in.height(), in.format());
    try {
        s.apply(in2.view(), out10.view());
        FAIL() << "a 10-bit dst accepted with vfgs_output_bit_depth 8";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("dst.bit_depth = 10, expected 8"), std::string::npos) << e.what();
    }
}

TEST(Session, VfgsThreadsGiveTheSameOutput) {
    // 200 rows: 13 stripes, the last one partial, shared unevenly among the workers.
    const FrameBuffer in = noise_picture(176, 200, PixelFormat{ChromaFormat::k420, 8}, 3);
    SessionOptions so;
    so.flavour = FgcFlavour::kVfgs;
    so.threads = 1;
    const std::vector<uint8_t> one = through_session(so, in);
    for (int t : {2, 3, 7}) {
        so.threads = t;
        EXPECT_EQ(through_session(so, in), one) << t << " threads";
    }
    vfgs::Options bad;
    bad.threads = -1;
    try {
        vfgs::Synthesizer v(bad);
        FAIL() << "threads = -1 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("threads = -1"), std::string::npos) << e.what();
    }
}

// reference_kernels reaches every model (benchmarks and verification compare the two paths
// through the session): the same pictures for rdd5, vtm and vfgs at 8 and 10 bits.
TEST(Session, ReferenceKernelsGiveTheSameOutputForEveryFlavour) {
    for (FgcFlavour f : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kVfgs})
        for (int bd : {8, 10}) {
            const FrameBuffer in = noise_picture(176, 200, PixelFormat{ChromaFormat::k420, bd}, 5);
            SessionOptions so;
            so.flavour = f;
            so.threads = 2;
            const std::vector<uint8_t> optimized = through_session(so, in);
            so.reference_kernels = true;
            EXPECT_EQ(through_session(so, in), optimized) << fgc_flavour_name(f) << " " << bd << "-bit";
        }
}

TEST(Session, ClipOverrideAndPictureMatrixReachAv1Synthesis) {
    const FrameBuffer in = noise_picture(96, 64, PixelFormat{ChromaFormat::k420, 10}, 9);
    for (int clip : {0, 1})
        for (int mc : {0, 1, 9}) {
            SessionOptions so;
            so.clip_to_restricted_range = clip;
            so.threads = 2;
            Session s(so);
            s.receive_av1_params(av1_params(), 0, 2);
            FrameBuffer a(in.width(), in.height(), in.format()), b = a;
            FrameInfo fi;
            fi.matrix_coefficients = mc;
            s.apply(const_cast<FrameBuffer&>(in).view(), a.view(), &fi);
            Av1FilmGrainParams p = av1_params();
            p.clip_to_restricted_range = clip;
            av1::apply_film_grain(p, const_cast<FrameBuffer&>(in).view(), b.view(), mc);
            EXPECT_TRUE(std::equal(a.bytes(), a.bytes() + a.byte_size(), b.bytes())) << clip << " " << mc;
        }
}

TEST(Session, OptionsOutsideTheirRangeAreRefusedNamingTheField) {
    SessionOptions o;
    o.block_size = 12;
    EXPECT_NE(error_of(o).find("block_size = 12 is not a block size (allowed 0, 8, 16, 32)"), std::string::npos);
    o = {};
    o.single_line_blocks = 4;
    EXPECT_NE(error_of(o).find("single_line_blocks = 4"), std::string::npos);
    o = {};
    o.clip_to_restricted_range = 2;
    EXPECT_NE(error_of(o).find("clip_to_restricted_range = 2 is out of range (allowed -1..1)"), std::string::npos);
    o = {};
    o.flavour = FgcFlavour::kVfgs;
    o.single_line_blocks = 8;
    EXPECT_NE(error_of(o).find("single_line_blocks is an option of the vtm and tr flavours"), std::string::npos);
    o = {};
    o.vfgs_gain_percent = 50;  // rdd5
    EXPECT_NE(error_of(o).find("belong to the vfgs flavour"), std::string::npos);
    o = {};
    o.flavour = FgcFlavour::kVfgs;
    o.vfgs_output_bit_depth = 7;
    EXPECT_NE(error_of(o).find("vfgs_output_bit_depth = 7"), std::string::npos);
    o = {};
    o.threads = 257;
    EXPECT_NE(error_of(o).find("threads = 257 is out of range (allowed 0..256)"), std::string::npos);
}

// ApplyResult::parameters_refused tells an invalid set passed through from a picture that
// simply has no grain: what the GStreamer element's on-invalid acts on.
TEST(Session, ParametersRefusedOnlyForInvalidSetsPassedThrough) {
    const PixelFormat fmt{ChromaFormat::k420, 8};
    // VFGS refuses pictures narrower than 129 or lower than 128
    FrameBuffer picture = noise_picture(192, 128, fmt, 3);
    FrameBuffer out(192, 128, fmt);
    SessionOptions o;
    o.passthrough_invalid = true;
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVfgs}) {
        SCOPED_TRACE(fgc_flavour_name(flavour));
        o.flavour = flavour;
        Session session(o);
        FgcParams bad = fgc_params();
        bad.comp[0].intervals[0].comp_model_value[0] = 5000;  // far beyond RDD 5's range
        session.receive_fgc_params(bad, FgcCodec::kHevc);
        const ApplyResult refused = session.apply(picture.view(), out.view());
        EXPECT_FALSE(refused.grain_applied);
        EXPECT_TRUE(refused.parameters_refused);
        EXPECT_NE(refused.message.find("comp_model_value"), std::string::npos) << refused.message;
        FgcParams cancel;
        cancel.film_grain_characteristics_cancel_flag = true;
        session.receive_fgc_params(cancel, FgcCodec::kHevc);
        const ApplyResult cancelled = session.apply(picture.view(), out.view());
        EXPECT_FALSE(cancelled.grain_applied);
        EXPECT_FALSE(cancelled.parameters_refused) << cancelled.message;
    }
    // AV1: an invalid set is refused, apply_grain = 0 is not
    Session av1(o);
    Av1FilmGrainParams bad = av1_params();
    bad.point_y_value = {200, 100};  // decreasing
    av1.receive_av1_params(bad);
    EXPECT_TRUE(av1.apply(picture.view(), out.view()).parameters_refused);
    Av1FilmGrainParams off = av1_params();
    off.apply_grain = 0;
    av1.receive_av1_params(off);
    EXPECT_FALSE(av1.apply(picture.view(), out.view()).parameters_refused);
}

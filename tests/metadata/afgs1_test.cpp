// AFGS1 T.35 payloads: write -> read round trips, stored sets across payloads,
// prediction, the interpretations of the defective text, selection, and every
// malformed-payload path of the reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <random>
#include <string>

#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/bit_reader.hpp"

using namespace filmgrain;

namespace {

// A random parameter set in canonical form (unused fields at their defaults), as
// the reader returns it.
Av1FilmGrainParams random_params(std::mt19937& rng, bool luma_only, bool allow_chroma) {
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.update_grain = 1;
    p.grain_seed = r(0, 65535);
    auto points = [&](int max_points, int* count, int* values, int* scalings) {
        *count = r(0, max_points);
        int v = r(0, 20);
        for (int i = 0; i < *count; ++i) {
            values[i] = v;
            scalings[i] = r(0, 3) == 0 ? r(0, 255) : r(0, 40);
            v += r(1, 30);
            if (v > 255) {
                *count = i + 1;
                break;
            }
        }
    };
    points(14, &p.num_y_points, p.point_y_value.data(), p.point_y_scaling.data());
    if (!luma_only && allow_chroma) {
        p.chroma_scaling_from_luma = r(0, 3) == 0;
        if (!p.chroma_scaling_from_luma) {
            points(10, &p.num_cb_points, p.point_cb_value.data(), p.point_cb_scaling.data());
            points(10, &p.num_cr_points, p.point_cr_value.data(), p.point_cr_scaling.data());
        }
    }
    p.grain_scaling_minus_8 = r(0, 3);
    p.ar_coeff_lag = r(0, 3);
    auto coeff = [&] { return r(0, 2) == 0 ? r(0, 255) : 128 + r(-15, 15); };
    if (p.num_y_points)
        for (int i = 0; i < p.num_pos_luma(); ++i) p.ar_coeffs_y_plus_128[i] = coeff();
    if (p.chroma_scaling_from_luma || p.num_cb_points)
        for (int i = 0; i < p.num_pos_chroma(); ++i) p.ar_coeffs_cb_plus_128[i] = coeff();
    if (p.chroma_scaling_from_luma || p.num_cr_points)
        for (int i = 0; i < p.num_pos_chroma(); ++i) p.ar_coeffs_cr_plus_128[i] = coeff();
    p.ar_coeff_shift_minus_6 = r(0, 3);
    p.grain_scale_shift = r(0, 3);
    if (p.num_cb_points) {
        p.cb_mult = r(0, 255);
        p.cb_luma_mult = r(0, 255);
        p.cb_offset = r(0, 511);
    }
    if (p.num_cr_points) {
        p.cr_mult = r(0, 255);
        p.cr_luma_mult = r(0, 255);
        p.cr_offset = r(0, 511);
    }
    p.overlap_flag = r(0, 1);
    p.clip_to_restricted_range = r(0, 1);
    return p;
}

Afgs1SetTarget random_target(std::mt19937& rng, bool luma_only) {
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Afgs1SetTarget t;
    t.apply_units_resolution_log2 = r(0, 4);
    t.apply_horz_resolution = r(0, 4095);
    t.apply_vert_resolution = r(0, 4095);
    t.luma_only_flag = luma_only;
    if (luma_only) {
        t.subsampling_x = t.subsampling_y = 0;
    } else {
        t.subsampling_x = r(0, 1);
        t.subsampling_y = t.subsampling_x ? r(0, 1) : 0;
    }
    t.video_signal_characteristics_flag = r(0, 1);
    if (t.video_signal_characteristics_flag) {
        t.bit_depth_minus8 = r(0, 4);
        t.cicp_info_present_flag = r(0, 1);
        if (t.cicp_info_present_flag) {
            t.color_primaries = std::array{1, 2, 4, 5, 6, 7, 8, 9, 10, 11, 12, 22}[std::size_t(r(0, 11))];
            t.transfer_characteristics = r(4, 18);
            t.matrix_coefficients = r(4, 14);
            t.video_full_range_flag = r(0, 1);
        }
    }
    return t;
}

// Sets that only differ from the first by their scaling values, so the writer predicts.
Av1FilmGrainParams variant_of(const Av1FilmGrainParams& first, std::mt19937& rng) {
    Av1FilmGrainParams p = first;
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    for (int i = 0; i < p.num_y_points; ++i) p.point_y_scaling[i] = std::clamp(p.point_y_scaling[i] + r(-3, 3), 0, 255);
    for (int i = 0; i < p.num_cb_points; ++i) p.point_cb_scaling[i] = std::clamp(p.point_cb_scaling[i] + r(-20, 20), 0, 255);
    p.grain_seed = r(0, 65535);
    return p;
}

Afgs1Payload random_payload(std::mt19937& rng) {
    auto r = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    Afgs1Payload pl;
    const int count = r(1, 8);
    std::vector<int> idx = {0, 1, 2, 3, 4, 5, 6, 7};
    std::shuffle(idx.begin(), idx.end(), rng);
    for (int n = 0; n < count; ++n) {
        Afgs1ParamSet s;
        s.film_grain_param_set_idx = idx[n];
        const bool luma_only = r(0, 5) == 0;
        s.target = random_target(rng, luma_only);
        if (n > 0 && r(0, 1) && !pl.sets[0].target.luma_only_flag && !luma_only) {
            s.params = variant_of(pl.sets[0].params, rng);
        } else {
            s.params = random_params(rng, luma_only, true);
        }
        pl.sets.push_back(s);
    }
    return pl;
}

std::string read_error(const std::vector<uint8_t>& bytes, bool header = true) {
    try {
        Afgs1Reader().receive(bytes, header);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kMalformedPayload) << e.what();
        return e.what();
    }
    return "";
}

// Hand-built payloads for the malformed paths: one set written by `body`, sized
// and padded like a writer would.
std::vector<uint8_t> one_set_payload(const std::function<void(BitWriter&)>& body, int size_adjust = 0,
                                     bool header = true) {
    BitWriter b;
    body(b);
    const std::size_t bits = b.bit_count();
    const std::size_t size = (bits + 9 + 7) / 8 + std::size_t(size_adjust);
    BitWriter w;
    if (header) {
        w.u(8, 0xB5);
        w.u(16, 0x5890);
        w.u(8, 1);
    }
    w.u(1, 1);
    w.u(4, 0);
    w.u(3, 0);
    w.u(1, 0);
    w.u(8, uint32_t(size));
    for (std::size_t i = 0; i < bits; ++i) w.u(1, (b.bytes()[i >> 3] >> (7 - (i & 7))) & 1u);
    for (std::size_t i = bits + 9; i < size * 8; ++i) w.u(1, 0);
    return w.bytes();
}

// Header of a full set up to (not including) predict_scaling_flag: idx 0, 4:2:0, no signal info.
void set_head(BitWriter& w, int idx = 0) {
    w.u(3, uint32_t(idx));
    w.u(1, 1);       // apply_grain_flag
    w.u(16, 1234);   // grain_seed
    w.u(1, 1);       // update_grain_flag
    w.u(4, 0);       // apply_units_resolution_log2
    w.u(12, 64);
    w.u(12, 64);
    w.u(1, 0);  // luma_only_flag
    w.u(1, 1);
    w.u(1, 1);
    w.u(1, 0);  // video_signal_characteristics_flag
}

// The rest of a set after the luma scaling function: no chroma points, lag 0.
// `predict`: predict_scaling_flag was 1, so each chroma function has its predict flag (0 here).
void set_tail(BitWriter& w, bool luma_points, bool predict = false) {
    w.u(1, 0);  // chroma_scaling_from_luma_flag
    if (predict) w.u(1, 0);
    w.u(4, 0);  // num_cb_points
    if (predict) w.u(1, 0);
    w.u(4, 0);  // num_cr_points
    w.u(2, 0);  // grain_scaling_minus8
    w.u(2, 0);  // ar_coeff_lag
    if (luma_points) w.u(2, 3);  // bits_per_ar_coeff_y_minus5 (no coefficients at lag 0)
    w.u(2, 0);
    w.u(2, 0);
    w.u(1, 0);
    w.u(1, 0);
}

void luma_points(BitWriter& w, std::initializer_list<std::pair<int, int>> inc_scal, int bits_incr = 8, int bits_scal = 8) {
    w.u(4, uint32_t(inc_scal.size()));
    w.u(3, uint32_t(bits_incr - 1));
    w.u(2, uint32_t(bits_scal - 5));
    for (auto [inc, scal] : inc_scal) {
        w.u(bits_incr, uint32_t(inc));
        w.u(bits_scal, uint32_t(scal));
    }
}

std::vector<uint8_t> valid_payload() {
    return one_set_payload([](BitWriter& w) {
        set_head(w);
        w.u(1, 0);  // predict_scaling_flag
        luma_points(w, {{10, 20}, {100, 60}});
        set_tail(w, true);
    });
}

}  // namespace

TEST(Afgs1, RandomPayloadsRoundTrip) {
    std::mt19937 rng(20240117);
    int predicted_payloads = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        const Afgs1Payload pl = random_payload(rng);
        const bool header = iter % 4 != 0;
        Afgs1WriteOptions wo;
        wo.t35_header = header;
        const std::vector<uint8_t> bytes = write_afgs1(pl, wo);
        EXPECT_EQ(afgs1_has_t35_header(bytes.data(), bytes.size()), header);
        Afgs1Reader reader;
        const Afgs1Payload back = reader.receive(bytes, header);
        ASSERT_EQ(back, pl) << "iteration " << iter;
        for (const auto& s : pl.sets) EXPECT_EQ(*reader.stored(s.film_grain_param_set_idx), s);
        wo.predict_scaling = false;
        const std::vector<uint8_t> plain = write_afgs1(pl, wo);
        EXPECT_LE(bytes.size(), plain.size());
        if (bytes.size() < plain.size()) ++predicted_payloads;
        ASSERT_EQ(Afgs1Reader().receive(plain, header), pl);
    }
    EXPECT_GT(predicted_payloads, 100);  // prediction was exercised
}

TEST(Afgs1, StoredSetsAcrossPayloads) {
    std::mt19937 rng(7);
    Afgs1Payload first;
    for (int idx : {3, 5}) {
        Afgs1ParamSet s;
        s.film_grain_param_set_idx = idx;
        s.target = random_target(rng, false);
        s.params = random_params(rng, false, true);
        first.sets.push_back(s);
    }
    Afgs1Reader reader;
    reader.receive(write_afgs1(first));

    // update_grain_flag = 0: the stored set with the new seed; apply_grain_flag = 0: disabled.
    Afgs1Payload second;
    Afgs1ParamSet reuse;
    reuse.film_grain_param_set_idx = 5;
    reuse.params.apply_grain = 1;
    reuse.params.update_grain = 0;
    reuse.params.grain_seed = 4321;
    Afgs1ParamSet off;
    off.film_grain_param_set_idx = 3;
    off.params.apply_grain = 0;
    second.sets = {reuse, off};
    const std::vector<uint8_t> bytes = write_afgs1(second);
    EXPECT_LE(bytes.size(), 4u + 1 + 4 + 1);  // short forms: 3 + 1 bytes of sets
    const Afgs1Payload got = reader.receive(bytes);
    ASSERT_EQ(got.sets.size(), 2u);
    Afgs1ParamSet want_reuse = first.sets[1];
    want_reuse.params.grain_seed = 4321;
    want_reuse.params.update_grain = 0;
    EXPECT_EQ(got.sets[0], want_reuse);
    Afgs1ParamSet want_off = first.sets[0];
    want_off.params.apply_grain = 0;
    want_off.params.update_grain = 0;
    EXPECT_EQ(got.sets[1], want_off);

    // Set 3 was disabled but keeps its parameters: update_grain_flag = 0 re-enables them.
    Afgs1Payload third;
    Afgs1ParamSet again;
    again.film_grain_param_set_idx = 3;
    again.params.apply_grain = 1;
    again.params.update_grain = 0;
    again.params.grain_seed = 99;
    third.sets = {again};
    const Afgs1Payload got3 = reader.receive(write_afgs1(third));
    Afgs1ParamSet want3 = first.sets[0];
    want3.params.grain_seed = 99;
    want3.params.update_grain = 0;
    EXPECT_EQ(got3.sets[0], want3);

    // A malformed payload leaves the stored sets untouched.
    const auto before = *reader.stored(5);
    EXPECT_THROW(reader.receive(std::vector<uint8_t>{0xB5, 0x58, 0x90, 0x01, 0x80}), Error);
    EXPECT_EQ(*reader.stored(5), before);
}

TEST(Afgs1, DisabledPayload) {
    const std::vector<uint8_t> bytes = write_afgs1(Afgs1Payload{0, {}});
    EXPECT_EQ(bytes, (std::vector<uint8_t>{0xB5, 0x58, 0x90, 0x01, 0x00}));
    const Afgs1Payload p = Afgs1Reader().receive(bytes);
    EXPECT_EQ(p.afgs1_enable_flag, 0);
    EXPECT_FALSE(select_afgs1_set(p, Afgs1Picture{64, 64}));
}

TEST(Afgs1, PredictionFormula) {
    // Reference set 0: luma points (20, 20) and (120, 40). Set 1 predicts with
    // multiplier 2.0 (256 + 32), intercept -5, 3-bit residuals 5 and 2 at granularity 2:
    //   ((20*32 + 8) >> 4) - 5 + (5 - 4)*2 = 37,   ((40*32 + 8) >> 4) - 5 + (2 - 4)*2 = 71
    BitWriter b0, b1;
    set_head(b0, 0);
    b0.u(1, 0);
    luma_points(b0, {{20, 20}, {100, 40}});
    set_tail(b0, true);
    set_head(b1, 1);
    b1.u(1, 1);  // predict_scaling_flag
    b1.u(1, 1);  // predict_y_scaling_flag
    b1.u(9, 256 + 32);
    b1.u(9, 256 - 5);
    b1.u(3, 3);
    b1.u(3, 5);
    b1.u(3, 2);
    b1.u(3, 2);  // granularity
    set_tail(b1, true, true);
    BitWriter w;
    w.u(8, 0xB5);
    w.u(16, 0x5890);
    w.u(8, 1);
    w.u(1, 1);
    w.u(4, 0);
    w.u(3, 1);
    for (BitWriter* b : {&b0, &b1}) {
        const std::size_t bits = b->bit_count(), size = (bits + 9 + 7) / 8;
        w.u(1, 0);
        w.u(8, uint32_t(size));
        for (std::size_t i = 0; i < bits; ++i) w.u(1, (b->bytes()[i >> 3] >> (7 - (i & 7))) & 1u);
        for (std::size_t i = bits + 9; i < size * 8; ++i) w.u(1, 0);
    }
    const Afgs1Payload p = Afgs1Reader().receive(w.bytes());
    ASSERT_EQ(p.sets.size(), 2u);
    const auto& q = p.sets[1].params;
    ASSERT_EQ(q.num_y_points, 2);
    EXPECT_EQ(q.point_y_value[0], 20);
    EXPECT_EQ(q.point_y_value[1], 120);
    EXPECT_EQ(q.point_y_scaling[0], 37);
    EXPECT_EQ(q.point_y_scaling[1], 71);
}

TEST(Afgs1, ZeroResidualBitsMeansNoResidual) {
    BitWriter b0, b1;
    set_head(b0, 0);
    b0.u(1, 0);
    luma_points(b0, {{20, 20}, {100, 40}});
    set_tail(b0, true);
    set_head(b1, 4);
    b1.u(1, 1);
    b1.u(1, 1);
    b1.u(9, 256 + 8);  // 0.5
    b1.u(9, 256 + 1);
    b1.u(3, 0);  // bits_per_y_scaling_res = 0: no residuals, no granularity
    set_tail(b1, true, true);
    BitWriter w;
    w.u(1, 1);
    w.u(4, 0);
    w.u(3, 1);
    for (BitWriter* b : {&b0, &b1}) {
        const std::size_t bits = b->bit_count(), size = (bits + 9 + 7) / 8;
        w.u(1, 0);
        w.u(8, uint32_t(size));
        for (std::size_t i = 0; i < bits; ++i) w.u(1, (b->bytes()[i >> 3] >> (7 - (i & 7))) & 1u);
        for (std::size_t i = bits + 9; i < size * 8; ++i) w.u(1, 0);
    }
    const Afgs1Payload p = Afgs1Reader().receive(w.bytes(), false);
    const auto& q = p.sets[1].params;
    ASSERT_EQ(q.num_y_points, 2);
    EXPECT_EQ(q.point_y_scaling[0], ((20 * 8 + 8) >> 4) + 1);
    EXPECT_EQ(q.point_y_scaling[1], ((40 * 8 + 8) >> 4) + 1);
}

TEST(Afgs1, ArCoefficientBiasRemovedOnce) {
    // lag 1, BitsArY = 5: raw 0 is coefficient -16, raw 31 is +15 (ar_coeffs_y_plus_128 112 / 143).
    const auto bytes = one_set_payload([](BitWriter& w) {
        set_head(w);
        w.u(1, 0);
        luma_points(w, {{0, 30}});
        w.u(1, 0);
        w.u(4, 0);
        w.u(4, 0);
        w.u(2, 0);
        w.u(2, 1);  // lag 1: 4 luma coefficients
        w.u(2, 0);  // BitsArY = 5
        for (int v : {0, 31, 16, 17}) w.u(5, uint32_t(v));
        w.u(2, 0);
        w.u(2, 0);
        w.u(1, 0);
        w.u(1, 0);
    });
    const auto p = Afgs1Reader().receive(bytes).sets[0].params;
    EXPECT_EQ(p.ar_coeffs_y_plus_128[0], 112);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[1], 143);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[2], 128);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[3], 129);
}

TEST(Afgs1, ReadsTheAomReferenceWriterLayout) {
    // AOM's AFGS1 writer uses 8-bit increments and scalings, a 0 chroma offset and
    // 8-bit AR coefficients coded as coefficient + 128.
    const auto bytes = one_set_payload([](BitWriter& w) {
        set_head(w);
        w.u(1, 0);
        luma_points(w, {{16, 40}, {100, 60}});
        w.u(1, 0);
        w.u(4, 1);  // num_cb_points
        w.u(3, 7);
        w.u(2, 3);
        w.u(8, 0);  // cb_scaling_offset
        w.u(8, 64);
        w.u(8, 33);
        w.u(4, 1);  // num_cr_points
        w.u(3, 7);
        w.u(2, 3);
        w.u(8, 0);
        w.u(8, 200);
        w.u(8, 44);
        w.u(2, 1);  // grain_scaling_minus8
        w.u(2, 1);  // lag 1
        w.u(2, 3);
        for (int c : {-3, 5, 0, 127}) w.u(8, uint32_t(c + 128));
        for (int plane = 0; plane < 2; ++plane) {
            w.u(2, 3);
            for (int c : {1, -128, 2, 3, 4}) w.u(8, uint32_t(c + 128));
        }
        w.u(2, 2);
        w.u(2, 1);
        for (int v : {120, 190, 300, 130, 180, 260}) w.u(v > 255 ? 9 : 8, uint32_t(v));
        w.u(1, 1);
        w.u(1, 1);
    });
    const auto p = Afgs1Reader().receive(bytes).sets[0].params;
    EXPECT_EQ(p.num_y_points, 2);
    EXPECT_EQ(p.point_y_value[1], 116);
    EXPECT_EQ(p.point_cb_value[0], 64);
    EXPECT_EQ(p.point_cb_scaling[0], 33);
    EXPECT_EQ(p.point_cr_value[0], 200);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[0], 125);
    EXPECT_EQ(p.ar_coeffs_y_plus_128[3], 255);
    EXPECT_EQ(p.ar_coeffs_cb_plus_128[1], 0);
    EXPECT_EQ(p.ar_coeffs_cr_plus_128[4], 132);
    EXPECT_EQ(p.cb_mult, 120);
    EXPECT_EQ(p.cb_luma_mult, 190);
    EXPECT_EQ(p.cb_offset, 300);
    EXPECT_EQ(p.cr_offset, 260);
    EXPECT_EQ(p.ar_coeff_shift_minus_6, 2);
    EXPECT_EQ(p.grain_scale_shift, 1);
    EXPECT_EQ(p.clip_to_restricted_range, 1);
}

TEST(Afgs1, Selection) {
    Afgs1Payload pl;
    auto add = [&](int idx, int w, int h, int sx, int sy, bool luma_only, int apply) {
        Afgs1ParamSet s;
        s.film_grain_param_set_idx = idx;
        s.target.apply_horz_resolution = w;
        s.target.apply_vert_resolution = h;
        s.target.luma_only_flag = luma_only;
        s.target.subsampling_x = sx;
        s.target.subsampling_y = sy;
        s.params.apply_grain = apply;
        s.params.grain_seed = idx;
        pl.sets.push_back(s);
    };
    add(0, 1920, 1080, 1, 1, false, 1);
    add(1, 1280, 720, 1, 1, false, 1);
    add(2, 3840, 2160, 1, 1, false, 0);
    add(3, 640, 360, 0, 0, true, 1);
    add(4, 1920, 1080, 0, 0, false, 1);
    auto pick = [&](int w, int h, ChromaFormat f) -> int {
        Afgs1Picture pic{w, h, f, 8};
        const auto s = select_afgs1_set(pl, pic);
        return s ? int(s->set_index) : -1;
    };
    EXPECT_EQ(pick(1920, 1080, ChromaFormat::k420), 0);   // exact
    EXPECT_EQ(pick(1920, 1080, ChromaFormat::k444), 4);   // subsampling decides
    EXPECT_EQ(pick(1600, 900, ChromaFormat::k420), 1);    // largest not above the picture
    EXPECT_EQ(pick(3840, 2160, ChromaFormat::k420), 2);   // exact, and it disables grain
    EXPECT_EQ(select_afgs1_set(pl, Afgs1Picture{3840, 2160})->params.apply_grain, 0);
    EXPECT_EQ(pick(1920, 1080, ChromaFormat::k400), 3);   // only the luma-only set fits
    EXPECT_EQ(pick(320, 180, ChromaFormat::k420), -1);    // nothing small enough
    // Bit depth and colour description, when signalled, must match.
    pl.sets[0].target.video_signal_characteristics_flag = 1;
    pl.sets[0].target.bit_depth_minus8 = 2;
    pl.sets[0].target.cicp_info_present_flag = 1;
    pl.sets[0].target.matrix_coefficients = 0;
    EXPECT_EQ(pick(1920, 1080, ChromaFormat::k420), 1);
    Afgs1Picture pic10{1920, 1080, ChromaFormat::k420, 10};
    auto s = select_afgs1_set(pl, pic10);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->set_index, 0u);
    EXPECT_EQ(s->matrix_coefficients, 0);  // from the set
    pic10.matrix_coefficients = 1;
    EXPECT_EQ(select_afgs1_set(pl, pic10)->set_index, 1u);
    EXPECT_EQ(select_afgs1_set(pl, pic10)->matrix_coefficients, 1);  // from the picture
    // Units: 1920x1080 in units of 8 is 240x135.
    pl.sets[1].target.apply_units_resolution_log2 = 3;
    pl.sets[1].target.apply_horz_resolution = 240;
    pl.sets[1].target.apply_vert_resolution = 135;
    EXPECT_EQ(pick(1920, 1080, ChromaFormat::k420), 1);
}

TEST(Afgs1Malformed, EveryTruncationIsAnErrorNamingAField) {
    std::mt19937 rng(3);
    for (int iter = 0; iter < 40; ++iter) {
        const std::vector<uint8_t> full = write_afgs1(random_payload(rng));
        for (std::size_t n = 0; n < full.size(); ++n) {
            const std::string e = read_error(std::vector<uint8_t>(full.begin(), full.begin() + long(n)));
            ASSERT_NE(e.find("truncated while reading"), std::string::npos) << n << ": " << e;
        }
    }
    EXPECT_NE(read_error({}).find("itu_t_t35_country_code"), std::string::npos);
}

TEST(Afgs1Malformed, BadCodes) {
    auto bytes = valid_payload();
    ASSERT_EQ(read_error(bytes), "");
    auto with = [&](std::size_t i, uint8_t v) {
        auto b = bytes;
        b[i] = v;
        return read_error(b);
    };
    EXPECT_NE(with(0, 0xB4).find("itu_t_t35_country_code = 180"), std::string::npos);
    EXPECT_NE(with(1, 0x59).find("itu_t_t35_terminal_provider_code"), std::string::npos);
    EXPECT_NE(with(2, 0x91).find("itu_t_t35_terminal_provider_code"), std::string::npos);
    EXPECT_NE(with(3, 0x02).find("itu_t_t35_terminal_provider_oriented_code = 2"), std::string::npos);
    // reserved_4bits: "ignored by a decoder"
    EXPECT_EQ(with(4, uint8_t(bytes[4] | 0x78)), "");
}

TEST(Afgs1Malformed, OutOfRangeAndReservedValues) {
    auto err = [](const std::function<void(BitWriter&)>& body, int size_adjust = 0) {
        return read_error(one_set_payload(body, size_adjust));
    };
    EXPECT_NE(err([](BitWriter& w) {
                  set_head(w);
                  w.u(1, 0);
                  w.u(4, 15);
              }).find("num_y_points = 15"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  set_head(w);
                  w.u(1, 0);
                  luma_points(w, {{10, 20}, {0, 30}});
                  set_tail(w, true);
              }).find("point_y_value_increment[1] = 0"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  set_head(w);
                  w.u(1, 0);
                  luma_points(w, {{200, 20}, {100, 30}});
                  set_tail(w, true);
              }).find("point_y_value[1] = 300"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  set_head(w);
                  w.u(1, 0);
                  luma_points(w, {{10, 20}});
                  w.u(1, 0);
                  w.u(4, 11);
              }).find("num_cb_points = 11"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  set_head(w);
                  w.u(1, 0);
                  luma_points(w, {{10, 20}});
                  w.u(1, 0);
                  w.u(4, 1);
                  w.u(3, 7);
                  w.u(2, 3);
                  w.u(8, 200);  // cb_scaling_offset
                  w.u(8, 10);
                  w.u(8, 100);  // 100 + 200 > 255
              }).find("point_cb_scaling[0] + cb_scaling_offset = 300"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  w.u(3, 0);
                  w.u(1, 1);
                  w.u(16, 0);
                  w.u(1, 1);
                  w.u(4, 0);
                  w.u(12, 1);
                  w.u(12, 1);
                  w.u(1, 0);
                  w.u(1, 1);
                  w.u(1, 1);
                  w.u(1, 1);  // video_signal_characteristics_flag
                  w.u(3, 5);  // bit_depth_minus8 = 5
              }).find("bit_depth_minus8 = 5"),
              std::string::npos);
    EXPECT_NE(err([](BitWriter& w) {
                  w.u(3, 0);
                  w.u(1, 1);
                  w.u(16, 0);
                  w.u(1, 1);
                  w.u(4, 0);
                  w.u(12, 1);
                  w.u(12, 1);
                  w.u(1, 0);
                  w.u(1, 0);
                  w.u(1, 1);  // 4:4:0
              }).find("subsampling_x = 0 with subsampling_y = 1"),
              std::string::npos);
    for (auto [field, value] : {std::pair{"color_primaries", 3}, std::pair{"transfer_characteristics", 0},
                                std::pair{"matrix_coefficients", 3}}) {
        const std::string f = field;
        const int v = value;
        const std::string e = err([&](BitWriter& w) {
            w.u(3, 0);
            w.u(1, 1);
            w.u(16, 0);
            w.u(1, 1);
            w.u(4, 0);
            w.u(12, 1);
            w.u(12, 1);
            w.u(1, 0);
            w.u(1, 1);
            w.u(1, 1);
            w.u(1, 1);
            w.u(3, 0);
            w.u(1, 1);  // cicp_info_present_flag
            w.u(8, f == "color_primaries" ? uint32_t(v) : 1);
            w.u(8, f == "transfer_characteristics" ? uint32_t(v) : 1);
            w.u(8, f == "matrix_coefficients" ? uint32_t(v) : 1);
            w.u(1, 0);
        });
        EXPECT_NE(e.find(f + " = " + std::to_string(v) + " is a reserved value"), std::string::npos) << e;
    }
    // payload_size too small, and non-zero padding.
    const auto too_small = err(
        [](BitWriter& w) {
            set_head(w);
            w.u(1, 0);
            luma_points(w, {{10, 20}});
            set_tail(w, true);
        },
        -1);
    EXPECT_NE(too_small.find("payload_size ="), std::string::npos) << too_small;
    auto padded = valid_payload();
    padded.back() |= 1;
    EXPECT_NE(read_error(padded).find("padding_zero_bit"), std::string::npos);
    auto trailing = valid_payload();
    trailing.push_back(0x55);
    EXPECT_NE(read_error(trailing).find("data after the last parameter set"), std::string::npos);
    trailing.back() = 0;  // zero bytes after the sets are tolerated
    EXPECT_EQ(read_error(trailing), "");
}

TEST(Afgs1Malformed, ReferencesThatDoNotExist) {
    // update_grain_flag = 0 for an index never signalled
    BitWriter w;
    w.u(8, 0xB5);
    w.u(16, 0x5890);
    w.u(8, 1);
    w.u(1, 1);
    w.u(4, 0);
    w.u(3, 0);
    w.u(1, 1);
    w.u(2, 3);
    w.u(3, 6);
    w.u(1, 1);
    w.u(16, 77);
    w.u(1, 0);
    EXPECT_NE(read_error(w.bytes()).find("update_grain_flag = 0 but film_grain_param_set_idx = 6 holds no parameters"),
              std::string::npos);
    // prediction in the first set
    EXPECT_NE(read_error(one_set_payload([](BitWriter& b) {
                  set_head(b);
                  b.u(1, 1);
              })).find("predict_scaling_flag = 1 in the first parameter set"),
              std::string::npos);
    // duplicate index: two apply_grain_flag = 0 sets with index 2
    BitWriter dup;
    dup.u(8, 0xB5);
    dup.u(16, 0x5890);
    dup.u(8, 1);
    dup.u(1, 1);
    dup.u(4, 0);
    dup.u(3, 1);
    for (int k = 0; k < 2; ++k) {
        dup.u(1, 1);
        dup.u(2, 1);
        dup.u(3, 2);
        dup.u(1, 0);
        dup.u(1, 0);
    }
    EXPECT_NE(read_error(dup.bytes()).find("film_grain_param_set_idx = 2 is signalled twice"), std::string::npos);
}

TEST(Afgs1Writer, RejectsWhatCannotBeCoded) {
    auto err = [](const Afgs1Payload& pl) {
        try {
            write_afgs1(pl);
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ErrorCode::kInvalidParams);
            return std::string(e.what());
        }
        return std::string();
    };
    Afgs1Payload pl;
    EXPECT_NE(err(pl).find("number of parameter sets"), std::string::npos);
    pl.sets.resize(9);
    EXPECT_NE(err(pl).find("number of parameter sets"), std::string::npos);
    pl.sets.resize(2);
    EXPECT_NE(err(pl).find("film_grain_param_set_idx = 0 is used by two sets"), std::string::npos);
    pl.sets.resize(1);
    pl.sets[0].params.apply_grain = 1;
    pl.sets[0].target.apply_horz_resolution = 4096;
    EXPECT_NE(err(pl).find("apply_horz_resolution"), std::string::npos);
    pl.sets[0].target.apply_horz_resolution = 64;
    pl.sets[0].params.num_y_points = 2;
    pl.sets[0].params.point_y_value = {10, 10};
    EXPECT_NE(err(pl).find("point_y_value[1]"), std::string::npos);
}

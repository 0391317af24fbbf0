// H.266 picture order count on hand-built streams (no H.266 encoder is packaged in Debian
// 12): an SPS with profile_tier_level, general constraints, sub-layers and subpictures in
// front of the POC fields, pictures whose header sits in a PH NAL unit or in the slice,
// lsb wrap-around, an end of sequence followed by a CRA with a dropped RASL picture, and
// ph_poc_msb_cycle_val. Every picture carries its own FGC SEI, so each unit's payload is
// checked to stay with its picture. The same streams carry AFGS1 (T.35 SEI, prefix and
// suffix) for issue 19's "AFGS1 inside H.266": stored sets in decode order, each picture
// taking its own unit's payload in output order, through `params extract` and `apply`.
#include <gtest/gtest.h>

#include <filesystem>

#include "bitstream/av1_grain_extraction.hpp"
#include "bitstream/h266_poc.hpp"
#include "bitstream/metadata_insertion.hpp"
#include "bitstream/nal_units.hpp"
#include "bitstream/stream_scan.hpp"
#include "metadata/bit_reader.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_sei.hpp"
#include "core/frame_buffer.hpp"
#include "filmgrain/session.hpp"
#include "stream_fixtures.hpp"
#include "tool_under_test.hpp"
#include <nlohmann/json.hpp>

using namespace filmgrain;
using namespace filmgrain::bitstream;

namespace {

constexpr int kLog2MaxLsb = 4;  // POC lsb wraps every 16

void append_nal(std::vector<uint8_t>& stream, int type, int temporal_id, const BitWriter& body_in) {
    BitWriter body = body_in;
    body.flag(true);  // rbsp_stop_one_bit
    body.byte_align_zero();
    std::vector<uint8_t> rbsp = {0x00, uint8_t((type << 3) | (temporal_id + 1))};
    rbsp.insert(rbsp.end(), body.bytes().begin(), body.bytes().end());
    const std::vector<uint8_t> nal = add_emulation_prevention(rbsp.data(), rbsp.size());
    stream.insert(stream.end(), {0, 0, 0, 1});
    stream.insert(stream.end(), nal.begin(), nal.end());
}

// sps_max_sublayers_minus1 = 2 (sub-layer level flags), GCI present with reserved bits,
// two subpictures of different size with explicit ids, two extra PH bytes with three
// extra bits present, and optionally the POC msb cycle.
BitWriter sps(bool msb_cycle) {
    BitWriter w;
    w.u(4, 0);  // sps_seq_parameter_set_id
    w.u(4, 0);  // sps_video_parameter_set_id
    w.u(3, 2);  // sps_max_sublayers_minus1
    w.u(2, 1);  // 4:2:0
    w.u(2, 1);  // CTU 64
    w.flag(true);  // sps_ptl_dpb_hrd_params_present_flag
    w.u(7, 1);
    w.flag(false);
    w.u(8, 51);
    w.u(2, 0);
    w.flag(true);  // gci_present_flag
    for (int i = 0; i < 71; i++) w.flag(i % 5 == 0);
    w.u(8, 3);  // gci_num_reserved_bits
    w.u(3, 0);
    w.byte_align_zero();
    w.flag(true);   // ptl_sublayer_level_present_flag[1]
    w.flag(false);  // [0]
    w.byte_align_zero();
    w.u(8, 48);  // sublayer_level_idc[1]
    w.u(8, 1);   // ptl_num_sub_profiles
    w.u(32, 0xdeadbeef);
    w.flag(false);  // sps_gdr_enabled_flag
    w.flag(true);   // sps_ref_pic_resampling_enabled_flag
    w.flag(false);  // sps_res_change_in_clvs_allowed_flag
    w.ue(320);      // width
    w.ue(192);      // height
    w.flag(true);   // conformance window
    for (int i = 0; i < 4; i++) w.ue(i);
    w.flag(true);  // sps_subpic_info_present_flag
    w.ue(1);       // two subpictures
    w.flag(false);  // sps_independent_subpics_flag
    w.flag(false);  // sps_subpic_same_size_flag
    // 320x192 in 64x64 CTUs: 5x3, so 3 bits for x and 2 for y.
    w.u(3, 2);  // width_minus1[0]
    w.u(2, 2);  // height_minus1[0]
    w.u(2, 3);  // treated_as_pic / loop filter [0]
    w.u(3, 3);  // top_left_x[1]
    w.u(2, 0);  // top_left_y[1]
    w.u(2, 0);  // flags [1]
    w.ue(7);    // sps_subpic_id_len_minus1
    w.flag(true);
    w.flag(true);
    w.u(8, 17);
    w.u(8, 42);
    w.ue(2);  // 10-bit
    w.u(2, 0);
    w.u(4, kLog2MaxLsb - 4);
    w.flag(msb_cycle);
    if (msb_cycle) w.ue(5);  // 6-bit msb cycle
    w.u(2, 2);               // sps_num_extra_ph_bytes
    for (int i = 0; i < 16; i++) w.flag(i == 1 || i == 7 || i == 12);
    w.u(2, 0);  // sps_num_extra_sh_bytes (not read; any continuation is fine)
    return w;
}

BitWriter pps() {
    BitWriter w;
    w.u(6, 0);
    w.u(4, 0);
    w.flag(false);
    return w;
}

void picture_header(BitWriter& w, bool irap, int lsb, bool msb_cycle_sps, int msb_cycle = -1) {
    w.flag(irap);   // ph_gdr_or_irap_pic_flag
    w.flag(false);  // ph_non_ref_pic_flag
    if (irap) w.flag(false);  // ph_gdr_pic_flag
    w.flag(!irap);            // ph_inter_slice_allowed_flag
    if (!irap) w.flag(true);
    w.ue(0);  // PPS 0
    w.u(kLog2MaxLsb, uint32_t(lsb));
    w.u(3, 5);  // the three ph_extra_bit
    if (msb_cycle_sps) {
        w.flag(msb_cycle >= 0);
        if (msb_cycle >= 0) w.u(6, uint32_t(msb_cycle));
    }
    w.flag(true);  // what follows in a real header; never read
}

struct Pic {
    int type, tid, lsb;
    bool ph_unit;
    int expected_poc;
    bool output = true;
    bool clvs = false;
    int msb_cycle = -1;
};

constexpr int kTrail = 0, kRasl = 3, kIdr = 7, kCra = 9, kPhNut = 19, kEos = 21;

AccessUnitSei fgc_sei_for(int i) {
    return {{SeiMessage{kSeiPayloadFgc, write_fgc_sei_payload(test_support::fgc_params_for(i), FgcCodec::kVvc)}}, {}};
}

std::vector<uint8_t> build(const std::vector<Pic>& pics, bool msb_cycle_sps, std::size_t eos_before,
                           const std::function<AccessUnitSei(int)>& sei_for = fgc_sei_for) {
    std::vector<uint8_t> s;
    append_nal(s, 15, 0, sps(msb_cycle_sps));
    append_nal(s, 16, 0, pps());
    for (std::size_t i = 0; i < pics.size(); i++) {
        const Pic& p = pics[i];
        if (i == eos_before) append_nal(s, kEos, 0, BitWriter{});
        const AccessUnitSei messages = sei_for(int(i));
        std::vector<uint8_t> sei;
        if (!messages.prefix.empty()) sei = sei_nal_unit(StreamCodec::kH266, false, messages.prefix);
        const bool irap = p.type == kIdr || p.type == kCra;
        if (p.ph_unit) {
            BitWriter ph;
            picture_header(ph, irap, p.lsb, msb_cycle_sps, p.msb_cycle);
            append_nal(s, kPhNut, p.tid, ph);
            s.insert(s.end(), sei.begin(), sei.end());
        } else {
            s.insert(s.end(), sei.begin(), sei.end());
        }
        for (int slice = 0; slice < 2; slice++) {  // two slices: only the first starts the picture
            BitWriter sl;
            const bool header_here = !p.ph_unit && slice == 0;
            sl.flag(header_here);
            if (header_here) picture_header(sl, irap, p.lsb, msb_cycle_sps, p.msb_cycle);
            sl.ue(3);
            append_nal(s, p.type, p.tid, sl);
        }
        if (!messages.suffix.empty()) {
            const auto suffix = sei_nal_unit(StreamCodec::kH266, true, messages.suffix);
            s.insert(s.end(), suffix.begin(), suffix.end());
        }
    }
    return s;
}

void expect_scan(const std::vector<Pic>& pics, const std::vector<uint8_t>& s) {
    const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kH266);
    EXPECT_TRUE(scan.warnings.empty());
    ASSERT_EQ(scan.units.size(), pics.size());
    int sequence = -1;
    for (std::size_t i = 0; i < pics.size(); i++) {
        const AccessUnit& u = scan.units[i];
        SCOPED_TRACE("picture " + std::to_string(i));
        EXPECT_TRUE(u.warnings.empty()) << (u.warnings.empty() ? "" : u.warnings[0]);
        EXPECT_EQ(u.pictures, 1);
        ASSERT_TRUE(u.poc.has_value());
        EXPECT_EQ(*u.poc, pics[i].expected_poc);
        EXPECT_EQ(u.output, pics[i].output);
        if (pics[i].clvs) sequence++;
        EXPECT_EQ(u.sequence, std::max(sequence, 0));
        ASSERT_EQ(u.fgc.size(), 1u);
        EXPECT_TRUE(u.fgc[0].params.has_value()) << u.fgc[0].error;
        EXPECT_EQ(u.fgc[0].payload, write_fgc_sei_payload(test_support::fgc_params_for(int(i)), FgcCodec::kVvc));
    }
}

}  // namespace

TEST(H266Poc, PictureHeaderUnitsAndInSliceHeadersWrapAndRestartAfterEndOfSequence) {
    const std::vector<Pic> pics = {
        {kIdr, 0, 0, true, 0, true, true},
        {kTrail, 0, 8, true, 8},
        {kTrail, 1, 4, false, 4},
        {kTrail, 2, 2, false, 2},
        {kTrail, 2, 6, true, 6},
        {kTrail, 0, 0, false, 16},   // lsb wraps: msb 16
        {kTrail, 1, 12, true, 12},   // 12 against prevTid0 16: same msb band below
        {kTrail, 0, 8, false, 24},
        {kTrail, 0, 15, true, 31},
        {kTrail, 0, 6, false, 38},   // wraps again
        // end of sequence: the CRA starts a new CLVS, its RASL picture is not output
        {kCra, 0, 5, true, 5, true, true},
        {kRasl, 0, 3, false, 3, false},
        {kTrail, 0, 9, false, 9},
    };
    expect_scan(pics, build(pics, false, 10));
}

TEST(H266Poc, MsbCycleValueOverridesTheDerivation) {
    std::vector<Pic> pics = {
        {kIdr, 0, 0, true, 0, true, true},
        {kTrail, 0, 4, false, 3 * 16 + 4, true, false, 3},
        {kTrail, 0, 6, true, 3 * 16 + 6},  // derived from the previous POC 52
    };
    expect_scan(pics, build(pics, true, 99));
}

TEST(H266Poc, SliceWithoutAnyPictureHeaderIsAWarningNotACrash) {
    std::vector<uint8_t> s;
    append_nal(s, 15, 0, sps(false));
    append_nal(s, 16, 0, pps());
    BitWriter sl;
    sl.flag(false);  // header not in the slice, and no PH unit came
    sl.ue(3);
    append_nal(s, kTrail, 0, sl);
    const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kH266);
    ASSERT_EQ(scan.units.size(), 1u);
    EXPECT_FALSE(scan.units[0].warnings.empty());
    EXPECT_FALSE(scan.units[0].poc.has_value());
}

namespace {

constexpr int kAfgs1Width = 96, kAfgs1Height = 64;

Afgs1ParamSet afgs1_set(int idx, const Av1FilmGrainParams& params, int width, int height) {
    Afgs1ParamSet set;
    set.film_grain_param_set_idx = idx;
    set.params = params;
    set.target.apply_horz_resolution = width;
    set.target.apply_vert_resolution = height;
    set.target.video_signal_characteristics_flag = 1;  // 8-bit 4:2:0
    return set;
}

// Decode-order unit i: even units a prefix SEI, odd ones a suffix SEI after their slices;
// unit 4 no payload; unit 6 update_grain_flag = 0 with a new seed (the set unit 5 stored);
// units 0 and 8 a second set for another picture size, which must be ignored.
std::vector<std::vector<uint8_t>> afgs1_payloads(std::size_t units) {
    std::vector<std::vector<uint8_t>> out;
    for (int i = 0; i < int(units); i++) {
        Afgs1Payload pl;
        if (i == 6) {
            Av1FilmGrainParams reseed = test_support::av1_params_for(5);
            reseed.update_grain = 0;
            reseed.grain_seed = 4321;
            pl.sets = {afgs1_set(0, reseed, kAfgs1Width, kAfgs1Height)};
        } else if (i != 4) {
            pl.sets = {afgs1_set(0, test_support::av1_params_for(i), kAfgs1Width, kAfgs1Height)};
            if (i % 8 == 0)
                pl.sets.insert(pl.sets.begin(),
                               afgs1_set(1, test_support::av1_params_for(i / 2 + 10), kAfgs1Width / 2, kAfgs1Height / 2));
        }
        out.push_back(pl.sets.empty() ? std::vector<uint8_t>{} : write_afgs1(pl));
    }
    return out;
}

Av1FilmGrainParams afgs1_expected(int unit) {
    Av1FilmGrainParams want = test_support::av1_params_for(unit == 6 ? 5 : unit);
    if (unit == 6) want.grain_seed = 4321;
    return want;
}

const std::vector<Pic> kReorderedPictures = {
    {kIdr, 0, 0, true, 0, true, true},  {kTrail, 0, 8, true, 8},   {kTrail, 1, 4, false, 4},
    {kTrail, 2, 2, false, 2},           {kTrail, 2, 6, true, 6},   {kTrail, 0, 0, false, 16},
    {kTrail, 1, 12, true, 12},          {kTrail, 0, 8, false, 24}, {kTrail, 0, 15, true, 31},
    {kTrail, 0, 6, false, 38},          {kCra, 0, 5, true, 5, true, true},
    {kRasl, 0, 3, false, 3, false},     {kTrail, 0, 9, false, 9},
};

std::vector<uint8_t> afgs1_stream(const std::vector<std::vector<uint8_t>>& payloads) {
    return build(kReorderedPictures, false, 10, [&](int i) {
        AccessUnitSei sei;
        if (payloads[std::size_t(i)].empty()) return sei;
        std::vector<SeiMessage>& where = i % 2 ? sei.suffix : sei.prefix;
        where.push_back(SeiMessage{kSeiPayloadT35, payloads[std::size_t(i)]});
        return sei;
    });
}

}  // namespace

TEST(H266Afgs1, EachOutputPictureTakesItsOwnUnitsPayloadWithStoredSetsInDecodeOrder) {
    const auto payloads = afgs1_payloads(kReorderedPictures.size());
    const auto stream = afgs1_stream(payloads);
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kH266);
    ASSERT_TRUE(scan.warnings.empty());
    ASSERT_EQ(scan.units.size(), kReorderedPictures.size());
    for (std::size_t i = 0; i < scan.units.size(); i++) {
        SCOPED_TRACE("unit " + std::to_string(i));
        ASSERT_EQ(scan.units[i].t35.size(), payloads[i].empty() ? 0u : 1u);
        if (payloads[i].empty()) continue;
        EXPECT_EQ(scan.units[i].t35[0].suffix, i % 2 == 1);
        EXPECT_TRUE(is_afgs1_t35(scan.units[i].t35[0].t35));
    }
    std::vector<std::string> warnings;
    const auto per_picture = afgs1_payloads_in_output_order(scan, warnings);
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings[0]);
    // POC order within each sequence; the RASL picture after the CRA is not output
    const std::vector<int> units_in_output = {0, 3, 2, 4, 1, 6, 5, 7, 8, 9, 10, 12};
    ASSERT_EQ(per_picture.size(), units_in_output.size());
    for (std::size_t k = 0; k < per_picture.size(); k++) {
        const int unit = units_in_output[k];
        SCOPED_TRACE("output picture " + std::to_string(k) + " (unit " + std::to_string(unit) + ")");
        ASSERT_EQ(per_picture[k].has_value(), unit != 4);
        if (unit == 4) continue;
        Afgs1Picture picture;
        picture.width = kAfgs1Width;
        picture.height = kAfgs1Height;
        const std::optional<Afgs1Selection> set = select_afgs1_set(*per_picture[k], picture);
        ASSERT_TRUE(set.has_value());
        Av1FilmGrainParams got = set->params;
        got.update_grain = afgs1_expected(unit).update_grain;
        EXPECT_EQ(got, afgs1_expected(unit));
    }
}

TEST(H266Afgs1, ParamsExtractThenApplyEqualsApplyWithThePayloadsInOutputOrder) {
    namespace fs = std::filesystem;
    const fs::path dir = test_support::fresh_test_dir("afgs1-h266");
    const auto payloads = afgs1_payloads(kReorderedPictures.size());
    const auto stream = afgs1_stream(payloads);
    test_support::write_bytes(dir / "s.266", stream);
    const std::vector<int> units_in_output = {0, 3, 2, 4, 1, 6, 5, 7, 8, 9, 10, 12};
    // `apply --afgs1` reads the files in output order, so unit 6's update_grain_flag = 0 would
    // meet another stored set there (unit 1's, output before it): its file carries the set it
    // resolves to in decode order instead (unit 5's with the new seed).
    for (std::size_t k = 0; k < units_in_output.size(); k++) {
        const int unit = units_in_output[k];
        if (payloads[std::size_t(unit)].empty()) continue;
        Afgs1Payload resolved;
        resolved.sets = {afgs1_set(0, afgs1_expected(6), kAfgs1Width, kAfgs1Height)};
        test_support::write_bytes(dir / ("afgs1_" + std::to_string(k) + ".bin"),
                                  unit == 6 ? write_afgs1(resolved) : payloads[std::size_t(unit)]);
    }
    // the clean pictures: no H.266 decoder is packaged, so a synthetic clip stands in for them
    std::vector<uint8_t> clean(units_in_output.size() * kAfgs1Width * kAfgs1Height * 3 / 2);
    for (std::size_t i = 0; i < clean.size(); i++) clean[i] = uint8_t(16 + (i * 7 + i / 97) % 200);
    test_support::write_bytes(dir / "clean.yuv", clean);
    using test_support::q;
    using test_support::tool;
    const std::string picture = " --size " + std::to_string(kAfgs1Width) + "x" + std::to_string(kAfgs1Height) +
                                " --pix-fmt yuv420p ";
    ASSERT_TRUE(test_support::run_or_fail(tool() + " params extract -q" + picture + q(dir / "s.266") + " -o " +
                                          q(dir / "p.json")));
    ASSERT_TRUE(test_support::run_or_fail(tool() + " apply -q" + picture + "-i " + q(dir / "clean.yuv") + " -p " +
                                          q(dir / "p.json") + " -o " + q(dir / "extracted.yuv")));
    ASSERT_TRUE(test_support::run_or_fail(tool() + " apply -q" + picture + "-i " + q(dir / "clean.yuv") + " --afgs1 " +
                                          q(dir / "afgs1_%d.bin") + " -o " + q(dir / "applied.yuv")));
    const auto extracted = test_support::read_bytes(dir / "extracted.yuv");
    ASSERT_EQ(extracted.size(), clean.size());
    EXPECT_TRUE(extracted == test_support::read_bytes(dir / "applied.yuv"));
    // output picture 3 is unit 4's, which carries no payload: no grain; every other one has grain
    const std::size_t fb = std::size_t(kAfgs1Width) * kAfgs1Height * 3 / 2;
    for (std::size_t k = 0; k < units_in_output.size(); k++)
        EXPECT_EQ(std::equal(extracted.begin() + long(fb * k), extracted.begin() + long(fb * (k + 1)),
                             clean.begin() + long(fb * k)),
                  k == 3)
            << "picture " << k;

    // The session fed in output order with each unit's payload as the scan resolves it in
    // decode order (write_afgs1_resolved: what fg_stream_scan_afgs1_payload and filmgrainparse
    // hand over) gives the same pictures. Unit 6's raw bytes would take the set unit 1 stored
    // (output before it) and give output picture 5 other grain.
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kH266);
    Afgs1Reader stored;
    std::vector<std::vector<uint8_t>> resolved(scan.units.size());
    for (std::size_t i = 0; i < scan.units.size(); i++)
        for (const FoundT35& t : scan.units[i].t35) resolved[i] = write_afgs1_resolved(stored.receive(t35_bytes(t.t35)));
    const auto applied = test_support::read_bytes(dir / "applied.yuv");
    for (const bool raw : {false, true}) {
        Session session;
        for (std::size_t k = 0; k < units_in_output.size(); k++) {
            const int unit = units_in_output[k];
            const std::vector<uint8_t>& bytes = raw ? payloads[std::size_t(unit)] : resolved[std::size_t(unit)];
            if (!bytes.empty()) session.receive_afgs1_t35(bytes.data(), bytes.size());
            FrameBuffer in(kAfgs1Width, kAfgs1Height, PixelFormat{ChromaFormat::k420, 8}), out = in;
            std::copy(clean.begin() + long(fb * k), clean.begin() + long(fb * (k + 1)), in.bytes());
            session.apply(in.view(), out.view());
            const bool same = std::equal(out.bytes(), out.bytes() + fb, applied.begin() + long(fb * k));
            EXPECT_EQ(same, !raw || unit != 6) << (raw ? "raw" : "resolved") << " payloads, picture " << k;
        }
    }

    // inspect reads each payload in decode order: unit 6's set shows the seed it signals on the
    // parameters it reuses, unit 0's two sets their two target pictures.
    const auto text = test_support::run_shell(tool() + " inspect " + q(dir / "s.266") + " 2>&1");
    ASSERT_TRUE(text.clean_success()) << text.output;
    EXPECT_NE(text.output.find("AFGS1: 2 set(s); #1 48x32 4:2:0 8-bit"), std::string::npos) << text.output;
    EXPECT_NE(text.output.find("#0 96x64 4:2:0 8-bit, seed 4321 on the stored parameters"), std::string::npos)
        << text.output;
    const auto js = test_support::run_shell(tool() + " inspect --json " + q(dir / "s.266") + " 2>/dev/null");
    ASSERT_TRUE(js.clean_success()) << js.output;
    const nlohmann::json units = nlohmann::json::parse(js.output).at("access_units");
    ASSERT_EQ(units.size(), scan.units.size());
    for (std::size_t i = 0; i < units.size(); i++) {
        const nlohmann::json& t35 = units[i].at("t35");
        ASSERT_EQ(t35.size(), payloads[i].empty() ? 0u : 1u) << "unit " << i;
        if (payloads[i].empty()) continue;
        const nlohmann::json& set = t35[0].at("afgs1_payload").at("sets").back();
        const Av1FilmGrainParams want = afgs1_expected(int(i));
        EXPECT_EQ(set.at("grain_seed").get<long long>(), want.grain_seed) << "unit " << i;
        EXPECT_EQ(set.at("num_y_points").get<long long>(), want.num_y_points) << "unit " << i;
        EXPECT_EQ(set.at("update_grain").get<long long>(), i == 6 ? 0 : 1) << "unit " << i;
        EXPECT_EQ(set.at("width").get<long long>(), kAfgs1Width) << "unit " << i;
    }
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

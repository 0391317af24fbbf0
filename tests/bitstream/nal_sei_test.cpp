// NAL framing, emulation prevention, SEI message lists, T.35 prefixes and AV1 OBU
// framing on hand-built inputs, including damaged ones.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "bitstream/av1_obu.hpp"
#include "bitstream/metadata_insertion.hpp"
#include "bitstream/nal_units.hpp"
#include "bitstream/sei_messages.hpp"
#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"
#include "metadata/fgc_sei.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;

TEST(EmulationPrevention, RoundTripsRandomPayloadsAndLeavesNoStartCode) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 500; trial++) {
        std::vector<uint8_t> rbsp(rng() % 64);
        // mostly zeros and small values: the bytes emulation prevention is about
        for (auto& b : rbsp) b = uint8_t(rng() % 3 == 0 ? rng() % 256 : rng() % 4);
        const auto nal = add_emulation_prevention(rbsp.data(), rbsp.size());
        for (std::size_t i = 0; i + 2 < nal.size(); i++)
            ASSERT_FALSE(nal[i] == 0 && nal[i + 1] == 0 && nal[i + 2] <= 2) << "trial " << trial << " byte " << i;
        if (!nal.empty()) ASSERT_NE(nal.back(), 0);
        auto back = remove_emulation_prevention(nal.data(), nal.size());
        // an RBSP ending in a single zero byte gets a 0x03 pad that is not an emulation
        // prevention byte (real RBSPs end with the stop bit, so only this test meets it)
        if (back.size() == rbsp.size() + 1) back.pop_back();
        ASSERT_EQ(back, rbsp) << "trial " << trial;
    }
}

TEST(AnnexB, SplitsStartCodesOfThreeAndFourBytesAndWarnsAboutGarbage) {
    const std::vector<uint8_t> s = {0x55, 0, 0, 1, 0x67, 1, 2, 0, 0, 0, 1, 0x68, 3, 0, 0, 1, 0, 0, 1, 0x65, 9, 0};
    const AnnexBSplit split = split_annexb(s.data(), s.size());
    ASSERT_EQ(split.nals.size(), 3u);
    EXPECT_EQ(s[split.nals[0].offset], 0x67);
    EXPECT_EQ(split.nals[0].size, 3u);
    EXPECT_EQ(s[split.nals[1].offset], 0x68);
    EXPECT_EQ(split.nals[1].size, 2u);
    EXPECT_EQ(s[split.nals[2].offset], 0x65);
    EXPECT_EQ(split.nals[2].size, 2u);  // trailing zero byte dropped
    EXPECT_EQ(split.warnings.size(), 2u);  // leading garbage, empty NAL unit
}

TEST(Sei, SeveralPayloadsPerNalWithLongTypesAndSizesRoundTrip) {
    std::vector<SeiMessage> msgs(3);
    msgs[0].payload_type = kSeiPayloadFgc;
    msgs[0].payload = write_fgc_sei_payload(filmgrain::test_support::fgc_params_for(3), FgcCodec::kHevc);
    msgs[1].payload_type = kSeiPayloadT35;
    msgs[1].payload = {0xB5, 0x58, 0x90, 0x01, 0, 0, 1, 0, 0, 0};
    msgs[2].payload_type = 300;  // coded as 0xFF 0x2D
    msgs[2].payload.assign(700, 0);  // size coded with two 0xFF bytes; all zeros needs escaping
    const auto rbsp = build_sei_rbsp(msgs);
    const auto nal = add_emulation_prevention(rbsp.data(), rbsp.size());
    const SeiParse back = parse_sei_rbsp(remove_emulation_prevention(nal.data(), nal.size()));
    EXPECT_TRUE(back.warnings.empty());
    ASSERT_EQ(back.messages.size(), 3u);
    for (int i = 0; i < 3; i++) {
        EXPECT_EQ(back.messages[i].payload_type, msgs[i].payload_type);
        EXPECT_EQ(back.messages[i].payload, msgs[i].payload);
    }
    T35Payload t;
    ASSERT_TRUE(parse_t35_payload(back.messages[1].payload.data(), back.messages[1].payload.size(), t));
    EXPECT_TRUE(is_afgs1_t35(t));
    EXPECT_EQ(t.bytes.size(), 9u);
}

TEST(Sei, ATruncatedMessageIsAWarningAndEarlierMessagesSurvive) {
    std::vector<SeiMessage> msgs(2);
    msgs[0].payload_type = 5;
    msgs[0].payload = {1, 2, 3};
    msgs[1].payload_type = kSeiPayloadFgc;
    msgs[1].payload.assign(40, 0x11);
    auto rbsp = build_sei_rbsp(msgs);
    rbsp.resize(rbsp.size() - 20);
    const SeiParse p = parse_sei_rbsp(rbsp);
    ASSERT_EQ(p.messages.size(), 1u);
    EXPECT_EQ(p.messages[0].payload_type, 5);
    ASSERT_EQ(p.warnings.size(), 1u);
    EXPECT_NE(p.warnings[0].find("payloadSize=40"), std::string::npos) << p.warnings[0];
}

TEST(T35, CountryCodeExtension) {
    const uint8_t b[] = {0xFF, 0x12, 0x34, 0x56, 0x07};
    T35Payload t;
    ASSERT_TRUE(parse_t35_payload(b, sizeof b, t));
    EXPECT_EQ(t.country_code, 0xFF);
    EXPECT_EQ(t.country_code_extension, 0x12);
    EXPECT_EQ(t.provider_code, 0x3456);
    EXPECT_EQ(t.provider_oriented_code, 7);
    EXPECT_FALSE(is_afgs1_t35(t));
    EXPECT_FALSE(parse_t35_payload(b, 0, t));
    EXPECT_FALSE(parse_t35_payload(b, 1, t));  // 0xFF without its extension byte
}

TEST(Av1Obu, Leb128RoundTripAndLimits) {
    for (uint64_t v : {0ull, 1ull, 127ull, 128ull, 16383ull, 16384ull, 0xFFFFFFFFull}) {
        std::vector<uint8_t> b;
        write_leb128(b, v);
        std::size_t pos = 0;
        uint64_t back = 0;
        ASSERT_TRUE(read_leb128(b.data(), b.size(), pos, back));
        EXPECT_EQ(back, v);
        EXPECT_EQ(pos, b.size());
    }
    const uint8_t too_long[] = {0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x80, 0x01};
    std::size_t pos = 0;
    uint64_t v = 0;
    EXPECT_FALSE(read_leb128(too_long, sizeof too_long, pos, v));
}

TEST(Av1Obu, LowOverheadStreamWithT35MetadataPerTemporalUnit) {
    std::vector<uint8_t> s;
    for (int tu = 0; tu < 3; tu++) {
        auto td = av1_obu_bytes(kObuTemporalDelimiter, {});
        s.insert(s.end(), td.begin(), td.end());
        auto md = av1_obu_bytes(kObuMetadata, av1_t35_metadata_payload({0xB5, 0x58, 0x90, 0x01, uint8_t(tu)}));
        s.insert(s.end(), md.begin(), md.end());
        auto fr = av1_obu_bytes(kObuFrame, {1, 2, 3});
        s.insert(s.end(), fr.begin(), fr.end());
    }
    const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kAv1);
    EXPECT_EQ(scan.container, "obu");
    ASSERT_EQ(scan.units.size(), 3u);
    for (int tu = 0; tu < 3; tu++) {
        ASSERT_EQ(scan.units[tu].t35.size(), 1u);
        EXPECT_TRUE(is_afgs1_t35(scan.units[tu].t35[0].t35));
        EXPECT_EQ(scan.units[tu].t35[0].t35.bytes.back(), tu);
        EXPECT_EQ(scan.units[tu].pictures, 1);
        EXPECT_TRUE(scan.units[tu].warnings.empty());
    }
    // an obu_size running past the end is a warning on the unit, the others stay
    s.resize(s.size() - 2);
    const StreamScan cut = scan_stream(s.data(), s.size(), StreamCodec::kAv1);
    ASSERT_EQ(cut.units.size(), 3u);
    EXPECT_EQ(cut.units[2].t35.size(), 1u);
    EXPECT_EQ(cut.warnings.size(), 1u);
}

TEST(Av1Obu, AnnexBContainerIsDetectedAndParsed) {
    // temporal_unit( frame_unit( obu_length obu ... ) ), OBUs without obu_size
    std::vector<uint8_t> fu;
    const std::vector<std::vector<uint8_t>> obus = {
        {uint8_t(kObuTemporalDelimiter << 3)},
        {uint8_t(kObuMetadata << 3), 4, 0xB5, 0x58, 0x90, 0x01, 0x80},
        {uint8_t(kObuFrame << 3), 9, 9}};
    for (const auto& o : obus) {
        write_leb128(fu, o.size());
        fu.insert(fu.end(), o.begin(), o.end());
    }
    std::vector<uint8_t> tu;
    write_leb128(tu, fu.size());
    tu.insert(tu.end(), fu.begin(), fu.end());
    std::vector<uint8_t> s;
    write_leb128(s, tu.size());
    s.insert(s.end(), tu.begin(), tu.end());
    EXPECT_EQ(detect_stream_codec(s.data(), s.size(), "x.bin"), StreamCodec::kAv1);
    const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kAv1);
    EXPECT_EQ(scan.container, "annexb-av1");
    ASSERT_EQ(scan.units.size(), 1u);
    ASSERT_EQ(scan.units[0].t35.size(), 1u);
    EXPECT_TRUE(is_afgs1_t35(scan.units[0].t35[0].t35));
}

TEST(StreamScan, GarbageNeverCrashesAndIsReported) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 300; trial++) {
        std::vector<uint8_t> s(rng() % 200);
        for (auto& b : s) b = uint8_t(rng() % 5 == 0 ? 0 : rng() % 256);
        for (StreamCodec c : {StreamCodec::kH264, StreamCodec::kH265, StreamCodec::kH266, StreamCodec::kAv1}) {
            const StreamScan scan = scan_stream(s.data(), s.size(), c);
            for (const AccessUnit& u : scan.units) EXPECT_LE(u.offset, s.size());
        }
    }
}

// A Matroska, MP4 or transport stream file given to the scanner is named as such, not
// scanned as a damaged elementary stream (its start bytes would pass for OBUs or NAL units).
TEST(StreamScan, ContainerFilesAreNamedAndRefused) {
    std::vector<uint8_t> mkv = {0x1A, 0x45, 0xDF, 0xA3, 0x9F, 0x42, 0x86, 0x81, 0x01};
    std::vector<uint8_t> mp4 = {0, 0, 0, 0x20, 'f', 't', 'y', 'p', 'i', 's', 'o', 'm'};
    std::vector<uint8_t> ts(3 * 188, 0xFF);
    ts[0] = ts[188] = ts[376] = 0x47;
    EXPECT_STREQ(container_name(mkv.data(), mkv.size()), "Matroska/WebM");
    EXPECT_STREQ(container_name(mp4.data(), mp4.size()), "MP4/QuickTime");
    EXPECT_STREQ(container_name(ts.data(), ts.size()), "MPEG transport stream");
    const std::vector<uint8_t> ivf = {'D', 'K', 'I', 'F', 0, 0, 32, 0};
    const std::vector<uint8_t> annexb = {0, 0, 0, 1, 0x40, 0x01, 0x0C};
    EXPECT_EQ(container_name(ivf.data(), ivf.size()), nullptr);
    EXPECT_EQ(container_name(annexb.data(), annexb.size()), nullptr);

    const std::string path = (std::filesystem::temp_directory_path() /
                              ("filmgrain-container-" + std::to_string(::getpid()) + ".ivf"))
                                 .string();
    {
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(mkv.data()), std::streamsize(mkv.size()));
    }
    try {
        scan_stream_file(path, StreamCodec::kAv1);
        ADD_FAILURE() << "a Matroska file was scanned";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::kUnsupported);
        EXPECT_NE(std::string(e.what()).find("Matroska/WebM"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("-f ivf"), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
}

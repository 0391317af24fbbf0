// fgc_sei_removal: what filmgrainparse hands a decoder that would apply FGC SEI itself.
#include "bitstream/fgc_sei_removal.hpp"

#include <gtest/gtest.h>

#include "bitstream/metadata_insertion.hpp"
#include "bitstream/nal_units.hpp"
#include "filmgrain/error.hpp"
#include "bitstream/stream_scan.hpp"
#include "metadata/fgc_sei.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using filmgrain::Error;

namespace {

// An H.265 access unit: a prefix SEI with `messages`, then an IDR slice's first bytes.
std::vector<uint8_t> access_unit(const std::vector<SeiMessage>& messages) {
    std::vector<uint8_t> au = sei_nal_unit(StreamCodec::kH265, false, messages);
    const std::vector<uint8_t> slice = {0, 0, 0, 1, 0x26, 0x01, 0xAF, 0x12, 0x34, 0x56};
    au.insert(au.end(), slice.begin(), slice.end());
    return au;
}

SeiMessage fgc_message(int k) {
    return SeiMessage{kSeiPayloadFgc, write_fgc_sei_payload(test_support::fgc_params_for(k), FgcCodec::kHevc)};
}

}  // namespace

TEST(FgcSeiRemoval, KeepsTheOtherMessagesOfTheSeiAndEverythingElse) {
    const SeiMessage t35{kSeiPayloadT35, {0xB5, 0x58, 0x90, 0x01, 0x10, 0x20}};
    const std::vector<uint8_t> in = access_unit({fgc_message(1), t35, fgc_message(2)});
    const auto out = remove_fgc_sei(StreamCodec::kH265, in.data(), in.size());
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(*out, access_unit({t35}));
    const StreamScan scan = scan_stream(out->data(), out->size(), StreamCodec::kH265);
    ASSERT_EQ(scan.units.size(), 1u);
    EXPECT_TRUE(scan.units[0].fgc.empty());
    EXPECT_EQ(scan.units[0].t35.size(), 1u);
}

TEST(FgcSeiRemoval, DropsAnSeiLeftEmptyAndLeavesUnitsWithoutFgcAlone) {
    const std::vector<uint8_t> in = access_unit({fgc_message(3)});
    const auto out = remove_fgc_sei(StreamCodec::kH265, in.data(), in.size());
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(*out, std::vector<uint8_t>({0, 0, 0, 1, 0x26, 0x01, 0xAF, 0x12, 0x34, 0x56}));
    const std::vector<uint8_t> plain = access_unit({SeiMessage{kSeiPayloadT35, {0xB5, 1}}});
    EXPECT_FALSE(remove_fgc_sei(StreamCodec::kH265, plain.data(), plain.size()).has_value());
    EXPECT_FALSE(remove_fgc_sei(StreamCodec::kAv1, in.data(), in.size()).has_value());
}

TEST(FgcSeiRemoval, H264SeiLosesItsFgcMessage) {
    std::vector<uint8_t> au = sei_nal_unit(
        StreamCodec::kH264, false,
        {SeiMessage{kSeiPayloadFgc, write_fgc_sei_payload(test_support::fgc_params_for(0), FgcCodec::kAvc)}});
    const std::vector<uint8_t> slice = {0, 0, 0, 1, 0x65, 0x88, 0x84, 0x00};
    au.insert(au.end(), slice.begin(), slice.end());
    const auto out = remove_fgc_sei(StreamCodec::kH264, au.data(), au.size());
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(*out, slice);
}

// Unit by unit as a parser element hands them over, NalStreamParser finds what the
// whole-stream scan finds.
TEST(NalStreamParser, AccessUnitsPushedOneByOneScanAsTheWholeStream) {
    std::vector<uint8_t> stream;
    std::vector<std::size_t> starts;
    for (int k = 0; k < 4; k++) {
        starts.push_back(stream.size());
        std::vector<uint8_t> au = sei_nal_unit(StreamCodec::kH265, false, {fgc_message(k)});
        // an IDR_W_RADL slice with first_slice_segment_in_pic_flag = 1, cut short: the POC
        // decoder warns the same way in both readings
        const std::vector<uint8_t> slice = {0, 0, 0, 1, 0x26, 0x01, 0xAF, uint8_t(k), 0x34};
        au.insert(au.end(), slice.begin(), slice.end());
        stream.insert(stream.end(), au.begin(), au.end());
    }
    starts.push_back(stream.size());
    const StreamScan whole = scan_stream(stream.data(), stream.size(), StreamCodec::kH265);
    NalStreamParser parser(StreamCodec::kH265);
    std::vector<AccessUnit> units;
    for (std::size_t i = 0; i + 1 < starts.size(); i++) {
        parser.push(stream.data() + starts[i], starts[i + 1] - starts[i], starts[i], units);
        parser.end_access_unit(units);
        ASSERT_EQ(units.size(), i + 1) << "one unit per push";
    }
    ASSERT_EQ(units.size(), whole.units.size());
    for (std::size_t i = 0; i < units.size(); i++) {
        EXPECT_EQ(units[i].index, whole.units[i].index);
        EXPECT_EQ(units[i].offset, whole.units[i].offset);
        ASSERT_EQ(units[i].fgc.size(), 1u);
        EXPECT_EQ(units[i].fgc[0].payload, whole.units[i].fgc[0].payload);
        EXPECT_EQ(units[i].warnings, whole.units[i].warnings);
    }
    EXPECT_THROW(NalStreamParser(StreamCodec::kAv1), Error);
}

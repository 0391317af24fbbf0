// Where a range of a coded stream may start decoding (bitstream/decode_restart.hpp): at the
// latest random access point at or before the range, unless libavcodec would carry an FGC SEI
// into it that a decoder starting there does not have; never past damaged units.
#include <gtest/gtest.h>

#include "bitstream/decode_restart.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;

namespace {

FoundFgc fgc_sei(bool persistence, int repetition_period = 1, bool cancel = false) {
    FoundFgc f;
    FgcParams p;
    p.film_grain_characteristics_cancel_flag = cancel;
    p.film_grain_characteristics_persistence_flag = persistence;
    p.film_grain_characteristics_repetition_period = repetition_period;
    f.params = p;
    return f;
}

// `count` access units of one picture each, an IDR every `idr_every`, each with a parameter
// set of its own when it is an IDR.
StreamScan stream(StreamCodec codec, int count, int idr_every) {
    StreamScan s;
    s.codec = codec;
    s.container = codec == StreamCodec::kAv1 ? "ivf" : "annexb";
    for (int i = 0; i < count; i++) {
        AccessUnit au;
        au.index = i;
        au.offset = 32 + 100 * std::size_t(i);
        au.pictures = 1;
        au.random_access = i % idr_every == 0;
        if (au.random_access) au.parameter_sets = {{au.offset + 4, 10}};
        s.units.push_back(au);
    }
    return s;
}

}  // namespace

TEST(DecodeRestart, LatestRandomAccessPointAtOrBeforeTheRange) {
    const StreamScan s = stream(StreamCodec::kH265, 40, 10);
    EXPECT_FALSE(plan_decode_restart(s, 0));
    EXPECT_FALSE(plan_decode_restart(s, 9));  // the stream's start is no restart: nothing to skip
    for (int first : {10, 15, 19}) {
        const auto r = plan_decode_restart(s, first);
        ASSERT_TRUE(r) << first;
        EXPECT_EQ(r->unit, 10);
        EXPECT_EQ(r->output_before, 10);
        EXPECT_EQ(r->offset, s.units[10].offset);
        // the parameter sets the skipped units held, not the restart unit's own
        EXPECT_EQ(r->parameter_sets, (std::vector<std::pair<std::size_t, std::size_t>>{{36, 10}}));
        EXPECT_EQ(r->ivf_header_bytes, 0u);
    }
    const auto r = plan_decode_restart(s, 39);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->unit, 30);
    EXPECT_EQ(r->parameter_sets.size(), 3u);
}

TEST(DecodeRestart, PicturesNotOutputDoNotCount) {
    StreamScan s = stream(StreamCodec::kH265, 20, 10);
    s.units[3].output = false;  // e.g. RASL pictures of a CRA the stream starts with
    s.units[4].output = false;
    const auto r = plan_decode_restart(s, 8);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->unit, 10);
    EXPECT_EQ(r->output_before, 8);
}

// libavcodec keeps a persistent FGC SEI into the IDR; a decoder starting at the IDR has none.
TEST(DecodeRestart, AnFgcSeiInForceBlocksTheRestartUnlessTheUnitBringsItsOwn) {
    StreamScan s = stream(StreamCodec::kH265, 20, 10);
    s.units[0].fgc = {fgc_sei(true)};
    EXPECT_FALSE(plan_decode_restart(s, 15));
    s.units[10].fgc = {fgc_sei(true)};
    ASSERT_TRUE(plan_decode_restart(s, 15));
    s.units[10].fgc.clear();
    s.units[0].fgc = {fgc_sei(false)};  // taken by picture 0 and dropped
    ASSERT_TRUE(plan_decode_restart(s, 15));
    s.units[0].fgc = {fgc_sei(true, 1, true)};  // a cancel
    ASSERT_TRUE(plan_decode_restart(s, 15));
    s.units[0].fgc = {fgc_sei(true)};
    s.units[5].fgc = {fgc_sei(true, 1, true)};  // cancelled before the IDR
    ASSERT_TRUE(plan_decode_restart(s, 15));
    // a suffix SEI is not read by libavcodec: it neither sets the state nor counts as the unit's own
    s.units[5].fgc.clear();
    s.units[10].fgc = {fgc_sei(true)};
    s.units[10].fgc[0].suffix = true;
    EXPECT_FALSE(plan_decode_restart(s, 15));
}

TEST(DecodeRestart, H264PersistsByRepetitionPeriod) {
    StreamScan s = stream(StreamCodec::kH264, 20, 10);
    s.units[0].fgc = {fgc_sei(false, 1)};
    EXPECT_FALSE(plan_decode_restart(s, 15));
    s.units[0].fgc = {fgc_sei(true, 0)};
    EXPECT_TRUE(plan_decode_restart(s, 15));
}

TEST(DecodeRestart, Av1KeyFramesAndTheIvfHeader) {
    StreamScan s = stream(StreamCodec::kAv1, 20, 6);
    s.units[0].fgc = {fgc_sei(true)};  // (AV1 has none; grain is in the frame headers)
    const auto r = plan_decode_restart(s, 13);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->unit, 12);
    EXPECT_EQ(r->ivf_header_bytes, 32u);
    EXPECT_TRUE(r->parameter_sets.empty());
}

TEST(DecodeRestart, NotPastDamageOrForH266) {
    StreamScan s = stream(StreamCodec::kH265, 20, 10);
    s.units[3].warnings = {"damaged"};
    EXPECT_FALSE(plan_decode_restart(s, 15));
    s.units[3].warnings.clear();
    s.units[12].warnings = {"damaged"};  // after the restart point: decoded either way
    EXPECT_TRUE(plan_decode_restart(s, 15));
    s.warnings = {"stream damaged"};
    EXPECT_FALSE(plan_decode_restart(s, 15));
    EXPECT_FALSE(plan_decode_restart(stream(StreamCodec::kH266, 20, 10), 15));
}

// The stream parsers on real encoder output made here: x265 and x264 streams with FGC
// SEI messages inserted by the project's own SEI writer, aomenc streams with T.35
// metadata OBUs. Checks: every payload found in its access unit, POC and output order
// against the encoders' known GOP structure, and damaged copies reported, not crashing.
#include <gtest/gtest.h>

#include <random>

#include "bitstream/metadata_insertion.hpp"
#include "bitstream/stream_report.hpp"
#include "bitstream/stream_scan.hpp"
#include "metadata/fgc_sei.hpp"
#include "stream_fixtures.hpp"

using namespace filmgrain;
using namespace filmgrain::bitstream;
using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

constexpr int kFrames = 16;

// FGC SEI in every access unit: prefix for even indices, suffix for odd ones (H.265),
// always with a T.35 message beside it in the same SEI NAL unit.
AccessUnitSei sei_for(StreamCodec codec, int au) {
    AccessUnitSei s;
    SeiMessage fgc{kSeiPayloadFgc, write_fgc_sei_payload(fgc_params_for(au),
                                                         codec == StreamCodec::kH264 ? FgcCodec::kAvc : FgcCodec::kHevc)};
    SeiMessage t35{kSeiPayloadT35, {0xB5, 0x00, 0x3C, uint8_t(au)}};
    if (codec == StreamCodec::kH265 && au % 2 == 1)
        s.suffix = {fgc, t35};
    else
        s.prefix = {t35, fgc};
    return s;
}

StreamScan encode_and_scan(const fs::path& dir, StreamCodec codec, const std::string& encoder_args) {
    const fs::path src = dir / "src.y4m", raw = dir / "raw.bin", with_sei = dir / "sei.bin";
    write_synthetic_y4m(src, 128, 96, kFrames, 8);
    const std::string cmd = codec == StreamCodec::kH264
                                ? "x264 --quiet " + encoder_args + " -o '" + raw.string() + "' '" + src.string() + "'"
                                : "x265 --log-level error " + encoder_args + " --input '" + src.string() + "' -o '" +
                                      raw.string() + "'";
    if (!run_or_fail(cmd)) return {};
    const auto stream = insert_sei(read_bytes(raw), codec, [&](int au) { return sei_for(codec, au); });
    write_bytes(with_sei, stream);
    return scan_stream(stream.data(), stream.size(), codec);
}

void expect_every_payload_in_its_unit(const StreamScan& scan, StreamCodec codec) {
    ASSERT_EQ(scan.units.size(), std::size_t(kFrames));
    for (const AccessUnit& u : scan.units) {
        SCOPED_TRACE("access unit " + std::to_string(u.index));
        EXPECT_TRUE(u.warnings.empty()) << u.warnings[0];
        EXPECT_EQ(u.pictures, 1);
        ASSERT_EQ(u.fgc.size(), 1u);
        ASSERT_TRUE(u.fgc[0].params.has_value()) << u.fgc[0].error;
        EXPECT_EQ(u.fgc[0].suffix, codec == StreamCodec::kH265 && u.index % 2 == 1);
        const FgcParams want = fgc_params_for(u.index);
        EXPECT_EQ(u.fgc[0].params->comp[0].intervals[0].comp_model_value, want.comp[0].intervals[0].comp_model_value);
        EXPECT_EQ(u.fgc[0].params->comp[1].intervals[0].comp_model_value, want.comp[1].intervals[0].comp_model_value);
        ASSERT_EQ(u.t35.size(), 1u);
        EXPECT_EQ(u.t35[0].t35.country_code, 0xB5);
        EXPECT_EQ(u.t35[0].t35.provider_code, 0x003C);
        EXPECT_EQ(u.t35[0].t35.bytes.back(), u.index);
    }
}

// With a fixed GOP of `gop` pictures, output picture k is display frame k; its POC is
// `scale` * (k - first frame of its coded video sequence).
void expect_output_order_pocs(const StreamScan& scan, int gop, int scale, bool closed) {
    const auto order = units_in_output_order(scan);
    ASSERT_EQ(order.size(), std::size_t(kFrames));
    for (int k = 0; k < kFrames; k++) {
        SCOPED_TRACE("output picture " + std::to_string(k));
        ASSERT_TRUE(order[k]->poc.has_value());
        EXPECT_EQ(*order[k]->poc, scale * (closed ? k % gop : k));
        EXPECT_EQ(order[k]->sequence, closed ? k / gop : 0);
    }
}

}  // namespace

TEST(EncodedStreams, H265ClosedGopIdrWithBFramesAndPrefixSuffixSei) {
    const fs::path dir = fresh_test_dir("h265-closed");
    const StreamScan scan = encode_and_scan(dir, StreamCodec::kH265,
                                            "--preset ultrafast --bframes 3 --keyint 8 --min-keyint 8 --no-scenecut "
                                            "--no-open-gop");
    EXPECT_EQ(scan.units[0].picture_type.substr(0, 3), "IDR");
    EXPECT_EQ(scan.units[8].picture_type.substr(0, 3), "IDR");
    // the IDRs are the random access points; x265 sends VPS, SPS and PPS once, before the first
    for (const AccessUnit& u : scan.units) {
        EXPECT_EQ(u.random_access, u.index % 8 == 0) << u.index;
        EXPECT_EQ(u.parameter_sets.size(), u.index == 0 ? 3u : 0u) << u.index;
    }
    expect_every_payload_in_its_unit(scan, StreamCodec::kH265);
    expect_output_order_pocs(scan, 8, 1, true);
    fs::remove_all(dir);
}

TEST(EncodedStreams, H265OpenGopCraKeepsCountingPoc) {
    const fs::path dir = fresh_test_dir("h265-open");
    const StreamScan scan = encode_and_scan(dir, StreamCodec::kH265,
                                            "--preset ultrafast --bframes 3 --keyint 8 --min-keyint 8 --no-scenecut "
                                            "--open-gop");
    bool saw_cra = false;
    for (const auto& u : scan.units) {
        saw_cra = saw_cra || u.picture_type == "CRA_NUT";
        // a CRA's leading pictures may refer to pictures before it: no restart there
        if (u.picture_type == "CRA_NUT") EXPECT_FALSE(u.random_access) << u.index;
    }
    EXPECT_TRUE(saw_cra);
    expect_every_payload_in_its_unit(scan, StreamCodec::kH265);
    expect_output_order_pocs(scan, 8, 1, false);
    fs::remove_all(dir);
}

TEST(EncodedStreams, H264PocType0WithBFrames) {
    const fs::path dir = fresh_test_dir("h264-b");
    const StreamScan scan = encode_and_scan(dir, StreamCodec::kH264,
                                            "--preset ultrafast --bframes 2 --b-adapt 0 --keyint 8 --min-keyint 8 "
                                            "--no-scenecut");
    expect_every_payload_in_its_unit(scan, StreamCodec::kH264);
    // x264 counts POC in fields: 2 per frame
    expect_output_order_pocs(scan, 8, 2, true);
    // an IDR every 8 units, each with its SPS and PPS (x264 repeats them)
    for (const AccessUnit& u : scan.units) {
        EXPECT_EQ(u.random_access, u.index % 8 == 0) << u.index;
        EXPECT_EQ(u.parameter_sets.size(), u.index % 8 == 0 ? 2u : 0u) << u.index;
    }
    for (const auto& u : scan.units) EXPECT_TRUE(u.idr_pic_id.has_value());
    fs::remove_all(dir);
}

TEST(EncodedStreams, H264PocType2WithoutBFrames) {
    const fs::path dir = fresh_test_dir("h264-p");
    const StreamScan scan = encode_and_scan(dir, StreamCodec::kH264,
                                            "--preset ultrafast --bframes 0 --keyint 8 --min-keyint 8 --no-scenecut");
    expect_every_payload_in_its_unit(scan, StreamCodec::kH264);
    expect_output_order_pocs(scan, 8, 2, true);
    fs::remove_all(dir);
}

TEST(EncodedStreams, ParamsFileListsOutputOrderWithEachUnitsSei) {
    const fs::path dir = fresh_test_dir("h265-params");
    const StreamScan scan = encode_and_scan(dir, StreamCodec::kH265,
                                            "--preset ultrafast --bframes 3 --keyint 8 --min-keyint 8 --no-scenecut "
                                            "--no-open-gop");
    std::vector<std::string> warnings;
    const ParamsFile f = params_file_from_scan(scan, warnings);
    EXPECT_TRUE(warnings.empty());
    const auto order = units_in_output_order(scan);
    ASSERT_EQ(f.frames.size(), order.size());
    for (std::size_t k = 0; k < order.size(); k++) {
        EXPECT_EQ(f.frames[k].poc, order[k]->poc);
        ASSERT_TRUE(f.frames[k].fgc.has_value());
        EXPECT_EQ(f.frames[k].fgc->comp[0].intervals[0].comp_model_value,
                  fgc_params_for(order[k]->index).comp[0].intervals[0].comp_model_value);
    }
    fs::remove_all(dir);
}

TEST(EncodedStreams, AomencStreamWithT35MetadataObus) {
    const fs::path dir = fresh_test_dir("av1-t35");
    const fs::path src = dir / "src.y4m", raw = dir / "raw.ivf";
    write_synthetic_y4m(src, 64, 64, 4, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=4 --cpu-used=6 --film-grain-test=2 -o '" + raw.string() +
                            "' '" + src.string() + "'"));
    const auto stream = insert_av1_t35(read_bytes(raw), [](int tu) {
        return std::vector<std::vector<uint8_t>>{{0xB5, 0x58, 0x90, 0x01, uint8_t(tu), 0x00, 0x00, 0x01}};
    });
    const StreamScan scan = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    EXPECT_EQ(scan.container, "ivf");
    ASSERT_EQ(scan.units.size(), 4u);
    for (const AccessUnit& u : scan.units) {
        EXPECT_TRUE(u.warnings.empty());
        EXPECT_GE(u.pictures, 1);
        // only the first temporal unit shows a key frame, with the sequence header
        EXPECT_EQ(u.random_access, u.index == 0) << u.index;
        ASSERT_EQ(u.t35.size(), 1u);
        EXPECT_TRUE(is_afgs1_t35(u.t35[0].t35));
        EXPECT_EQ(u.t35[0].t35.bytes[3], u.index);
        EXPECT_EQ(u.t35[0].t35.bytes.size(), 7u);
    }
    fs::remove_all(dir);
}

TEST(EncodedStreams, TruncatedAndCorruptedCopiesAreReportedNotFatal) {
    const fs::path dir = fresh_test_dir("h265-damage");
    const StreamScan clean = encode_and_scan(dir, StreamCodec::kH265, "--preset ultrafast --bframes 3 --keyint 8");
    const auto stream = read_bytes(dir / "sei.bin");
    ASSERT_FALSE(stream.empty());
    std::mt19937 rng(3);
    int damaged_reports = 0;
    for (int trial = 0; trial < 200; trial++) {
        std::vector<uint8_t> s(stream.begin(), stream.begin() + long(rng() % stream.size()));
        for (int flips = 0; flips < 4 && !s.empty(); flips++) s[rng() % s.size()] ^= uint8_t(1u << (rng() % 8));
        const StreamScan scan = scan_stream(s.data(), s.size(), StreamCodec::kH265);
        EXPECT_LE(scan.units.size(), clean.units.size() + 8);
        damaged_reports += scan.bad_units() > 0 || !scan.warnings.empty();
    }
    // bit flips inside SEI payloads, parameter sets or slice headers must show up somewhere
    EXPECT_GT(damaged_reports, 0);
    fs::remove_all(dir);
}

// A stream read a run at a time (scan_stream_file scans H.26x so, whatever its size) gives
// the whole-stream scan unit for unit, field for field: for x265 and x264 streams with SEI in
// every unit, whatever the run length and the first bytes, and for damaged copies too.
namespace {

std::string describe(const StreamScan& s) {
    std::string d;
    for (const std::string& w : s.warnings) d += "W " + w + "\n";
    for (const AccessUnit& u : s.units) {
        d += std::to_string(u.index) + " @" + std::to_string(u.offset) + " " + u.picture_type + " poc " +
             (u.poc ? std::to_string(*u.poc) : "-") + " idr " + (u.idr_pic_id ? std::to_string(*u.idr_pic_id) : "-") +
             " seq " + std::to_string(u.sequence) + " out " + std::to_string(u.output) + " nal " +
             std::to_string(u.nal_units) + " pic " + std::to_string(u.pictures) + " ra " + std::to_string(u.random_access);
        for (const auto& [at, size] : u.parameter_sets) d += " ps " + std::to_string(at) + "+" + std::to_string(size);
        for (const FoundFgc& f : u.fgc) d += " fgc " + std::to_string(f.suffix) + ":" + std::to_string(f.payload.size()) + f.error;
        for (const FoundT35& t : u.t35) d += " t35 " + std::to_string(t.t35.bytes.size());
        for (const std::string& w : u.warnings) d += " w " + w;
        if (u.pts) d += " pts " + std::to_string(*u.pts);
        if (u.av1_sequence_header) d += " seqhdr";
        if (u.av1_frame_grain) d += " grain " + std::to_string(u.av1_frame_grain->grain_seed);
        d += "\n";
    }
    return d;
}

StreamScan scan_in_runs(const std::vector<uint8_t>& stream, StreamCodec codec, std::size_t first_bytes, std::size_t run) {
    std::vector<uint8_t> first(stream.begin(), stream.begin() + long(std::min(first_bytes, stream.size())));
    std::size_t pos = first.size();
    return scan_stream_incrementally(codec, std::move(first), [&](uint8_t* dst, std::size_t n) {
        const std::size_t k = std::min(n, stream.size() - pos);
        std::copy(stream.begin() + long(pos), stream.begin() + long(pos + k), dst);
        pos += k;
        return k;
    }, run);
}

}  // namespace

TEST(EncodedStreams, ScanningInRunsEqualsScanningWhole) {
    const fs::path dir = fresh_test_dir("runs");
    for (StreamCodec codec : {StreamCodec::kH265, StreamCodec::kH264}) {
        SCOPED_TRACE(stream_codec_name(codec));
        const StreamScan whole = encode_and_scan(dir, codec,
                                                 codec == StreamCodec::kH265 ? "--preset ultrafast --bframes 3 --keyint 8"
                                                                             : "--preset ultrafast --bframes 2 --keyint 8");
        const auto stream = read_bytes(dir / "sei.bin");
        ASSERT_FALSE(stream.empty());
        const std::string want = describe(whole);
        for (std::size_t run : {1, 2, 3, 5, 61, 997, 1 << 16})
            for (std::size_t first : {std::size_t(0), std::size_t(4), std::size_t(700)})
                ASSERT_EQ(describe(scan_in_runs(stream, codec, first, run)), want) << "run " << run << " first " << first;
        // damaged copies: the same warnings and units either way
        std::mt19937 rng(11);
        for (int trial = 0; trial < 200; trial++) {
            std::vector<uint8_t> s(stream.begin(), stream.begin() + long(rng() % stream.size()));
            for (int flips = 0; flips < 4 && !s.empty(); flips++) s[rng() % s.size()] ^= uint8_t(1u << (rng() % 8));
            const std::size_t first = rng() % 64, run = 1 + rng() % 300;
            ASSERT_EQ(describe(scan_in_runs(s, codec, first, run)), describe(scan_stream(s.data(), s.size(), codec)))
                << "trial " << trial << " first " << first << " run " << run;
        }
    }
    fs::remove_all(dir);
}

TEST(EncodedStreams, Av1IvfScannedInRunsEqualsScanningWhole) {
    const fs::path dir = fresh_test_dir("runs-av1");
    write_synthetic_y4m(dir / "src.y4m", 64, 64, 8, 8);
    ASSERT_TRUE(run_or_fail("aomenc --quiet --ivf --limit=8 --cpu-used=8 --kf-max-dist=4 --film-grain-test=3 -o '" +
                            (dir / "g.ivf").string() + "' '" + (dir / "src.y4m").string() + "'"));
    const auto stream = read_bytes(dir / "g.ivf");
    const StreamScan whole = scan_stream(stream.data(), stream.size(), StreamCodec::kAv1);
    ASSERT_EQ(whole.units.size(), 8u);
    const std::string want = describe(whole);
    for (std::size_t run : {1, 7, 12, 33, 1000, 1 << 16})
        for (std::size_t first : {std::size_t(32), std::size_t(40), std::size_t(700)})
            ASSERT_EQ(describe(scan_in_runs(stream, StreamCodec::kAv1, first, run)), want) << "run " << run << " first " << first;
    std::mt19937 rng(12);
    for (int trial = 0; trial < 200; trial++) {
        std::vector<uint8_t> s(stream.begin(), stream.begin() + long(32 + rng() % (stream.size() - 32)));
        for (int flips = 0; flips < 3; flips++) s[32 + rng() % (s.size() - 32)] ^= uint8_t(1u << (rng() % 8));
        const std::size_t first = 32 + rng() % 64, run = 1 + rng() % 300;
        ASSERT_EQ(describe(scan_in_runs(s, StreamCodec::kAv1, first, run)),
                  describe(scan_stream(s.data(), s.size(), StreamCodec::kAv1)))
            << "trial " << trial << " first " << first << " run " << run;
    }
    // cut inside the file header
    const std::vector<uint8_t> header_only(stream.begin(), stream.begin() + 20);
    EXPECT_EQ(describe(scan_in_runs(header_only, StreamCodec::kAv1, 8, 5)),
              describe(scan_stream(header_only.data(), header_only.size(), StreamCodec::kAv1)));
    fs::remove_all(dir);
}

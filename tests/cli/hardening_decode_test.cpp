// `filmgrain decode` on damaged AV1 (issue 24): what the decoder refuses is skipped with a
// warning naming the unit, as ffmpeg and dav1d do, and decoding goes on; --strict makes the
// damage a non-zero exit after the same complete output; a stream of which nothing decodes is
// an error without an output file. The streams are encoded here (aomenc, 64x64, 6 frames,
// --film-grain-test=1) and damaged deterministically: the forbidden bit of a frame OBU's
// header (which every AV1 decoder refuses) plus bits of its payload.
//
// Run against the ASan/UBSan tool too (FILMGRAIN_TOOL_UNDER_TEST, tests/CMakeLists.txt).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tool_under_test.hpp"

using namespace filmgrain::test_support;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 64, kHeight = 64, kFrames = 6;
constexpr std::size_t kFrameBytes = kWidth * kHeight * 3 / 2;

std::vector<uint8_t> read_file(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), {});
}

void write_file(const fs::path& p, const std::vector<uint8_t>& b) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// Moving content, so that aomenc codes inter frames with real tile data.
void write_source_y4m(const fs::path& p) {
    std::ofstream f(p, std::ios::binary);
    f << "YUV4MPEG2 W" << kWidth << " H" << kHeight << " F25:1 Ip A1:1 C420jpeg\n";
    for (int t = 0; t < kFrames; t++) {
        f << "FRAME\n";
        std::string pic(kFrameBytes, char(128));
        for (int y = 0; y < kHeight; y++)
            for (int x = 0; x < kWidth; x++) {
                int v = 40 + (x + 3 * t) * 150 / kWidth + (y + t) * 40 / kHeight + ((x * 7 + y * 13) % 17);
                if ((x - 4 * t + 64) % 40 < 12 && (y + 2 * t) % 32 < 10) v = 230 - v / 3;
                pic[std::size_t(y * kWidth + x)] = char(v);
            }
        f << pic;
    }
}

// The pictures of a Y4M file of kWidth x kHeight yuv420p (empty when it is not one).
std::vector<std::vector<uint8_t>> y4m_frames(const fs::path& p) {
    const std::vector<uint8_t> d = read_file(p);
    std::vector<std::vector<uint8_t>> frames;
    std::size_t pos = 0;
    while (pos < d.size() && d[pos] != '\n') pos++;
    const std::string header(d.begin(), d.begin() + long(pos));
    if (header.rfind("YUV4MPEG2 W64 H64", 0) != 0) return frames;
    pos++;
    while (pos + 6 + kFrameBytes <= d.size() && std::string(d.begin() + long(pos), d.begin() + long(pos + 6)) == "FRAME\n") {
        frames.emplace_back(d.begin() + long(pos + 6), d.begin() + long(pos + 6 + kFrameBytes));
        pos += 6 + kFrameBytes;
    }
    return frames;
}

struct IvfFrame {
    std::size_t header;   // where its 12-byte IVF frame header starts
    std::size_t payload;  // where its temporal unit starts
    std::size_t size;
};

std::vector<IvfFrame> ivf_frames(const std::vector<uint8_t>& s) {
    std::vector<IvfFrame> f;
    for (std::size_t pos = 32; pos + 12 <= s.size();) {
        const std::size_t size = s[pos] | s[pos + 1] << 8 | s[pos + 2] << 16 | std::size_t(s[pos + 3]) << 24;
        f.push_back({pos, pos + 12, size});
        pos += 12 + size;
    }
    return f;
}

// Where the header of the first frame or frame header OBU (types 6, 3) of a temporal unit is,
// and where its payload starts; 0 when there is none.
std::pair<std::size_t, std::size_t> frame_obu(const std::vector<uint8_t>& s, const IvfFrame& tu) {
    for (std::size_t p = tu.payload; p < tu.payload + tu.size;) {
        const int type = (s[p] >> 3) & 15;
        std::size_t at = p + 1 + ((s[p] >> 2) & 1), size = 0;
        for (int shift = 0;; shift += 7) {
            const uint8_t b = s[at++];
            size |= std::size_t(b & 127) << shift;
            if (!(b & 128)) break;
        }
        if (type == 6 || type == 3) return {p, at};
        p = at + size;
    }
    return {0, 0};
}

class HardeningDecode : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new fs::path(fs::temp_directory_path() / ("filmgrain-hardening-decode-" + std::to_string(::getpid())));
        fs::remove_all(*dir_);
        fs::create_directories(*dir_);
        if (std::system("command -v aomenc >/dev/null 2>&1") != 0) return;
        write_source_y4m(*dir_ / "src.y4m");
        const std::string cmd = "aomenc --quiet --ivf --limit=" + std::to_string(kFrames) +
                                " --cpu-used=6 --threads=1 --film-grain-test=1 -o " + q(*dir_ / "clean.ivf") + " " +
                                q(*dir_ / "src.y4m") + " >/dev/null 2>&1";
        if (std::system(cmd.c_str()) != 0) fs::remove(*dir_ / "clean.ivf");
    }
    static void TearDownTestSuite() {
        // FILMGRAIN_KEEP_TEST_FILES=1 keeps the streams for a look at a failure
        if (!std::getenv("FILMGRAIN_KEEP_TEST_FILES")) fs::remove_all(*dir_);
        delete dir_;
    }
    void SetUp() override {
        if (!fs::exists(*dir_ / "clean.ivf")) GTEST_SKIP() << "aomenc (aom-tools) is not installed";
        clean_ = read_file(*dir_ / "clean.ivf");
        frames_ = ivf_frames(clean_);
        ASSERT_EQ(frames_.size(), std::size_t(kFrames));
        const CommandResult r = run_tool("decode -q " + q(*dir_ / "clean.ivf") + " -o " + q(dir() / "clean.y4m"));
        if (r.output.find("no libavformat") != std::string::npos) GTEST_SKIP() << "built without libav*";
        ASSERT_TRUE(r.clean_success()) << r.output;
        EXPECT_EQ(r.output, "") << "a clean stream gives no warning";
        clean_pictures_ = y4m_frames(dir() / "clean.y4m");
        ASSERT_EQ(clean_pictures_.size(), std::size_t(kFrames));
    }
    static fs::path dir() { return *dir_; }
    // A copy of the clean stream whose temporal unit `tu` (its first frame OBU) is refused by
    // any decoder: the OBU's forbidden bit and two bits of its payload flipped.
    void damage(std::vector<uint8_t>& s, int tu) const {
        const auto [header, payload] = frame_obu(s, frames_[std::size_t(tu)]);
        ASSERT_GT(header, 0u) << "temporal unit " << tu << " has no frame OBU";
        s[header] ^= 0x80;
        s[payload] ^= 0x10;
        s[payload + 1] ^= 0x02;
    }
    // The first temporal unit with a frame OBU of its own (not a show_existing_frame) after the
    // key frame's: its picture is the one that goes missing.
    int damageable_unit() const {
        for (int tu = 2; tu < kFrames; tu++)
            if (frame_obu(clean_, frames_[std::size_t(tu)]).first &&
                ((clean_[frame_obu(clean_, frames_[std::size_t(tu)]).first] >> 3) & 15) == 6)
                return tu;
        return 2;
    }

    static fs::path* dir_;
    std::vector<uint8_t> clean_;
    std::vector<IvfFrame> frames_;
    std::vector<std::vector<uint8_t>> clean_pictures_;
};

fs::path* HardeningDecode::dir_ = nullptr;

}  // namespace

TEST_F(HardeningDecode, RefusedTemporalUnitIsSkippedWithAWarningNamingIt) {
    std::vector<uint8_t> s = clean_;
    const int tu = damageable_unit();
    damage(s, tu);
    write_file(dir() / "damaged.ivf", s);
    const CommandResult r = run_tool("decode " + q(dir() / "damaged.ivf") + " -o " + q(dir() / "out.y4m"));
    ASSERT_TRUE(r.clean_success()) << r.output;
    const std::string unit = "packet " + std::to_string(tu) + " (pts ";
    EXPECT_NE(r.output.find("filmgrain: warning: " + unit), std::string::npos) << r.output;
    // dav1d drops such a unit without an error (as the dav1d tool does): the parser's report
    // on the packet is what names it
    EXPECT_NE(r.output.find("the demuxer flags it damaged (") , std::string::npos) << r.output;
    EXPECT_NE(r.output.find("obu_forbidden_bit out of range"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 damaged unit(s) in '" + (dir() / "damaged.ivf").string() + "' skipped or concealed"),
              std::string::npos)
        << r.output;
    // the pictures before the damaged unit are the clean stream's, grain included; the
    // refused unit's picture is missing and decoding went on after it
    const auto pictures = y4m_frames(dir() / "out.y4m");
    ASSERT_EQ(pictures.size(), std::size_t(kFrames - 1)) << r.output;
    for (int i = 0; i < tu; i++) EXPECT_EQ(pictures[std::size_t(i)], clean_pictures_[std::size_t(i)]) << "frame " << i;
    EXPECT_NE(r.output.find(std::to_string(kFrames - 1) + " frame(s) written"), std::string::npos) << r.output;
}

TEST_F(HardeningDecode, StrictExitsNonZeroNamingTheCountAfterTheSameOutput) {
    std::vector<uint8_t> s = clean_;
    const int tu = damageable_unit();
    damage(s, tu);
    damage(s, tu + 1 < kFrames ? tu + 1 : tu - 1);
    write_file(dir() / "damaged.ivf", s);
    const CommandResult lenient = run_tool("decode -q " + q(dir() / "damaged.ivf") + " -o " + q(dir() / "lenient.y4m"));
    ASSERT_TRUE(lenient.clean_success()) << lenient.output;
    const CommandResult r = run_tool("decode -q --strict " + q(dir() / "damaged.ivf") + " -o " + q(dir() / "strict.y4m"));
    EXPECT_TRUE(r.clean_error()) << r.output;
    EXPECT_TRUE(r.exited_with(3)) << r.output;
    EXPECT_NE(r.output.find("filmgrain: error: --strict: 2 damaged unit(s); the output is complete"), std::string::npos)
        << r.output;
    // -q keeps the per-unit warnings: they are data lost
    EXPECT_NE(r.output.find("warning: packet " + std::to_string(tu) + " ("), std::string::npos) << r.output;
    ASSERT_TRUE(fs::exists(dir() / "strict.y4m")) << "--strict still writes the complete output";
    EXPECT_EQ(read_file(dir() / "strict.y4m"), read_file(dir() / "lenient.y4m"));
    EXPECT_FALSE(y4m_frames(dir() / "strict.y4m").empty());
    // an undamaged stream passes --strict
    const CommandResult ok = run_tool("decode -q --strict " + q(dir() / "clean.ivf") + " -o " + q(dir() / "ok.y4m"));
    EXPECT_TRUE(ok.clean_success()) << ok.output;
    EXPECT_EQ(ok.output, "");
}

TEST_F(HardeningDecode, NothingDecodableIsAnErrorWithoutOutputFile) {
    // every temporal unit's bytes overwritten with 0xFF (each OBU header then has its
    // forbidden bit set): no decoder gets a picture out of it; the IVF framing is intact
    std::vector<uint8_t> s = clean_;
    const int damaged = kFrames;
    for (const IvfFrame& f : frames_) std::fill_n(s.begin() + long(f.payload), f.size, uint8_t(0xFF));
    write_file(dir() / "ruined.ivf", s);
    const fs::path out = dir() / "ruined-out" / "out.y4m";
    fs::create_directories(out.parent_path());
    const CommandResult r = run_tool("decode " + q(dir() / "ruined.ivf") + " -o " + q(out));
    EXPECT_TRUE(r.clean_error()) << r.output;
    EXPECT_TRUE(r.exited_with(1)) << r.output;
    EXPECT_NE(r.output.find("filmgrain: error: '" + (dir() / "ruined.ivf").string() + "' decoded to no frame (" +
                            std::to_string(damaged) + " damaged unit(s) skipped)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("warning: packet 0 ("), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(fs::is_empty(out.parent_path())) << "a temporary was left behind";
}

TEST_F(HardeningDecode, TruncatedLastUnitIsReportedAndTheRestWritten) {
    // the file ends inside the last temporal unit, as a copy cut short does
    const IvfFrame& last = frames_.back();
    std::vector<uint8_t> s(clean_.begin(), clean_.begin() + long(last.payload + last.size / 2));
    write_file(dir() / "cut.ivf", s);
    const CommandResult r = run_tool("decode -q " + q(dir() / "cut.ivf") + " -o " + q(dir() / "cut.y4m"));
    ASSERT_TRUE(r.clean_success()) << r.output;
    EXPECT_NE(r.output.find("warning: packet " + std::to_string(kFrames - 1) + " ("), std::string::npos) << r.output;
    const auto pictures = y4m_frames(dir() / "cut.y4m");
    ASSERT_GE(pictures.size(), std::size_t(kFrames - 1));
    for (int i = 0; i < kFrames - 1; i++) EXPECT_EQ(pictures[std::size_t(i)], clean_pictures_[std::size_t(i)]) << "frame " << i;
}

TEST_F(HardeningDecode, ThreadsOutsideTheLimitAreRefused) {
    for (const char* n : {"257", "-1", "100000"}) {
        const CommandResult r = run_tool("decode --threads " + std::string(n) + " " + q(dir() / "clean.ivf") + " -o " +
                                         q(dir() / "t.y4m"));
        EXPECT_TRUE(r.clean_error()) << n << ": " << r.output;
        EXPECT_NE(r.output.find("--threads"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("256"), std::string::npos) << "the limit is named: " << r.output;
        EXPECT_FALSE(fs::exists(dir() / "t.y4m"));
    }
    const CommandResult r =
        run_tool("decode -q --threads 256 " + q(dir() / "clean.ivf") + " -o " + q(dir() / "t256.y4m"));
    EXPECT_TRUE(r.clean_success()) << r.output;
    EXPECT_EQ(y4m_frames(dir() / "t256.y4m"), clean_pictures_);
}

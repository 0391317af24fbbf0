// AV1 film grain conformance: every conformance/av1_* case, with parameters
// taken (a) from case.json params.av1 and (b) from grain.tbl by timestamp
// k * 400000 (10 MHz ticks at 25 fps), each frame's output MD5 compared with
// the golden. When expected.yuv.xz is present, a mismatch reports the first
// differing sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "av1/av1_synthesis.hpp"
#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "io/xz_file.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"

namespace fs = std::filesystem;
using namespace filmgrain;

namespace {

std::vector<std::string> av1_cases() {
    std::vector<std::string> out;
    const fs::path root = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance";
    if (!fs::exists(root)) return out;
    for (const auto& e : fs::directory_iterator(root))
        if (e.is_directory() && e.path().filename().string().rfind("av1_", 0) == 0)
            out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

enum class ParamSource { kCaseJson, kGrainTable };

std::string first_difference(const FrameBuffer& got, const uint8_t* expected, int frame) {
    const PixelFormat fmt = got.format();
    const int bps = fmt.bit_depth > 8 ? 2 : 1;
    for (int p = 0; p < num_planes(fmt.chroma); ++p) {
        const int pw = plane_width(fmt.chroma, p, got.width()), ph = plane_height(fmt.chroma, p, got.height());
        const uint8_t* a = got.bytes() + got.plane_offset(p);
        const uint8_t* b = expected + got.plane_offset(p);
        for (int y = 0; y < ph; ++y)
            for (int x = 0; x < pw; ++x) {
                const std::size_t o = (static_cast<std::size_t>(y) * pw + x) * bps;
                const int va = bps == 2 ? a[o] | (a[o + 1] << 8) : a[o];
                const int vb = bps == 2 ? b[o] | (b[o + 1] << 8) : b[o];
                if (va != vb) {
                    std::ostringstream s;
                    s << "first difference: frame " << frame << " plane " << p << " x " << x << " y " << y
                      << ": got " << va << ", expected " << vb;
                    return s.str();
                }
            }
    }
    return "no sample difference (md5 mismatch elsewhere?)";
}

void run_case(const std::string& name, ParamSource source) {
    const fs::path dir = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance" / name;
    std::ifstream jf(dir / "case.json");
    ASSERT_TRUE(jf) << "cannot open case.json";
    const nlohmann::json cj = nlohmann::json::parse(jf);
    const int width = cj.at("width"), height = cj.at("height");
    const PixelFormat fmt = parse_pix_fmt(cj.at("pix_fmt").get<std::string>());
    const int frames = cj.at("frames");
    const auto& info = cj.at("frames_info");
    ASSERT_EQ(static_cast<int>(info.size()), frames);

    const std::vector<uint8_t> input = read_xz_file((dir / "input.yuv.xz").string());
    const std::size_t fbytes = FrameBuffer::frame_bytes(width, height, fmt);
    ASSERT_EQ(input.size(), fbytes * static_cast<std::size_t>(frames));
    std::vector<uint8_t> expected;
    if (fs::exists(dir / "expected.yuv.xz")) {
        expected = read_xz_file((dir / "expected.yuv.xz").string());
        ASSERT_EQ(expected.size(), input.size());
    }

    const std::vector<Av1FrameParams> json_params = av1_frame_params_from_json(cj);
    AomGrainTable table;
    if (source == ParamSource::kGrainTable) table = read_aom_grain_table((dir / "grain.tbl").string());

    int mismatches = 0;
    for (int k = 0; k < frames; ++k) {
        const auto& fi = info[static_cast<std::size_t>(k)];
        const int mc = fi.at("params").value("matrix_coefficients", 2);
        Av1FilmGrainParams p;
        if (source == ParamSource::kCaseJson) {
            p = json_params[static_cast<std::size_t>(k)].grain;
        } else {
            const int64_t ts = static_cast<int64_t>(k) * 400000;
            const auto idx = table.find_index(ts);
            ASSERT_TRUE(idx.has_value()) << "no grain.tbl entry for timestamp " << ts;
            p = table.resolved_params(*idx);
            // filmgrn1 cannot carry clip_to_restricted_range (README caveat 6):
            // that one field is a stream fact taken from case.json.
            p.clip_to_restricted_range = json_params[static_cast<std::size_t>(k)].grain.clip_to_restricted_range;
            // Apart from that, the table must describe the same signalled parameters.
            EXPECT_EQ(av1_params_to_json(p), av1_params_to_json(json_params[static_cast<std::size_t>(k)].grain))
                << "frame " << k << ": grain.tbl and case.json disagree";
        }

        FrameBuffer src(width, height, fmt), dst(width, height, fmt);
        std::memcpy(src.bytes(), input.data() + fbytes * static_cast<std::size_t>(k), fbytes);
        av1::apply_film_grain(p, src.view(), dst.view(), mc);
        const std::string got = md5_hex(dst.bytes(), dst.byte_size());

        // The source must be untouched, and in-place must give the same result.
        ASSERT_EQ(0, std::memcmp(src.bytes(), input.data() + fbytes * static_cast<std::size_t>(k), fbytes));
        FrameBuffer inplace = src;
        av1::apply_film_grain(p, inplace.view(), inplace.view(), mc);
        EXPECT_EQ(md5_hex(inplace.bytes(), inplace.byte_size()), got) << "frame " << k << ": in-place differs";

        const std::string want = fi.at("expected_md5");
        if (got != want) {
            ++mismatches;
            std::string detail;
            if (!expected.empty())
                detail = first_difference(dst, expected.data() + fbytes * static_cast<std::size_t>(k), k);
            ADD_FAILURE() << name << " frame " << k << ": md5 " << got << " != expected " << want << ". " << detail;
        }
    }
    EXPECT_EQ(mismatches, 0);
}

class Av1Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Av1Conformance, ParamsFromCaseJson) { run_case(GetParam(), ParamSource::kCaseJson); }
TEST_P(Av1Conformance, ParamsFromGrainTable) { run_case(GetParam(), ParamSource::kGrainTable); }

INSTANTIATE_TEST_SUITE_P(Cases, Av1Conformance, ::testing::ValuesIn(av1_cases()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(Av1ConformanceSet, AllCasesPresent) { EXPECT_EQ(av1_cases().size(), 28u); }

}  // namespace

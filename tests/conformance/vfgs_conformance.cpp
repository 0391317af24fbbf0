// Conformance of the VFGS flavour (TR 23002-9 clause 7.5) against the
// InterDigital VersatileFilmGrain goldens in conformance/vfgs-*: one test per
// case, every frame's md5 must match. AFGS1 input (vfgs-afgs1-*) is not an FGC
// SEI flavour and is not run here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/frame_buffer.hpp"
#include "core/md5.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/vfgs.hpp"
#include "io/xz_file.hpp"
#include "metadata/fgc_json.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kConformanceDir = fs::path(FILMGRAIN_SOURCE_DIR) / "conformance";

std::vector<std::string> vfgs_cases() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(kConformanceDir, ec)) {
        const std::string n = e.path().filename().string();
        if (e.is_directory() && n.rfind("vfgs-", 0) == 0 && n.rfind("vfgs-afgs1-", 0) != 0 &&
            fs::exists(e.path() / "case.json"))
            names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
}

// Where the output first differs from expected.yuv.xz.
std::string first_difference(const fs::path& dir, int frame, const filmgrain::FrameBuffer& out) {
    const fs::path exp_path = dir / "expected.yuv.xz";
    if (!fs::exists(exp_path)) return "(no expected.yuv.xz to locate the difference)";
    const std::vector<uint8_t> exp = filmgrain::read_xz_file(exp_path.string());
    const size_t fb = out.byte_size();
    if (exp.size() < fb * static_cast<size_t>(frame + 1)) return "(expected.yuv.xz is too short)";
    const uint8_t* e = exp.data() + fb * static_cast<size_t>(frame);
    const auto fmt = out.format();
    const int bps = fmt.bit_depth > 8 ? 2 : 1;
    for (int p = 0; p < filmgrain::num_planes(fmt.chroma); ++p) {
        const int w = filmgrain::plane_width(fmt.chroma, p, out.width());
        const int h = filmgrain::plane_height(fmt.chroma, p, out.height());
        const uint8_t* a = out.bytes() + out.plane_offset(p);
        const uint8_t* b = e + out.plane_offset(p);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t o = (static_cast<size_t>(y) * w + x) * bps;
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
    return "(no sample differs from expected.yuv.xz)";
}

class VfgsConformance : public ::testing::TestWithParam<std::string> {};

TEST_P(VfgsConformance, BitExact) {
    const fs::path dir = kConformanceDir / GetParam();
    std::ifstream f(dir / "case.json");
    ASSERT_TRUE(f) << "cannot open " << (dir / "case.json");
    const json cj = json::parse(f);
    const int W = cj.at("width"), H = cj.at("height");
    const auto in_fmt = filmgrain::parse_pix_fmt(cj.at("pix_fmt").get<std::string>());
    const auto out_fmt = filmgrain::parse_pix_fmt(cj.value("output_pix_fmt", cj.at("pix_fmt").get<std::string>()));

    filmgrain::vfgs::Options opt;
    if (!cj.at("seed").is_null()) opt.seed = cj.at("seed").get<uint32_t>();
    opt.gain_percent = cj.value("vfgs_gain_percent", 100);
    if (out_fmt.bit_depth != in_fmt.bit_depth) opt.output_bit_depth = out_fmt.bit_depth;
    filmgrain::vfgs::Synthesizer synth(opt);
    if (cj.contains("vfgs_lfsr_init")) {
        const uint32_t want = static_cast<uint32_t>(std::stoul(cj.at("vfgs_lfsr_init").get<std::string>(), nullptr, 16));
        EXPECT_EQ(synth.lfsr_state(), want) << "initial LFSR state";
    }

    const std::vector<uint8_t> input = filmgrain::read_xz_file((dir / "input.yuv.xz").string());
    const size_t in_bytes = filmgrain::FrameBuffer::frame_bytes(W, H, in_fmt);
    const auto& frames = cj.at("frames_info");
    ASSERT_GE(input.size(), in_bytes * frames.size());

    json last_params;
    int mismatches = 0;
    std::string first_report;
    for (size_t k = 0; k < frames.size(); ++k) {
        const json& fi = frames[k];
        const json& pj = fi.at("params").at("fgc");
        // Same parameters as the previous frame: keep going (the LFSR continues
        // either way; a new set only rebuilds templates and LUTs).
        if (k == 0 || pj != last_params) {
            synth.set_params(filmgrain::fgc_params_from_json(pj));
            last_params = pj;
        }
        filmgrain::FrameBuffer src(W, H, in_fmt);
        std::memcpy(src.bytes(), input.data() + in_bytes * k, in_bytes);
        filmgrain::FrameBuffer dst(W, H, out_fmt);
        if (out_fmt.bit_depth == in_fmt.bit_depth) {
            synth.apply(src.view(), src.view());  // in place, as the reference does
            dst = src;
        } else {
            synth.apply(src.view(), dst.view());
        }
        const std::string md5 = filmgrain::md5_hex(dst.bytes(), dst.byte_size());
        const std::string want = fi.at("expected_md5");
        if (md5 != want) {
            ++mismatches;
            if (first_report.empty())
                first_report = "frame " + std::to_string(k) + ": md5 " + md5 + " != expected " + want + "; " +
                               first_difference(dir, static_cast<int>(k), dst);
        }
    }
    EXPECT_EQ(mismatches, 0) << mismatches << " of " << frames.size() << " frames differ; " << first_report;
}

INSTANTIATE_TEST_SUITE_P(Cases, VfgsConformance, ::testing::ValuesIn(vfgs_cases()),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                             std::string n = i.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

}  // namespace

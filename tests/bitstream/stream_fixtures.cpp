#include "stream_fixtures.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <iterator>

#include "conformance_case.hpp"
#include "core/frame_buffer.hpp"
#include "io/video_file.hpp"

namespace filmgrain::test_support {

std::string tool() { return std::string("'") + FILMGRAIN_TOOL_PATH + "'"; }
std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

namespace fs = std::filesystem;

fs::path fresh_test_dir(const std::string& name) {
    const fs::path d = fs::temp_directory_path() / ("filmgrain-bitstream-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::vector<uint8_t> read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& p, const std::vector<uint8_t>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void write_synthetic_y4m(const fs::path& p, int width, int height, int frames, int bit_depth) {
    VideoInfo info;
    info.width = width;
    info.height = height;
    info.format = PixelFormat{ChromaFormat::k420, bit_depth};
    info.y4m = true;
    VideoWriter w(p.string(), info, true);
    FrameBuffer f(width, height, info.format);
    const int shift = bit_depth - 8;
    for (int k = 0; k < frames; k++) {
        FrameView v = f.view();
        for (int c = 0; c < 3; c++) {
            const PlaneView& pl = v.planes[c];
            for (int y = 0; y < pl.height; y++)
                for (int x = 0; x < pl.width; x++) {
                    // a moving diagonal gradient with a bright square drifting right
                    int val = c == 0 ? 40 + ((x + y + 3 * k) * 2) % 160 : 128 + (c == 1 ? 1 : -1) * ((x + 2 * k) % 40 - 20);
                    if (c == 0 && x >= 8 + 4 * k && x < 40 + 4 * k && y >= 16 && y < 48) val = 220;
                    val <<= shift;
                    if (bit_depth == 8)
                        pl.row<uint8_t>(y)[x] = uint8_t(val);
                    else
                        pl.row<uint16_t>(y)[x] = uint16_t(val);
                }
        }
        w.write(f);
    }
    w.commit();
}

bool run_or_fail(const std::string& cmd) {
    std::string log;
    const int rc = run_command(cmd + " 2>&1", &log);
    if (rc != 0) ADD_FAILURE() << "command failed (" << rc << "): " << cmd << "\n" << log;
    return rc == 0;
}

FgcParams fgc_params_for(int k) {
    FgcParams p;
    p.log2_scale_factor = 5;
    p.film_grain_characteristics_persistence_flag = true;
    FgcComponentModel& y = p.comp[0];
    y.comp_model_present_flag = true;
    y.num_model_values_minus1 = 2;
    FgcIntensityInterval lo, hi;
    lo.intensity_interval_lower_bound = 0;
    lo.intensity_interval_upper_bound = 127;
    lo.comp_model_value = {60 + 10 * (k % 7), 8, 8 + 2 * (k % 3), 0, 0, 0};
    hi.intensity_interval_lower_bound = 128;
    hi.intensity_interval_upper_bound = 255;
    hi.comp_model_value = {40 + 5 * (k % 5), 10, 10, 0, 0, 0};
    y.intervals = {lo, hi};
    FgcComponentModel& cb = p.comp[1];
    cb.comp_model_present_flag = true;
    cb.num_model_values_minus1 = 0;
    FgcIntensityInterval all;
    all.intensity_interval_upper_bound = 255;
    all.comp_model_value = {30 + k % 4, 0, 0, 0, 0, 0};
    cb.intervals = {all};
    return p;
}

}  // namespace filmgrain::test_support

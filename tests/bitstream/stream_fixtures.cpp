#include "stream_fixtures.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <iterator>

#include "conformance_case.hpp"
#include "bitstream/metadata_insertion.hpp"
#include "core/frame_buffer.hpp"
#include "io/video_file.hpp"
#include "metadata/fgc_sei.hpp"

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

Av1FilmGrainParams av1_params_for(int k) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = 1000 + 37 * k;
    p.num_y_points = 2;
    p.point_y_value[0] = 0;
    p.point_y_scaling[0] = 40 + 8 * k;
    p.point_y_value[1] = 255;
    p.point_y_scaling[1] = 90 - 5 * k;
    p.num_cb_points = 1;
    p.point_cb_value[0] = 128;
    p.point_cb_scaling[0] = 30 + k;
    p.num_cr_points = 2;
    p.point_cr_value[0] = 20;
    p.point_cr_scaling[0] = 25;
    p.point_cr_value[1] = 230;
    p.point_cr_scaling[1] = 45 + 2 * k;
    p.grain_scaling_minus_8 = k % 4;
    p.ar_coeff_lag = 1 + k % 3;
    for (int i = 0; i < p.num_pos_luma(); i++) p.ar_coeffs_y_plus_128[std::size_t(i)] = 128 + (i * 5 + k) % 17 - 8;
    for (int i = 0; i < p.num_pos_chroma(); i++) {
        p.ar_coeffs_cb_plus_128[std::size_t(i)] = 128 + (i * 3 + k) % 11 - 5;
        p.ar_coeffs_cr_plus_128[std::size_t(i)] = 128 - (i * 7 + k) % 13 + 6;
    }
    p.ar_coeff_shift_minus_6 = k % 2;
    p.cb_mult = 128 + k;
    p.cr_offset = 250 + k;
    p.overlap_flag = k % 2;
    return p;
}

std::vector<uint8_t> encode_synthetic_clip(const fs::path& dir, bitstream::StreamCodec codec, int width, int height,
                                           int frames, int bit_depth) {
    write_synthetic_y4m(dir / "src.y4m", width, height, frames, bit_depth);
    const fs::path out = dir / "raw.bit";
    if (codec == bitstream::StreamCodec::kH264) {
        if (!run_or_fail("x264 --quiet --preset ultrafast --bframes 2 --keyint 6 --min-keyint 6 --no-scenecut -o " +
                         q(out) + " " + q(dir / "src.y4m") + " 2>/dev/null"))
            return {};
    } else {
        const std::string depth = bit_depth > 8 ? " --output-depth 10 --profile main10" : "";
        if (!run_or_fail("x265 --log-level error --preset ultrafast --bframes 3 --keyint 8 --min-keyint 8 "
                         "--no-scenecut --no-open-gop" + depth + " --input " + q(dir / "src.y4m") + " -o " + q(out)))
            return {};
    }
    return read_bytes(out);
}

std::vector<uint8_t> with_fgc_sei_per_access_unit(const std::vector<uint8_t>& stream, bitstream::StreamCodec codec,
                                                  const std::function<std::vector<uint8_t>(int)>& payload_for) {
    return bitstream::insert_sei(stream, codec, [&](int au) {
        bitstream::AccessUnitSei s;
        s.prefix = {bitstream::SeiMessage{bitstream::kSeiPayloadFgc,
                                          payload_for ? payload_for(au)
                                                      : write_fgc_sei_payload(fgc_params_for(au),
                                                                              bitstream::fgc_codec(codec))}};
        return s;
    });
}

}  // namespace filmgrain::test_support

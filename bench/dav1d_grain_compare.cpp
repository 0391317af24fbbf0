// In-process A/B of AV1 grain synthesis against dav1d's own: one libdav1d decoder (grain
// not applied) decodes an IVF stream, and every decoded picture gets its grain twice, from
// dav1d_apply_grain (dav1d's optimized kernels, into a picture from dav1d's pool) and from
// filmgrain's Session (into a reused frame), one thread each. The two are timed on
// the same picture in the same state of the decode loop, first one then the other in
// alternating order, so that the whole-process noise of tools/bench-compare (two decodes
// per difference) is gone. Both outputs are compared: a picture where they differ is an
// error.
//
//   [FILMGRAIN_SIMD_TARGET=AVX3|AVX2|SSE4|...] [DAV1D_CPU_MASK=N] filmgrain_dav1d_compare STREAM.ivf [--json FILE]
//
// DAV1D_CPU_MASK limits dav1d's CPU flags as its CLI's --cpumask does (x86: 1 SSE2, 2 SSSE3,
// 4 SSE4.1, 8 AVX2, 16 AVX-512 ICL; 15 = up to AVX2), so that both sides can be measured on
// the target an AVX2-only CPU would run: FILMGRAIN_SIMD_TARGET=AVX2 DAV1D_CPU_MASK=15.
//
// Which libdav1d it runs is the one CMake found (FILMGRAIN_DAV1D_ROOT, else the system's); the
// report names its dav1d_version() and filmgrain's dispatch target, since either changes the
// ratio.
#include <dav1d/dav1d.h>
#include <time.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "filmgrain/session.hpp"
#include "core/frame_buffer.hpp"
#include "core/simd_targets.hpp"
#include "filmgrain/av1_params.hpp"

// Exported by libdav1d (its CLI's --cpumask) but not declared in its installed headers.
extern "C" void dav1d_set_cpu_flags_mask(unsigned mask);

namespace {

using namespace filmgrain;

double thread_cpu_ms() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

// dav1d keeps the syntax elements unbiased as FFmpeg does (uv_mult - 128, uv_offset - 256,
// scaling_shift = grain_scaling_minus_8 + 8, ar_coeff_shift = ar_coeff_shift_minus_6 + 6).
Av1FilmGrainParams params_from_dav1d(const Dav1dFilmGrainData& d) {
    Av1FilmGrainParams p;
    p.apply_grain = 1;
    p.grain_seed = int(d.seed & 0xFFFF);
    p.num_y_points = d.num_y_points;
    for (int i = 0; i < d.num_y_points; ++i) p.point_y_value[i] = d.y_points[i][0], p.point_y_scaling[i] = d.y_points[i][1];
    p.chroma_scaling_from_luma = d.chroma_scaling_from_luma;
    p.num_cb_points = d.num_uv_points[0];
    p.num_cr_points = d.num_uv_points[1];
    for (int i = 0; i < d.num_uv_points[0]; ++i)
        p.point_cb_value[i] = d.uv_points[0][i][0], p.point_cb_scaling[i] = d.uv_points[0][i][1];
    for (int i = 0; i < d.num_uv_points[1]; ++i)
        p.point_cr_value[i] = d.uv_points[1][i][0], p.point_cr_scaling[i] = d.uv_points[1][i][1];
    p.grain_scaling_minus_8 = d.scaling_shift - 8;
    p.ar_coeff_lag = d.ar_coeff_lag;
    for (int i = 0; i < 24; ++i) p.ar_coeffs_y_plus_128[i] = d.ar_coeffs_y[i] + 128;
    for (int i = 0; i < 25; ++i) {
        p.ar_coeffs_cb_plus_128[i] = d.ar_coeffs_uv[0][i] + 128;
        p.ar_coeffs_cr_plus_128[i] = d.ar_coeffs_uv[1][i] + 128;
    }
    p.ar_coeff_shift_minus_6 = int(d.ar_coeff_shift) - 6;
    p.grain_scale_shift = d.grain_scale_shift;
    p.cb_mult = d.uv_mult[0] + 128, p.cb_luma_mult = d.uv_luma_mult[0] + 128, p.cb_offset = d.uv_offset[0] + 256;
    p.cr_mult = d.uv_mult[1] + 128, p.cr_luma_mult = d.uv_luma_mult[1] + 128, p.cr_offset = d.uv_offset[1] + 256;
    p.overlap_flag = d.overlap_flag;
    p.clip_to_restricted_range = d.clip_to_restricted_range;
    return p;
}

FrameView view_of(const Dav1dPicture& pic) {
    FrameView v;
    v.format = pic.p.layout == DAV1D_PIXEL_LAYOUT_I420   ? ChromaFormat::k420
               : pic.p.layout == DAV1D_PIXEL_LAYOUT_I422 ? ChromaFormat::k422
               : pic.p.layout == DAV1D_PIXEL_LAYOUT_I444 ? ChromaFormat::k444
                                                         : ChromaFormat::k400;
    v.bit_depth = pic.p.bpc;
    v.width = pic.p.w;
    v.height = pic.p.h;
    for (int pl = 0; pl < v.plane_count(); ++pl) {
        v.planes[pl].data = static_cast<uint8_t*>(pic.data[pl]);
        v.planes[pl].stride = pic.stride[pl ? 1 : 0];
        v.planes[pl].width = plane_width(v.format, pl, v.width);
        v.planes[pl].height = plane_height(v.format, pl, v.height);
    }
    return v;
}

bool same_pixels(const FrameView& a, const FrameView& b) {
    for (int pl = 0; pl < a.plane_count(); ++pl) {
        const std::size_t bytes = std::size_t(a.planes[pl].width) * std::size_t(a.bytes_per_sample());
        for (int y = 0; y < a.planes[pl].height; ++y)
            if (std::memcmp(a.planes[pl].row<uint8_t>(y), b.planes[pl].row<uint8_t>(y), bytes) != 0) return false;
    }
    return true;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

uint32_t le32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

void check(int rc, const char* what) {
    if (rc < 0 && rc != DAV1D_ERR(EAGAIN)) throw std::runtime_error(std::string(what) + " failed (" + std::to_string(rc) + ")");
}

struct Timings {
    std::vector<double> dav1d, ours;
    int differing = 0;
    int width = 0, height = 0, bit_depth = 0;
};

void run(const std::string& path, Timings& t) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path + "'");
    const std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (file.size() < 32 || std::memcmp(file.data(), "DKIF", 4) != 0)
        throw std::runtime_error("'" + path + "' is not an IVF file");
    Dav1dSettings s;
    dav1d_default_settings(&s);
    s.n_threads = 1;
    s.max_frame_delay = 1;
    s.apply_grain = 0;
    Dav1dContext* ctx = nullptr;
    check(dav1d_open(&ctx, &s), "dav1d_open");
    SessionOptions options;
    options.threads = 1;
    Session synth(options);
    FrameBuffer ours;
    std::size_t pos = le32(file.data() + 6) & 0xFFFF;  // header size
    auto take_pictures = [&] {
        for (;;) {
            Dav1dPicture pic{};
            const int rc = dav1d_get_picture(ctx, &pic);
            if (rc == DAV1D_ERR(EAGAIN)) return;
            check(rc, "dav1d_get_picture");
            if (pic.frame_hdr->film_grain.present) {
                const FrameView src = view_of(pic);
                if (ours.width() != src.width || ours.height() != src.height)
                    ours = FrameBuffer(src.width, src.height, PixelFormat{src.format, src.bit_depth});
                const Av1FilmGrainParams params = params_from_dav1d(pic.frame_hdr->film_grain.data);
                const int mc = int(pic.seq_hdr->mtrx);
                Dav1dPicture theirs{};
                double d_ms = 0, o_ms = 0;
                auto time_dav1d = [&] {
                    const double t0 = thread_cpu_ms();
                    check(dav1d_apply_grain(ctx, &theirs, &pic), "dav1d_apply_grain");
                    d_ms = thread_cpu_ms() - t0;
                };
                auto time_ours = [&] {
                    const double t0 = thread_cpu_ms();
                    synth.receive_av1_params(params, 0, mc);
                    synth.apply(src, ours.view());
                    o_ms = thread_cpu_ms() - t0;
                };
                if (t.ours.size() % 2) time_dav1d(), time_ours();
                else time_ours(), time_dav1d();
                t.dav1d.push_back(d_ms);
                t.ours.push_back(o_ms);
                t.differing += !same_pixels(view_of(theirs), ours.view());
                t.width = src.width, t.height = src.height, t.bit_depth = src.bit_depth;
                dav1d_picture_unref(&theirs);
            }
            dav1d_picture_unref(&pic);
        }
    };
    while (pos + 12 <= file.size()) {
        const std::size_t size = le32(file.data() + pos);
        pos += 12;
        if (pos + size > file.size()) throw std::runtime_error("truncated IVF frame at byte " + std::to_string(pos));
        Dav1dData data{};
        uint8_t* buf = dav1d_data_create(&data, size);
        if (!buf) throw std::runtime_error("dav1d_data_create failed");
        std::memcpy(buf, file.data() + pos, size);
        pos += size;
        while (data.sz > 0) {
            const int rc = dav1d_send_data(ctx, &data);
            check(rc, "dav1d_send_data");
            take_pictures();
        }
    }
    // Drain: with one thread and max_frame_delay 1 pictures come out as they are sent, but
    // a reordering stream could hold some back.
    for (int k = 0; k < 64; ++k) take_pictures();
    dav1d_close(&ctx);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc == 3 || (argc == 4 && std::string(argv[2]) != "--json") || argc > 4) {
        std::fprintf(stderr, "usage: %s STREAM.ivf [--json FILE]\n", argv[0]);
        return 2;
    }
    try {
        // The same switch as the tool's (tools/command_line.cpp), so that both can be measured
        // on one target.
        if (const char* target = std::getenv("FILMGRAIN_SIMD_TARGET"); target && *target)
            if (!simd::force_target(std::string(target)))
                throw std::runtime_error("FILMGRAIN_SIMD_TARGET=" + std::string(target) + " is not available");
        if (const char* mask = std::getenv("DAV1D_CPU_MASK"); mask && *mask) {
            char* end = nullptr;
            const unsigned long m = std::strtoul(mask, &end, 0);
            if (*end || m > 0xFFFFu)
                throw std::runtime_error("DAV1D_CPU_MASK=" + std::string(mask) + " is not a flag mask (0..65535)");
            dav1d_set_cpu_flags_mask(unsigned(m));
        }
        const std::string dav1d = dav1d_version(), target = simd::dispatched_target();
        Timings t;
        run(argv[1], t);
        if (t.ours.empty()) throw std::runtime_error("no picture with film grain in '" + std::string(argv[1]) + "'");
        const double d = median(t.dav1d), o = median(t.ours);
        std::printf("%dx%d %d-bit, %zu pictures with grain: dav1d %s dav1d_apply_grain %.3f ms, filmgrain (%s) %.3f "
                    "ms (medians, thread CPU time, 1 thread); ratio filmgrain/dav1d %.3f; outputs differ on %d "
                    "picture(s)\n",
                    t.width, t.height, t.bit_depth, t.ours.size(), dav1d.c_str(), d, target.c_str(), o, o / d,
                    t.differing);
        if (argc == 4) {
            std::ofstream js(argv[3]);
            js << "{\"dav1d_version\": \"" << dav1d << "\", \"filmgrain_target\": \"" << target << "\", "
               << "\"width\": " << t.width << ", \"height\": " << t.height << ", \"bit_depth\": " << t.bit_depth
               << ", \"pictures\": " << t.ours.size() << ", \"differing\": " << t.differing << ", \"dav1d_ms\": [";
            for (std::size_t k = 0; k < t.dav1d.size(); ++k) js << (k ? ", " : "") << t.dav1d[k];
            js << "], \"filmgrain_ms\": [";
            for (std::size_t k = 0; k < t.ours.size(); ++k) js << (k ? ", " : "") << t.ours[k];
            js << "]}\n";
        }
        return t.differing ? 1 : 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "filmgrain_dav1d_compare: %s\n", e.what());
        return 1;
    }
}

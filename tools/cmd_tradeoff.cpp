// `filmgrain tradeoff`: every grain method of the project on the same flat content and the
// same target grain (the Boolean model's closed form at one grey level), throughput against
// the error of the second-order statistics; writes a Markdown table and a PNG plot.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"
#include "core/thread_pool.hpp"
#include "grain_outputs.hpp"
#include "filmgrain/error.hpp"
#include "physical/boolean_covariance.hpp"
#include "physical/boolean_model.hpp"
#include "physical/gaussian_approximation.hpp"
#include "stats/grain_statistics.hpp"
#include "tradeoff_methods.hpp"
#include "tradeoff_offsets.hpp"
#include "tradeoff_plot.hpp"

namespace filmgrain::cli {
namespace {

constexpr int kGrey = 128;
constexpr int kMaxLag = 3;

struct TradeoffOptions {
    std::string output = "docs/TRADEOFF.md", plot = "docs/tradeoff.png", size = "1920x1080";
    int boolean_size = 384, threads = 2, frames = 3;
    std::vector<int> samples{16, 64, 256, 800};
    double radius = 0.1, filter_sigma = 0.8;
    bool skip_benchmark = false;
};

struct Row {
    std::string method, detail;
    double mpixels_per_s = 0, error = 0, variance_ratio = 0, lag1 = 0, lag1_target = 0;
    int threads = 1;
    std::string measured_on;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The 1-minute load average, which says how much of the 2 cores the timings really had.
std::string load_average() {
    std::ifstream f("/proc/loadavg");
    std::string one;
    f >> one;
    return one.empty() ? "unknown" : one;
}

double cpu_seconds() {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

// Grain of an 8-bit luma plane over the flat grey content, in units of full scale.
FloatPlane luma_grain(const FrameBuffer& f) {
    FrameView v = const_cast<FrameBuffer&>(f).view();
    FloatPlane g = float_plane_from(v.planes[0], 8);
    for (float& s : g.v) s -= kGrey / 255.f;
    return g;
}

FloatPlane quantized_grain(const FloatPlane& out) {
    FloatPlane g(out.width, out.height);
    for (std::size_t i = 0; i < g.v.size(); i++)
        g.v[i] = float(std::lround(std::clamp(out.v[i] * 255.f, 0.f, 255.f)) - kGrey) / 255.f;
    return g;
}

void score(Row& row, const FloatPlane& grain, const TargetCovariance& target) {
    const stats::Autocovariance c = stats::autocovariance(grain, kMaxLag);
    row.error = stats::relative_covariance_error(c, target);
    row.variance_ratio = c.at(0, 0) / target(0, 0);
    row.lag1 = c.at(1, 0) / c.at(0, 0);
    row.lag1_target = target(1, 0) / target(0, 0);
}

FrameBuffer flat_frame(int w, int h) {
    FrameBuffer f(w, h, PixelFormat{ChromaFormat::k420, 8});
    std::fill(f.bytes(), f.bytes() + f.byte_size(), uint8_t(kGrey));
    return f;
}

double luma_variance(const FrameSynthesizer& s, const FrameBuffer& src) {
    FrameBuffer dst = src;
    s(src, dst, 0);
    const FloatPlane g = luma_grain(dst);
    return stats::autocovariance(g, 0).at(0, 0);
}

// Picks an FGC scale (and log2_scale_factor) whose grain variance is the target's.
FgcParams calibrate_fgc(int cutoff, FgcFlavour flavour, double target_var, const FrameBuffer& probe) {
    int lsf = 5, scale = 64;
    for (int iter = 0; iter < 6; iter++) {
        const double v = luma_variance(fgc_synthesizer(fgc_params(scale, lsf, cutoff, cutoff), flavour), probe);
        double want = v > 0 ? scale * std::sqrt(target_var / v) : 255;
        while (want > 255 && lsf > 0) want /= 2, lsf--;
        while (want < 64 && lsf < 15) want *= 2, lsf++;
        const int next = int(std::clamp(std::lround(want), 1L, 255L));
        if (next == scale && iter > 0) break;
        scale = next;
    }
    return fgc_params(scale, lsf, cutoff, cutoff);
}

Av1FilmGrainParams calibrate_av1(const TargetCovariance& target, const FrameBuffer& probe) {
    int shift = 3, scaling = 64;
    for (int iter = 0; iter < 6; iter++) {
        const double v = luma_variance(av1_synthesizer(av1_params(target, scaling, shift, 1)), probe);
        double want = v > 0 ? scaling * std::sqrt(target(0, 0) / v) : 255;
        while (want > 255 && shift > 0) want /= 2, shift--;
        const int next = int(std::clamp(std::lround(want), 1L, 255L));
        if (next == scaling && iter > 0) break;
        scaling = next;
    }
    return av1_params(target, scaling, shift, 1);
}

Row run_frames(const std::string& method, const std::string& detail, const FrameSynthesizer& s, const FrameBuffer& src,
               int frames, const TargetCovariance& target) {
    Row row;
    row.method = method;
    row.detail = detail;
    FrameBuffer dst = src;
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < frames; k++) s(src, dst, k);
    row.mpixels_per_s = double(src.width()) * src.height() * frames / seconds_since(t0) * 1e-6;
    row.measured_on = std::to_string(src.width()) + "x" + std::to_string(src.height());
    score(row, luma_grain(dst), target);
    return row;
}

}  // namespace

void register_tradeoff(CLI::App& app) {
    auto o = std::make_shared<TradeoffOptions>();
    CLI::App* sub = app.add_subcommand("tradeoff", "speed against accuracy of every grain method on one target grain; "
                                                   "writes a Markdown table and a PNG plot");
    sub->add_option("--output", o->output, "Markdown report")->capture_default_str();
    sub->add_option("--plot", o->plot, "PNG plot (speed vs error)")->capture_default_str();
    sub->add_option("--size", o->size, "content size for the fast methods")->capture_default_str();
    sub->add_option("--boolean-size", o->boolean_size, "content side for the Boolean model runs")->capture_default_str()->check(CLI::Range(16, 4096));
    sub->add_option("--samples", o->samples, "Boolean-model N values")->capture_default_str();
    sub->add_option("--frames", o->frames, "frames timed per fast method")->capture_default_str()->check(CLI::Range(1, 100));
    sub->add_option("--threads", o->threads, "threads for the methods that use them")->capture_default_str()->check(CLI::Range(1, kMaxThreads));
    sub->add_option("--radius", o->radius, "target grain radius (input pixels)")->capture_default_str();
    sub->add_flag("--skip-benchmark", o->skip_benchmark, "skip the 1024x1024 N=800 Boolean benchmark");
    sub->callback([o]() {
        // Taken before any work of this run, so it shows what else the machine was doing.
        const std::string load_before = load_average();
        RawVideoOptions size_opt;
        size_opt.size = o->size;
        const VideoInfo vi = size_opt.to_info();
        physical::BooleanModelParams tp;
        tp.radius_mean = o->radius;
        tp.filter_sigma = o->filter_sigma;
        tp.threads = o->threads;
        physical::validate(tp);
        const double grey = kGrey / 255.0;
        const physical::BooleanCovariance cov(tp, grey);
        const TargetCovariance target = [&cov](int dx, int dy) { return cov.filtered_output_lag(dx, dy); };
        std::vector<Row> rows;
        auto log = [](const Row& r) {
            std::fprintf(stderr, "tradeoff: %-26s %-38s %9.3f Mpixel/s  error %.4f\n", r.method.c_str(), r.detail.c_str(),
                         r.mpixels_per_s, r.error);
        };

        // The Boolean model at several N.
        const FloatPlane u(o->boolean_size, o->boolean_size, float(grey));
        for (int n : o->samples) {
            physical::BooleanModelParams p = tp;
            p.samples = n;
            FloatPlane out;
            const auto t0 = std::chrono::steady_clock::now();
            const physical::RenderReport rep = physical::render_boolean_model(u, p, {}, 1, out);
            Row row;
            row.mpixels_per_s = double(out.v.size()) / seconds_since(t0) * 1e-6;
            row.method = "Boolean model, N=" + std::to_string(n);
            row.detail = physical::algorithm_name(rep.algorithm);
            row.threads = o->threads;
            row.measured_on = std::to_string(o->boolean_size) + "x" + std::to_string(o->boolean_size);
            score(row, quantized_grain(out), target);
            rows.push_back(row);
            log(row);
        }
        // The Gaussian approximation.
        {
            const auto t0 = std::chrono::steady_clock::now();
            const physical::GaussianApproximation g(tp);
            const double setup = seconds_since(t0);
            const FloatPlane uf(vi.width, vi.height, float(grey));
            FloatPlane out;
            const auto t1 = std::chrono::steady_clock::now();
            for (int k = 0; k < o->frames; k++) g.render(uf, {}, uint64_t(k), out);
            Row row;
            row.mpixels_per_s = double(vi.width) * vi.height * o->frames / seconds_since(t1) * 1e-6;
            row.method = "Gaussian approximation";
            row.detail = "kernel " + std::to_string(2 * g.kernel_radius() + 1) + "x" + std::to_string(2 * g.kernel_radius() + 1) +
                         ", set-up " + fixed_decimals(setup, 2) + " s";
            row.threads = o->threads;
            row.measured_on = std::to_string(vi.width) + "x" + std::to_string(vi.height);
            score(row, quantized_grain(out), target);
            rows.push_back(row);
            log(row);
        }
        // FGC: the isotropic cut-off that fits best, then each flavour with its own scale.
        const FrameBuffer probe = flat_frame(256, 256), content = flat_frame(vi.width, vi.height);
        int best_cut = 2;
        double best_err = 1e300;
        for (int cut = 2; cut <= 14; cut++) {
            Row r;
            FrameBuffer dst = probe;
            fgc_synthesizer(calibrate_fgc(cut, FgcFlavour::kRdd5, target(0, 0), probe), FgcFlavour::kRdd5)(probe, dst, 0);
            score(r, luma_grain(dst), target);
            if (r.error < best_err) best_err = r.error, best_cut = cut;
        }
        for (FgcFlavour f : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kVfgs}) {
            const FgcParams p = calibrate_fgc(best_cut, f, target(0, 0), probe);
            const auto& iv = p.comp[0].intervals[0];
            Row row = run_frames(std::string("FGC SEI, ") + fgc_flavour_name(f),
                                 "cut-off " + std::to_string(best_cut) + ", scale " + std::to_string(iv.comp_model_value[0]) +
                                     ", log2_scale_factor " + std::to_string(p.log2_scale_factor),
                                 fgc_synthesizer(p, f), content, o->frames, target);
            rows.push_back(row);
            log(row);
        }
        // AV1 / AFGS1: lag-3 auto-regression from Yule-Walker on the target.
        {
            const Av1FilmGrainParams p = calibrate_av1(target, probe);
            Row row = run_frames("AV1 / AFGS1", "AR lag 3 (Yule-Walker), scaling " + std::to_string(p.point_y_scaling[0]) +
                                                    ", shift " + std::to_string(p.grain_scaling_minus_8 + 8),
                                 av1_synthesizer(p), content, o->frames, target);
            rows.push_back(row);
            log(row);
        }

        // The acceptance benchmark: 1024x1024 grey 128, r = 0.05, N = 800.
        std::string bench;
        if (!o->skip_benchmark) {
            physical::BooleanModelParams p;
            p.radius_mean = 0.05;
            p.samples = 800;
            p.threads = o->threads;
            const FloatPlane ub(1024, 1024, float(grey));
            FloatPlane out;
            const double c0 = cpu_seconds();
            const auto t0 = std::chrono::steady_clock::now();
            const physical::RenderReport rep = physical::render_boolean_model(ub, p, {}, 1, out);
            const double wall = seconds_since(t0), cpu = cpu_seconds() - c0;
            std::ostringstream s;
            s << "1024x1024, grey 128, r = 0.05, sigma = 0.8, N = 800, " << o->threads << " threads, "
              << physical::algorithm_name(rep.algorithm) << ": **" << fixed_decimals(wall, 1) << " s wall**, "
              << fixed_decimals(cpu, 1) << " s CPU (" << fixed_decimals(cpu, 1) << " core-seconds, against 26 s x 40 cores = 1040 "
              << "core-seconds for the published CPU pixel-wise code: " << fixed_decimals(1040 / cpu, 0) << "x less CPU per output). "
              << "1-minute load average on the 2 cores: " << load_before << " before this tradeoff run started, "
              << load_average() << " when the benchmark ended (this run's own threads included); CPU / threads = "
              << fixed_decimals(cpu / o->threads, 1) << " s, so the wall time above is "
              << (wall < 1.15 * cpu / o->threads ? "that of cores the run had to itself"
                                                  : "longer than the CPU time explains: the cores were shared")
              << ".";
            bench = s.str();
            std::fprintf(stderr, "tradeoff: benchmark %s\n", bench.c_str());
        }

        std::ostringstream md;
        md << "# Speed against accuracy\n\n"
           << "Generated by `filmgrain tradeoff` (do not edit by hand). Every method draws grain on the same flat grey "
           << kGrey << " (8-bit) content for one target grain: the Boolean model with constant radius r = " << o->radius
           << " input pixels and Gaussian filter sigma = " << o->filter_sigma
           << " output pixels, whose closed-form autocovariance (N -> infinity) is the reference. "
           << "FGC and AV1 parameters are fitted to that target (FGC: the isotropic frequency cut-off with the lowest "
           << "error, then the scale matching the variance; AV1: a lag-3 auto-regression solved from the Yule-Walker "
           << "equations of the target covariance, then the scaling matching the variance).\n\n"
           << "- **error**: relative L2 error of the measured autocovariance over lags |dx|, |dy| <= " << kMaxLag
           << " against the closed form, sqrt(sum (C_measured - C)^2 / sum C^2), on the 8-bit output.\n"
           << "- **variance ratio**: measured grain variance / closed-form variance (the closed form's standard deviation "
           << "is " << fixed_decimals(std::sqrt(target(0, 0)) * 255, 2) << " code values).\n"
           << "- **lag-1 correlation**: C(1,0)/C(0,0), measured; the target is " << fixed_decimals(target(1, 0) / target(0, 0), 3)
           << ".\n- **throughput**: output Mpixel/s of the luma plane (FGC and AV1 also process 4:2:0 chroma without grain), "
           << "wall clock on this machine (2 cores; 1-minute load average " << load_before
           << " before this run started, " << load_average() << " when the table was written, this run included) "
           << "with the thread count shown.\n\n"
           << "| method | settings | threads | measured on | throughput (Mpixel/s) | error | variance ratio | lag-1 correlation |\n"
           << "|---|---|---|---|---|---|---|---|\n";
        std::vector<PlotPoint> pts;
        for (const Row& r : rows) {
            md << "| " << r.method << " | " << r.detail << " | " << r.threads << " | " << r.measured_on << " | "
               << fixed_decimals(r.mpixels_per_s, 3) << " | " << fixed_decimals(r.error, 4) << " | " << fixed_decimals(r.variance_ratio, 3)
               << " | " << fixed_decimals(r.lag1, 3) << " |\n";
            pts.push_back({r.method, r.mpixels_per_s, r.error});
        }
        md << "\nThe Boolean model's error at finite N is mostly the Monte Carlo variance u(1-u)/N added at lag 0 (its "
           << "expected covariance is C(d)/N + (1 - 1/N) C_sigma(d) for shared offsets); it falls as 1/N.\n";
        md << "\n" << boolean_offsets_section(tp, grey, o->samples, o->boolean_size);
        if (!bench.empty()) md << "\n## Boolean renderer benchmark\n\n" << bench << "\n";
        std::string why;
        const bool plotted = write_tradeoff_plot(o->plot, pts, &why);
        if (plotted)
            md << "\n![throughput against error](" << std::filesystem::path(o->plot).filename().string() << ")\n";
        else
            std::fprintf(stderr, "tradeoff: no plot: %s\n", why.c_str());
        const std::filesystem::path outp(o->output);
        if (outp.has_parent_path()) std::filesystem::create_directories(outp.parent_path());
        write_file_atomically(o->output, md.str());
        std::fprintf(stderr, "tradeoff: wrote %s%s\n", o->output.c_str(), plotted ? (" and " + o->plot).c_str() : "");
    });
}

}  // namespace filmgrain::cli

// `filmgrain stats`: grain statistics of a clean/grainy pair (stills or videos), whatever
// synthesized the grain.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_common.hpp"
#include "filmgrain/error.hpp"
#include "stats/grain_statistics.hpp"
#include "still_image.hpp"
#include "stats_report.hpp"

namespace filmgrain::cli {

nlohmann::json statistics_json(const FloatPlane& clean, const FloatPlane& grain, const StatsOptions& o) {
    nlohmann::json j;
    j["width"] = grain.width;
    j["height"] = grain.height;
    for (const auto& b : stats::variance_vs_intensity(clean, grain, o.bins))
        if (b.count)
            j["variance_vs_intensity"].push_back({{"lo", b.lo}, {"hi", b.hi}, {"count", b.count}, {"mean", b.mean}, {"variance", b.variance}});
    const stats::Autocovariance ac = stats::autocovariance(grain, o.max_lag);
    nlohmann::json rows = nlohmann::json::array();
    for (int dy = -o.max_lag; dy <= o.max_lag; dy++) {
        nlohmann::json row = nlohmann::json::array();
        for (int dx = -o.max_lag; dx <= o.max_lag; dx++) row.push_back(ac.at(dx, dy));
        rows.push_back(row);
    }
    j["autocovariance"] = {{"max_lag", o.max_lag}, {"rows_dy_from_minus_max", rows}};
    const stats::PowerSpectrum ps = stats::power_spectrum(grain, o.spectrum_block);
    j["power_spectrum"] = {{"block", ps.block}, {"radial", ps.radial}};
    const stats::GrainSize gs = stats::grain_size(ac);
    j["grain_size"] = {{"correlation_length", gs.correlation_length}, {"equivalent_diameter", gs.equivalent_diameter}};
    for (int b : o.blocks) {
        const stats::BoundaryVariance bv = stats::block_boundary_variance(grain, b);
        j["block_boundary_variance"].push_back(
            {{"block", b}, {"column_ratio", bv.column_ratio()}, {"row_ratio", bv.row_ratio()}});
    }
    for (const auto& p : stats::repetition_at_periods(grain, o.periods))
        j["repetition"].push_back({{"dx", p.dx}, {"dy", p.dy}, {"correlation", p.correlation}});
    for (const auto& p : stats::strongest_repetitions(grain, 8, 128, 3))
        j["strongest_repetitions"].push_back({{"dx", p.dx}, {"dy", p.dy}, {"correlation", p.correlation}});
    return j;
}

namespace {

void print_text(const nlohmann::json& j) {
    std::printf("grain statistics, %dx%d\n", j["width"].get<int>(), j["height"].get<int>());
    std::printf("variance vs intensity (grain in units of full scale):\n");
    for (const auto& b : j["variance_vs_intensity"])
        std::printf("  [%.3f, %.3f)  n=%-9lld mean=% .6f  sd=%.6f\n", b["lo"].get<double>(), b["hi"].get<double>(),
                    b["count"].get<long long>(), b["mean"].get<double>(), std::sqrt(b["variance"].get<double>()));
    const int L = j["autocovariance"]["max_lag"];
    std::printf("autocovariance, dx 0..%d along rows dy 0..%d:\n", L, L);
    for (int dy = 0; dy <= L; dy++) {
        std::printf(" ");
        for (int dx = 0; dx <= L; dx++) std::printf(" % .3e", j["autocovariance"]["rows_dy_from_minus_max"][dy + L][dx + L].get<double>());
        std::printf("\n");
    }
    std::printf("power spectrum, radial (cycles per %d pixels):", j["power_spectrum"]["block"].get<int>());
    for (double v : j["power_spectrum"]["radial"]) std::printf(" %.2e", v);
    std::printf("\ngrain size: correlation length %.3f px, equivalent diameter %.3f px\n",
                j["grain_size"]["correlation_length"].get<double>(), j["grain_size"]["equivalent_diameter"].get<double>());
    for (const auto& b : j["block_boundary_variance"])
        std::printf("block %2d boundary/interior variance: columns %.3f, rows %.3f\n", b["block"].get<int>(),
                    b["column_ratio"].get<double>(), b["row_ratio"].get<double>());
    for (const auto& p : j["repetition"])
        std::printf("correlation at shift (%d, %d): %.4f\n", p["dx"].get<int>(), p["dy"].get<int>(), p["correlation"].get<double>());
    for (const auto& p : j["strongest_repetitions"])
        std::printf("strongest repetition (%d, %d): %.4f\n", p["dx"].get<int>(), p["dy"].get<int>(), p["correlation"].get<double>());
    if (j.contains("frame_to_frame_correlation"))
        std::printf("frame-to-frame grain correlation: %.4f over %d frame pairs\n", j["frame_to_frame_correlation"].get<double>(),
                    j["frame_pairs"].get<int>());
}

}  // namespace

nlohmann::json grain_statistics_report(const StatsOptions& options) {
    const StatsOptions* o = &options;
    nlohmann::json j;
    if (is_video_path(o->clean)) {
        VideoReader a(o->clean, o->raw.to_info()), b(o->grainy, o->raw.to_info());
        FrameBuffer fa, fb;
        FloatPlane first_clean, first_grain, prev;
        double corr = 0;
        int pairs = 0, frames = 0;
        while (a.read(fa)) {
            if (!b.read(fb)) throw Error(ErrorCode::kIo, o->grainy + " has fewer frames than " + o->clean);
            const int c = o->channel;
            if (c < 0 || c >= fa.view().plane_count())
                throw Error(ErrorCode::kInvalidArgument, "--channel " + std::to_string(c) + " is not a plane of the input");
            const FloatPlane ca = float_plane_from(fa.view().planes[c], a.info().format.bit_depth);
            const FloatPlane g = stats::grain_of(ca, float_plane_from(fb.view().planes[c], b.info().format.bit_depth));
            if (frames == 0) {
                first_clean = ca;
                first_grain = g;
            } else {
                corr += stats::frame_to_frame_correlation(prev, g);
                pairs++;
            }
            prev = g;
            frames++;
        }
        if (!frames) throw Error(ErrorCode::kIo, o->clean + " has no frames");
        j = statistics_json(first_clean, first_grain, *o);
        if (pairs) {
            j["frame_to_frame_correlation"] = corr / pairs;
            j["frame_pairs"] = pairs;
        }
    } else {
        const StillImage a = read_still_image(o->clean), b = read_still_image(o->grainy);
        if (o->channel < 0 || o->channel >= int(a.channels.size()) || o->channel >= int(b.channels.size()))
            throw Error(ErrorCode::kInvalidArgument, "--channel " + std::to_string(o->channel) + " is not a channel of the inputs");
        j = statistics_json(a.channels[o->channel], stats::grain_of(a.channels[o->channel], b.channels[o->channel]), *o);
    }
    return j;
}

void add_stats_options(CLI::App* sub, StatsOptions& o) {
    sub->add_option("clean", o.clean, "clean input (still or .y4m/.yuv)")->required();
    sub->add_option("grainy", o.grainy, "the same with grain")->required();
    sub->add_flag("--json", o.json, "print JSON");
    sub->add_option("--max-lag", o.max_lag, "autocovariance lags")->capture_default_str()->check(CLI::Range(1, 64));
    sub->add_option("--channel", o.channel, "still: channel; video: plane")->capture_default_str();
    sub->add_option("--bins", o.bins, "intensity bins")->capture_default_str()->check(CLI::Range(1, 4096));
    sub->add_option("--spectrum-block", o.spectrum_block, "Welch block size")->capture_default_str()->check(CLI::Range(4, 256));
    sub->add_option("--blocks", o.blocks, "block sizes for the boundary variance (2..4096)")
        ->capture_default_str()
        ->check(CLI::Range(2, 4096));
    sub->add_option("--periods", o.periods, "template periods to test for repetition (1..65536)")
        ->capture_default_str()
        ->check(CLI::Range(1, 65536));
    o.raw.add_to(sub);
}

void register_stats(CLI::App& app) {
    register_subcommand(app, "stats", "grain statistics of a clean and a grainy picture or video", add_stats_options,
                        [](const StatsOptions& o) {
                            const nlohmann::json j = grain_statistics_report(o);
                            if (o.json)
                                std::printf("%s\n", j.dump(2).c_str());
                            else
                                print_text(j);
                            return 0;
                        });
}

}  // namespace filmgrain::cli

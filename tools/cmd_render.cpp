// `filmgrain render`: physically based grain (the Boolean model) on a still or a video.
#include <chrono>
#include <cstdio>
#include <optional>

#include "cli_common.hpp"
#include "option_parsing.hpp"
#include "filmgrain/error.hpp"
#include "core/thread_pool.hpp"
#include "physical/boolean_model.hpp"
#include "physical/cell_random.hpp"
#include "still_image.hpp"

namespace filmgrain::cli {
namespace {

struct RenderOptions {
    std::string input, output;
    double radius = 0.1, radius_sigma = 0, filter_sigma = 0.8, zoom = 1;
    std::optional<int> samples;
    std::optional<double> tolerance;
    std::string roi, algorithm = "auto", planes = "luma";
    int threads = 2;
    uint64_t seed = 0;
    bool quiet = false;
    RawVideoOptions raw;
};

physical::OutputRegion parse_roi(const std::string& s) {
    physical::OutputRegion r;
    if (s.empty()) return r;
    const Region g = parse_region(s, "--roi");
    r.x = g.x;
    r.y = g.y;
    r.w = g.w;
    r.h = g.h;
    return r;
}

struct Totals {
    double pixels = 0, samples = 0;
    int min_n = 1 << 30, max_n = 0;
    physical::BooleanAlgorithm algorithm = physical::BooleanAlgorithm::kAuto;
    void add(const physical::RenderReport& r, double px) {
        pixels += px;
        samples += r.mean_samples * px;
        if (r.tiles) {
            min_n = std::min(min_n, r.min_samples);
            max_n = std::max(max_n, r.max_samples);
            algorithm = r.algorithm;
        }
    }
};

physical::OutputRegion checked_region(const physical::OutputRegion& roi, int w, int h, double zoom) {
    const int fw = physical::zoomed_size(w, zoom), fh = physical::zoomed_size(h, zoom);
    if (roi.w == 0) return {0, 0, fw, fh};
    if (int64_t(roi.x) + roi.w > fw || int64_t(roi.y) + roi.h > fh)
        throw Error(ErrorCode::kInvalidArgument, "--roi " + std::to_string(roi.x) + "," + std::to_string(roi.y) + "," +
                                                     std::to_string(roi.w) + "," + std::to_string(roi.h) +
                                                     " is not inside the " + std::to_string(fw) + "x" +
                                                     std::to_string(fh) + " output");
    return roi;
}

void render_still(const RenderOptions& o, const physical::BooleanModelParams& p, Totals& t) {
    StillImage img = read_still_image(o.input);
    const physical::OutputRegion r = checked_region(parse_roi(o.roi), img.channels[0].width, img.channels[0].height, p.zoom);
    for (std::size_t c = 0; c < img.channels.size(); c++) {
        FloatPlane out;
        if (int(c) == img.alpha_channel) {  // alpha is not film: resample without grain
            out = FloatPlane(r.w, r.h);
            for (int y = 0; y < r.h; y++)
                for (int x = 0; x < r.w; x++)
                    out.at(x, y) = img.channels[c].at(std::min(img.channels[c].width - 1, int((r.x + x + 0.5) / p.zoom)),
                                                      std::min(img.channels[c].height - 1, int((r.y + y + 0.5) / p.zoom)));
        } else {
            t.add(physical::render_boolean_model(img.channels[c], p, r, physical::hash_coordinates(int64_t(c), 0, p.seed), out),
                  double(r.w) * r.h);
        }
        img.channels[c] = std::move(out);
    }
    write_still_image(o.output, img);
}

void render_video(const RenderOptions& o, const physical::BooleanModelParams& p, Totals& t) {
    VideoReader reader(o.input, o.raw.to_info());
    const VideoInfo& in = reader.info();
    const physical::OutputRegion r = checked_region(parse_roi(o.roi), in.width, in.height, p.zoom);
    const ChromaFormat cf = in.format.chroma;
    if ((r.x & chroma_shift_x(cf) ? 1 : 0) || (r.y & chroma_shift_y(cf) ? 1 : 0))
        throw Error(ErrorCode::kInvalidArgument, "--roi must start on a chroma sample (even x / y) for " +
                                                     pix_fmt_name(in.format));
    VideoInfo out_info = in;
    out_info.width = r.w;
    out_info.height = r.h;
    const bool y4m = has_y4m_extension(o.output) || (o.output == "-" && in.y4m);
    VideoWriter writer(o.output, out_info, y4m);
    FrameBuffer frame, out(r.w, r.h, in.format);
    const bool all_planes = o.planes == "all";
    for (int k = 0; reader.read(frame); k++) {
        FrameView src = frame.view(), dst = out.view();
        for (int c = 0; c < src.plane_count(); c++) {
            const int sx = c ? chroma_shift_x(cf) : 0, sy = c ? chroma_shift_y(cf) : 0;
            const FloatPlane u = float_plane_from(src.planes[c], in.format.bit_depth);
            const physical::OutputRegion pr{r.x >> sx, r.y >> sy, dst.planes[c].width, dst.planes[c].height};
            FloatPlane g;
            const bool grain = c == 0 || all_planes;
            if (grain) {
                physical::BooleanModelParams pp = p;
                const int fw = physical::zoomed_size(u.width, p.zoom), fh = physical::zoomed_size(u.height, p.zoom);
                if (pr.x + pr.w > fw || pr.y + pr.h > fh)
                    throw Error(ErrorCode::kInvalidArgument, "--zoom " + std::to_string(p.zoom) +
                                                                 " does not map chroma planes onto the output; use --planes luma or a zoom giving even sizes");
                t.add(physical::render_boolean_model(u, pp, pr, physical::hash_coordinates(k, c, p.seed), g),
                      double(pr.w) * pr.h);
            } else {
                // planes without grain are only resampled (nearest), nothing is modelled
                g = FloatPlane(pr.w, pr.h);
                for (int y = 0; y < pr.h; y++)
                    for (int x = 0; x < pr.w; x++)
                        g.at(x, y) = u.at(std::min(u.width - 1, int((pr.x + x + 0.5) / p.zoom)),
                                          std::min(u.height - 1, int((pr.y + y + 0.5) / p.zoom)));
            }
            store_float_plane(g, dst.planes[c], in.format.bit_depth);
        }
        writer.write(out);
    }
    writer.commit();
}

}  // namespace

void register_render(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* sub = app.add_subcommand("render", "physically based grain: the Boolean model of Newson, Delon and Galerne "
                                                 "(stills through OpenImageIO, video as Y4M/YUV)");
    sub->add_option("input", o->input, "input picture (PNG, TIFF, EXR, DPX, JPEG, ...) or video (.y4m, .yuv, -)")->required();
    sub->add_option("-o,--output", o->output, "output (same kind as the input)")->required();
    sub->add_option("--radius", o->radius, "mean grain radius, input pixels")->capture_default_str();
    sub->add_option("--radius-sigma", o->radius_sigma, "standard deviation of the (log-normal) radius; 0 = constant")
        ->capture_default_str();
    sub->add_option("--filter-sigma", o->filter_sigma, "Gaussian filter, output pixels")->capture_default_str();
    sub->add_option("--zoom", o->zoom, "output pixels per input pixel")->capture_default_str();
    auto* n = sub->add_option("--samples", o->samples, "Monte Carlo samples per pixel (default 800)");
    auto* t = sub->add_option("--tolerance", o->tolerance,
                              "instead of a fixed N: stop each pixel when its standard error reaches this (0..0.5)");
    n->excludes(t);
    sub->add_option("--roi", o->roi, "render only x,y,w,h (output pixels)");
    sub->add_option("--threads", o->threads, "worker threads (output is the same for any count)")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxThreads));
    sub->add_option("--seed", o->seed, "grain seed")->capture_default_str();
    sub->add_option("--algorithm", o->algorithm, "auto, pixel-wise or grain-wise (same output; speed only)")
        ->capture_default_str();
    sub->add_option("--planes", o->planes, "video: luma (chroma copied) or all")->capture_default_str();
    sub->add_flag("-q,--quiet", o->quiet, "no report on stderr");
    o->raw.add_to(sub);
    sub->callback([o]() {
        physical::BooleanModelParams p;
        p.radius_mean = o->radius;
        p.radius_sigma = o->radius_sigma;
        p.filter_sigma = o->filter_sigma;
        p.zoom = o->zoom;
        if (o->samples) p.samples = *o->samples;
        if (o->tolerance) {
            p.tolerance = *o->tolerance;
            if (!(p.tolerance > 0))
                throw Error(ErrorCode::kInvalidArgument, "--tolerance " + std::to_string(p.tolerance) + ", allowed range (0, 0.5]");
        }
        p.threads = o->threads;
        p.seed = o->seed;
        if (o->algorithm == "pixel-wise") p.algorithm = physical::BooleanAlgorithm::kPixelWise;
        else if (o->algorithm == "grain-wise") p.algorithm = physical::BooleanAlgorithm::kGrainWise;
        else if (o->algorithm != "auto")
            throw Error(ErrorCode::kInvalidArgument, "--algorithm '" + o->algorithm + "' (allowed auto, pixel-wise, grain-wise)");
        if (o->planes != "luma" && o->planes != "all")
            throw Error(ErrorCode::kInvalidArgument, "--planes '" + o->planes + "' (allowed luma, all)");
        try {
            physical::validate(p);
        } catch (const Error& e) {
            throw Error(ErrorCode::kInvalidArgument, e.what());
        }
        Totals tot;
        const auto t0 = std::chrono::steady_clock::now();
        if (is_video_path(o->input))
            render_video(*o, p, tot);
        else
            render_still(*o, p, tot);
        const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!o->quiet)
            std::fprintf(stderr, "render: %s, N used per pixel %.1f (min %d, max %d), %.3f s, %.2f Mpixel/s\n",
                         physical::algorithm_name(tot.algorithm), tot.pixels ? tot.samples / tot.pixels : 0.0,
                         tot.max_n ? tot.min_n : 0, tot.max_n, dt, tot.pixels / dt * 1e-6);
    });
}

}  // namespace filmgrain::cli

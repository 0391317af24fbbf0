#include "render_job.hpp"

#include <algorithm>

#include "filmgrain/error.hpp"
#include "option_parsing.hpp"
#include "core/thread_pool.hpp"
#include "physical/cell_random.hpp"

namespace filmgrain::cli {
namespace {

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


// Planes without grain (alpha, and chroma with --planes luma) are only resampled (nearest).
void resample_nearest(const FloatPlane& u, const physical::OutputRegion& r, double zoom, FloatPlane& out) {
    out = FloatPlane(r.w, r.h);
    for (int y = 0; y < r.h; y++)
        for (int x = 0; x < r.w; x++)
            out.at(x, y) = u.at(std::min(u.width - 1, int((r.x + x + 0.5) / zoom)),
                                std::min(u.height - 1, int((r.y + y + 0.5) / zoom)));
}

}  // namespace

physical::BooleanModelParams render_model_params(const RenderOptions& o) {
    physical::BooleanModelParams p;
    p.radius_mean = o.radius;
    p.radius_sigma = o.radius_sigma;
    p.filter_sigma = o.filter_sigma;
    p.zoom = o.zoom;
    if (o.samples) p.samples = *o.samples;
    if (o.tolerance) {
        p.tolerance = *o.tolerance;
        if (!(p.tolerance > 0))
            throw Error(ErrorCode::kInvalidArgument, "--tolerance " + std::to_string(p.tolerance) + ", allowed range (0, 0.5]");
    }
    p.threads = o.threads;
    p.seed = o.seed;
    if (o.algorithm == "pixel-wise") p.algorithm = physical::BooleanAlgorithm::kPixelWise;
    else if (o.algorithm == "grain-wise") p.algorithm = physical::BooleanAlgorithm::kGrainWise;
    else if (o.algorithm != "auto")
        throw Error(ErrorCode::kInvalidArgument, "--algorithm '" + o.algorithm + "' (allowed auto, pixel-wise, grain-wise)");
    if (o.planes != "luma" && o.planes != "all")
        throw Error(ErrorCode::kInvalidArgument, "--planes '" + o.planes + "' (allowed luma, all)");
    try {
        physical::validate(p);
    } catch (const Error& e) {
        throw Error(ErrorCode::kInvalidArgument, e.what());
    }
    return p;
}

void RenderTotals::add(const physical::RenderReport& r, double px) {
    pixels += px;
    samples += r.mean_samples * px;
    if (r.tiles) {
        min_n = std::min(min_n, r.min_samples);
        max_n = std::max(max_n, r.max_samples);
        algorithm = r.algorithm;
    }
}

void add_render_options(CLI::App* sub, RenderOptions& o) {
    sub->add_option("input", o.input, "input picture (PNG, TIFF, EXR, DPX, JPEG, ...) or video (.y4m, .yuv, -)")->required();
    sub->add_option("-o,--output", o.output, "output (same kind as the input)")->required();
    sub->add_option("--radius", o.radius,
                    "mean grain radius, input pixels (chickendream's median `rad` with log-std `dev`: rad*exp(dev^2/2))")
        ->capture_default_str();
    sub->add_option("--radius-sigma", o.radius_sigma,
                    "standard deviation of the (log-normal) radius; 0 = constant (from chickendream's `dev`: "
                    "radius*sqrt(exp(dev^2)-1))")
        ->capture_default_str();
    sub->add_option("--filter-sigma", o.filter_sigma, "Gaussian filter, output pixels")->capture_default_str();
    sub->add_option("--zoom", o.zoom, "output pixels per input pixel")->capture_default_str();
    auto* n = sub->add_option("--samples", o.samples, "Monte Carlo samples per pixel (default 800)");
    auto* t = sub->add_option("--tolerance", o.tolerance,
                              "instead of a fixed N: stop each pixel when its standard error reaches this (0..0.5)");
    n->excludes(t);
    sub->add_option("--roi", o.roi, "render only x,y,w,h (output pixels)");
    sub->add_option("--threads", o.threads, "worker threads (output is the same for any count)")
        ->capture_default_str()
        ->check(CLI::Range(1, kMaxThreads));
    sub->add_option("--seed", o.seed, "grain seed")->capture_default_str();
    sub->add_option("--algorithm", o.algorithm, "auto, pixel-wise or grain-wise (same output; speed only)")
        ->capture_default_str();
    sub->add_option("--planes", o.planes, "video: luma (chroma copied) or all")->capture_default_str();
    sub->add_flag("-q,--quiet", o.quiet, "no report on stderr");
    o.raw.add_to(sub);
}

RenderJob::RenderJob(const RenderOptions& options) : o_(options), p_(render_model_params(options)) {
    video_ = is_video_path(o_.input);
    const physical::OutputRegion roi = parse_roi(o_.roi);
    if (video_) {
        // kept for run_all(): standard input can be opened once
        reader_ = std::make_unique<VideoReader>(o_.input, o_.raw.to_info());
        in_info_ = reader_->info();
        region_ = checked_region(roi, in_info_.width, in_info_.height, p_.zoom);
        const ChromaFormat cf = in_info_.format.chroma;
        if ((region_.x & chroma_shift_x(cf) ? 1 : 0) || (region_.y & chroma_shift_y(cf) ? 1 : 0))
            throw Error(ErrorCode::kInvalidArgument, "--roi must start on a chroma sample (even x / y) for " +
                                                         pix_fmt_name(in_info_.format));
        if (o_.planes == "all")
            for (int c = 1; c < num_planes(cf); c++) {
                const int sx = chroma_shift_x(cf), sy = chroma_shift_y(cf);
                const int fw = physical::zoomed_size(plane_width(cf, c, in_info_.width), p_.zoom),
                          fh = physical::zoomed_size(plane_height(cf, c, in_info_.height), p_.zoom);
                if ((region_.x >> sx) + plane_width(cf, c, region_.w) > fw ||
                    (region_.y >> sy) + plane_height(cf, c, region_.h) > fh)
                    throw Error(ErrorCode::kInvalidArgument,
                                "--zoom " + std::to_string(p_.zoom) +
                                    " does not map chroma planes onto the output; use --planes luma or a zoom giving even sizes");
            }
    } else {
        still_ = std::make_unique<StillImage>(read_still_image(o_.input));
        region_ = checked_region(roi, still_->channels[0].width, still_->channels[0].height, p_.zoom);
    }
}

RenderJob::~RenderJob() = default;

VideoInfo RenderJob::output_info() const {
    VideoInfo out = in_info_;
    out.width = region_.w;
    out.height = region_.h;
    return out;
}

bool RenderJob::output_y4m() const { return has_y4m_extension(o_.output) || (o_.output == "-" && in_info_.y4m); }

long long RenderJob::frame_count() const { return video_ ? frame_count_from_size(o_.input, in_info_) : 1; }

int RenderJob::tile_alignment_x() const { return video_ ? 1 << chroma_shift_x(in_info_.format.chroma) : 1; }
int RenderJob::tile_alignment_y() const { return video_ ? 1 << chroma_shift_y(in_info_.format.chroma) : 1; }

void RenderJob::render_video_tile(const FrameBuffer& input, int k, const physical::OutputRegion& tile, FrameBuffer& out,
                                  RenderTotals& totals) const {
    const ChromaFormat cf = in_info_.format.chroma;
    if (tile.x < 0 || tile.y < 0 || tile.w < 1 || tile.h < 1 || tile.x + tile.w > region_.w || tile.y + tile.h > region_.h ||
        tile.x % tile_alignment_x() || tile.y % tile_alignment_y())
        throw Error(ErrorCode::kInvalidArgument,
                    "tile " + std::to_string(tile.x) + "," + std::to_string(tile.y) + "," + std::to_string(tile.w) + "," +
                        std::to_string(tile.h) + " is not inside the " + std::to_string(region_.w) + "x" +
                        std::to_string(region_.h) + " output or does not start on a chroma sample");
    if (out.width() != tile.w || out.height() != tile.h || out.format().chroma != in_info_.format.chroma ||
        out.format().bit_depth != in_info_.format.bit_depth)
        out = FrameBuffer(tile.w, tile.h, in_info_.format);
    FrameView src = const_cast<FrameBuffer&>(input).view(), dst = out.view();
    const bool all_planes = o_.planes == "all";
    for (int c = 0; c < src.plane_count(); c++) {
        const int sx = c ? chroma_shift_x(cf) : 0, sy = c ? chroma_shift_y(cf) : 0;
        const FloatPlane u = float_plane_from(src.planes[c], in_info_.format.bit_depth);
        const physical::OutputRegion pr{(region_.x + tile.x) >> sx, (region_.y + tile.y) >> sy, dst.planes[c].width,
                                        dst.planes[c].height};
        FloatPlane g;
        if (c == 0 || all_planes)
            totals.add(physical::render_boolean_model(u, p_, pr, physical::hash_coordinates(k, c, p_.seed), g),
                       double(pr.w) * pr.h);
        else
            resample_nearest(u, pr, p_.zoom, g);
        store_float_plane(g, dst.planes[c], in_info_.format.bit_depth);
    }
}

void RenderJob::render_still_tile(int c, const physical::OutputRegion& tile, FloatPlane& out, RenderTotals& totals) const {
    if (c < 0 || c >= int(still_->channels.size()))
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("channel", c, 0, int(still_->channels.size()) - 1));
    if (tile.x < 0 || tile.y < 0 || tile.w < 1 || tile.h < 1 || tile.x + tile.w > region_.w || tile.y + tile.h > region_.h)
        throw Error(ErrorCode::kInvalidArgument, "tile " + std::to_string(tile.x) + "," + std::to_string(tile.y) + "," +
                                                     std::to_string(tile.w) + "," + std::to_string(tile.h) +
                                                     " is not inside the " + std::to_string(region_.w) + "x" +
                                                     std::to_string(region_.h) + " output");
    const physical::OutputRegion r{region_.x + tile.x, region_.y + tile.y, tile.w, tile.h};
    if (c == still_->alpha_channel)  // alpha is not film: resampled without grain
        resample_nearest(still_->channels[c], r, p_.zoom, out);
    else
        totals.add(physical::render_boolean_model(still_->channels[c], p_, r, physical::hash_coordinates(int64_t(c), 0, p_.seed), out),
                   double(r.w) * r.h);
}

void RenderJob::run_all(RenderTotals& totals) {
    const physical::OutputRegion whole{0, 0, region_.w, region_.h};
    if (!video_) {
        StillImage img = *still_;
        for (std::size_t c = 0; c < img.channels.size(); c++) render_still_tile(int(c), whole, img.channels[c], totals);
        write_still_image(o_.output, img);
        return;
    }
    if (!reader_) reader_ = std::make_unique<VideoReader>(o_.input, o_.raw.to_info());
    VideoReader& reader = *reader_;
    VideoWriter writer(o_.output, output_info(), output_y4m());
    FrameBuffer frame, out(region_.w, region_.h, in_info_.format);
    for (int k = 0; reader.read(frame); k++) {
        render_video_tile(frame, k, whole, out, totals);
        writer.write(out);
    }
    writer.commit();
}

}  // namespace filmgrain::cli

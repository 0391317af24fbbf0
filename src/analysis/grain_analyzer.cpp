#include "analysis/grain_analyzer.hpp"

#include <opencv2/imgproc.hpp>

#include "analysis/denoising.hpp"
#include "analysis/flat_mask.hpp"
#include "analysis/plane_image.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::analysis {

GrainAnalyzer::GrainAnalyzer(const AnalysisOptions& options, PixelFormat format, int width, int height)
    : o_(options), fmt_(format), width_(width), height_(height) {
    if (o_.frame_step < 1) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("frame_step", o_.frame_step, 1, 1 << 30));
    if (o_.temporal_radius < 0 || o_.temporal_radius > 8)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("temporal_radius", o_.temporal_radius, 0, 8));
    if (o_.spatial_only) o_.temporal_radius = 0;
    if (o_.first_index < 0) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("first_index", o_.first_index, 0, 1 << 30));
    next_to_analyse_ = o_.first_index;
}

GrainAnalyzer::~GrainAnalyzer() = default;

void GrainAnalyzer::add_frame(const FrameBuffer& source, const FrameBuffer* denoised) {
    if (source.width() != width_ || source.height() != height_ || source.format().chroma != fmt_.chroma ||
        source.format().bit_depth != fmt_.bit_depth)
        throw Error(ErrorCode::kInvalidArgument, "frame " + std::to_string(frames_seen_) + " differs in size or format from the first");
    if (denoised && (denoised->width() != width_ || denoised->height() != height_ ||
                     denoised->format().chroma != fmt_.chroma || denoised->format().bit_depth != fmt_.bit_depth))
        throw Error(ErrorCode::kInvalidArgument,
                    "denoised frame " + std::to_string(frames_seen_) + " differs in size or format from the source");
    Held h{o_.first_index + frames_seen_, source, denoised ? std::make_unique<FrameBuffer>(*denoised) : nullptr, {},
           std::nullopt};
    window_.push_back(std::move(h));
    frames_seen_++;
    // A picture is analysed once its right-hand neighbours have arrived.
    const int radius = denoised ? 0 : o_.temporal_radius;
    while (next_to_analyse_ + radius < o_.first_index + frames_seen_) {
        if (wanted(next_to_analyse_)) {
            for (std::size_t i = 0; i < window_.size(); i++)
                if (window_[i].index == next_to_analyse_) analyse(i);
        }
        next_to_analyse_++;
    }
    while (!window_.empty() && window_.front().index < next_to_analyse_ - o_.temporal_radius) window_.pop_front();
}

void GrainAnalyzer::finish() {
    for (; next_to_analyse_ < o_.first_index + frames_seen_; next_to_analyse_++)
        if (wanted(next_to_analyse_))
            for (std::size_t i = 0; i < window_.size(); i++)
                if (window_[i].index == next_to_analyse_) analyse(i);
    window_.clear();
}

double GrainAnalyzer::reliable_fraction() const {
    return flat_samples_ ? double(reliable_samples_) / double(flat_samples_) : 0.0;
}

const cv::Mat& GrainAnalyzer::Held::plane(int p) {
    if (planes[p].empty()) planes[p] = plane_to_float(source.view(), p);
    return planes[p];
}

const MotionPicture& GrainAnalyzer::Held::motion_picture() {
    if (!motion) motion = prepare_motion_picture(plane(0));
    return *motion;
}

void GrainAnalyzer::analyse(std::size_t wi) {
    Held& centre = window_[wi];
    const int k = centre.index;
    const FrameView src = centre.source.view();
    ObservationRequest req;
    req.dct_power = true;  // FGC cut-offs; the spectrum of the report for both models
    req.ar_equations = o_.model == GrainModel::kAv1;
    req.level_block = o_.model == GrainModel::kAv1 ? kAv1LevelBlock : kFgcLevelBlock;
    // the clip's analysed pictures alternate between the halves, wherever the range starts
    req.half = (k / o_.frame_step) & 1;
    PictureObservations picture;
    picture.index = k;
    cv::Mat luma_normalized, luma_denoised;
    const bool keep = sample_.index < 0 || (sample_.index < 2 * o_.temporal_radius && k >= 2 * o_.temporal_radius);
    if (keep) sample_.index = k;
    // Luma leads: its global motion and its per-neighbour motion decisions guide the chroma
    // planes, whose moving texture is too faint to be told from grain.
    std::vector<cv::Point> luma_shifts;
    std::vector<cv::Mat> luma_accepted;
    const auto to_plane_size = [](const cv::Mat& mask, cv::Size size) {
        if (mask.size() == size) return mask;
        cv::Mat m;
        cv::resize(mask, m, size, 0, 0, cv::INTER_AREA);
        cv::threshold(m, m, 254, 255, cv::THRESH_BINARY);  // every luma sample under it agreed
        return m;
    };
    for (int p = 0; p < src.plane_count(); p++) {
        const cv::Mat& s = centre.plane(p);
        const int sx = p > 0 ? chroma_shift_x(fmt_.chroma) : 0, sy = p > 0 ? chroma_shift_y(fmt_.chroma) : 0;
        GrainEstimate g;
        if (centre.denoised) {
            g = grain_from_denoised(s, plane_to_float(centre.denoised->view(), p));
        } else {
            std::vector<Held*> held;
            for (auto& h : window_)
                if (h.index != k && std::abs(h.index - k) <= o_.temporal_radius) held.push_back(&h);
            if (p == 0)
                for (Held* h : held) luma_shifts.push_back(estimate_global_shift(centre.motion_picture(), h->motion_picture()));
            std::vector<TemporalNeighbour> neighbours;
            std::vector<cv::Mat> guides(held.size());
            for (std::size_t j = 0; j < held.size(); j++) {
                TemporalNeighbour n;
                n.plane = &held[j]->plane(p);
                n.shift = {int(std::lround(luma_shifts[j].x / double(1 << sx))), int(std::lround(luma_shifts[j].y / double(1 << sy)))};
                if (p > 0 && j < luma_accepted.size()) {
                    guides[j] = to_plane_size(luma_accepted[j], s.size());
                    n.guide = &guides[j];
                }
                neighbours.push_back(n);
            }
            g = neighbours.empty() ? denoise_spatial(s)
                                   : denoise_temporal(s, neighbours, fmt_.bit_depth, p == 0 ? &luma_accepted : nullptr);
        }
        const cv::Mat flat = flat_region_mask(g.denoised, fmt_.bit_depth);
        cv::Mat usable;
        cv::bitwise_and(flat, g.reliable, usable);
        const int nflat = cv::countNonZero(flat), nusable = cv::countNonZero(usable);
        picture.flat_samples += nflat;
        picture.reliable_samples += nusable;
        // Nothing (or almost nothing) still: measure on the spatial estimate rather than not at all.
        if (nusable < nflat / 10) usable = flat;
        CoLocatedLuma luma;
        if (p > 0) {
            if (req.ar_equations && !luma_normalized.empty())
                cv::resize(luma_normalized, luma.normalized, s.size(), 0, 0, cv::INTER_AREA);
            cv::resize(luma_denoised, luma.denoised, s.size(), 0, 0, cv::INTER_AREA);
        }
        count_legal_range(s, fmt_.bit_depth, 16, p == 0 ? 235 : 240, picture.planes[p]);
        cv::Mat normalized = observe_plane(s, g.denoised, g.grain, usable, fmt_.bit_depth, luma, req, picture.planes[p]);
        if (p == 0) luma_normalized = normalized, luma_denoised = g.denoised;
        if (keep) {
            sample_.source[p] = s;
            sample_.denoised[p] = g.denoised;
            if (p == 0) sample_.flat_luma = flat;
        }
    }
    merge_picture(picture);
    if (o_.keep_picture_observations) pictures_.push_back(std::move(picture));
}

bool GrainAnalyzer::wanted(int k) const {
    return k % o_.frame_step == 0 && k >= o_.analyse_from && k < o_.analyse_to;
}

// Every picture's observations are gathered on their own and added here, so that a clip
// analysed in ranges (the same pictures merged in the same order) gives the same sums.
void GrainAnalyzer::merge_picture(const PictureObservations& picture) {
    for (int p = 0; p < 3; p++) merge_observations(obs_[p], picture.planes[p]);
    flat_samples_ += picture.flat_samples;
    reliable_samples_ += picture.reliable_samples;
    frames_analysed_++;
}

FgcEstimate GrainAnalyzer::estimate_fgc() const {
    FgcTarget t;
    t.flavour = o_.flavour;
    t.chroma = fmt_.chroma;
    t.bit_depth = fmt_.bit_depth;
    if (o_.accuracy > 0) t.accuracy = o_.accuracy;
    return analysis::estimate_fgc(obs_, t);
}

Av1Estimate GrainAnalyzer::estimate_av1() const {
    Av1Target t;
    t.chroma = fmt_.chroma;
    t.bit_depth = fmt_.bit_depth;
    if (o_.accuracy > 0) t.accuracy = o_.accuracy;
    t.max_lag = o_.max_ar_lag;
    return analysis::estimate_av1(obs_, t);
}

}  // namespace filmgrain::analysis

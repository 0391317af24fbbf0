// The analysis driver: pictures in display order (optionally with their denoised versions)
// go in; every `frame_step`-th picture is analysed with its temporal neighbours; the
// observations of all analysed pictures are pooled into one parameter set for the clip.
#pragma once
#include <array>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/av1_estimation.hpp"
#include "analysis/block_observations.hpp"
#include "analysis/denoising.hpp"
#include "analysis/fgc_estimation.hpp"
#include "core/frame_buffer.hpp"

namespace filmgrain::analysis {

enum class GrainModel { kFgc, kAv1 };

struct AnalysisOptions {
    GrainModel model = GrainModel::kFgc;
    FgcFlavour flavour = FgcFlavour::kRdd5;
    int frame_step = 1;        // analyse pictures 0, step, 2 step, ...
    int temporal_radius = 2;   // neighbours on each side used by the temporal denoiser
    double accuracy = 0.0;     // 0: the model's own default (Av1Target, FgcTarget)
    int max_ar_lag = 3;
    bool spatial_only = false;  // denoise each picture on its own (no temporal neighbours)
    // A range of a clip (distributed analysis): the first picture added has index
    // `first_index`; only pictures in [analyse_from, analyse_to) are analysed, the others
    // are temporal neighbours. With the neighbours on both sides of the range supplied, the
    // range's observations equal those the whole clip gives for its pictures.
    int first_index = 0;
    int analyse_from = 0;
    int analyse_to = 1 << 30;
    bool keep_picture_observations = false;  // keep each analysed picture's own (picture_observations())
};

// One analysed picture's observations, merged into the clip's in picture order.
struct PictureObservations {
    int index = -1;
    std::array<PlaneObservations, 3> planes;
    long long flat_samples = 0, reliable_samples = 0;
};

// One analysed picture kept for the report: source and denoised planes (CV_32F).
struct AnalysedPicture {
    int index = -1;
    std::array<cv::Mat, 3> source, denoised;
    cv::Mat flat_luma;
};

class GrainAnalyzer {
public:
    GrainAnalyzer(const AnalysisOptions& options, PixelFormat format, int width, int height);
    ~GrainAnalyzer();
    // Pictures in display order. `denoised` (same format) replaces the internal denoiser.
    void add_frame(const FrameBuffer& source, const FrameBuffer* denoised = nullptr);
    // Analyses the pictures still waiting for neighbours. Call once after the last frame.
    void finish();
    int frames_seen() const { return frames_seen_; }
    int frames_analysed() const { return frames_analysed_; }
    const std::array<PlaneObservations, 3>& observations() const { return obs_; }
    const std::vector<PictureObservations>& picture_observations() const { return pictures_; }
    // Adds an analysed picture's observations (gathered elsewhere) as if analysed here.
    void merge_picture(const PictureObservations& picture);
    const AnalysedPicture& sample_picture() const { return sample_; }
    double reliable_fraction() const;  // share of flat samples with an unbiased grain estimate

    FgcEstimate estimate_fgc() const;
    Av1Estimate estimate_av1() const;

private:
    void analyse(std::size_t window_index);
    bool wanted(int index) const;
    AnalysisOptions o_;
    PixelFormat fmt_;
    int width_, height_;
    // A picture of the temporal window, with what its analyses and its neighbours' share,
    // made once on first use: its planes as float and its luma ready for motion estimation.
    struct Held {
        int index;
        FrameBuffer source;
        std::unique_ptr<FrameBuffer> denoised;
        std::array<cv::Mat, 3> planes{};
        std::optional<MotionPicture> motion;
        const cv::Mat& plane(int p);
        const MotionPicture& motion_picture();
    };
    std::deque<Held> window_;
    int frames_seen_ = 0, frames_analysed_ = 0;
    int next_to_analyse_ = 0;
    std::array<PlaneObservations, 3> obs_;
    long long reliable_samples_ = 0, flat_samples_ = 0;
    AnalysedPicture sample_;
    std::vector<PictureObservations> pictures_;
};

}  // namespace filmgrain::analysis

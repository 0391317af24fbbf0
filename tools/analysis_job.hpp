// `filmgrain analyze` as a job that can be cut into ranges of pictures: the CLI analyses
// the whole clip in one pass; the Python module's distributed analysis observes ranges on
// Dask workers (each with the temporal neighbours beyond its ends), gathers every analysed
// picture's observations and fits once, in picture order: the same observations and the
// same sums, so the same parameters as the one pass.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "cli_common.hpp"

#ifdef FILMGRAIN_HAVE_ANALYSIS
#include "analysis/grain_analyzer.hpp"
#endif

namespace filmgrain::cli {

struct AnalyzeOptions {
    std::string input, denoised, model, output, table, sei, report, afgs1;
    std::string sei_codec = "hevc";
    std::string flavour = "rdd5";
    int frame_step = 0;
    int max_frames = 32;
    int temporal_radius = 2;
    double accuracy = 0.0;  // 0: the model's own default
    double max_error = 0.25;  // the accuracy check: a component missing its levels by more is refused
    int max_lag = 3;
    bool spatial = false;
    bool force = false;  // write components that fail their accuracy check
    bool quiet = false;
    RawVideoOptions raw;
};

// The analyze subcommand's options (the CLI's, and through parse_subcommand_arguments the Python module's).
void add_analyze_options(CLI::App* sub, AnalyzeOptions& o);

#ifdef FILMGRAIN_HAVE_ANALYSIS
class AnalysisJob {
public:
    // Checks the options and reads the input's header. Throws Error naming the option.
    explicit AnalysisJob(const AnalyzeOptions& options);
    const VideoInfo& info() const { return info_; }
    long long frame_count() const { return total_; }  // -1: not known (a pipe)
    int frame_step() const { return ao_.frame_step; }
    int temporal_radius() const { return ao_.spatial_only ? 0 : ao_.temporal_radius; }

    // The observations of the analysed pictures in [from, to), in picture order.
    std::vector<analysis::PictureObservations> observe_range(int from, int to) const;
    // The one-pass analysis of `filmgrain analyze`, outputs included.
    int run();
    // Fits the pictures' observations (in picture order) of a clip of `frames` pictures
    // and writes the outputs, as run() does.
    void write_outputs_from(const std::vector<analysis::PictureObservations>& pictures, int frames) const;

private:
    // The analyser over [from, to) with the temporal neighbours beyond its ends.
    std::unique_ptr<analysis::GrainAnalyzer> analyse_range(int from, int to) const;
    // `sample`: the picture the report shows (the one-pass analyser's own when null).
    void write_outputs(const analysis::GrainAnalyzer& analyzer, int frames,
                       const analysis::AnalysedPicture* sample = nullptr) const;
    AnalyzeOptions o_;
    std::unique_ptr<VideoReader> reader_;  // opened by the constructor, read by run()
    VideoInfo info_;
    long long total_ = -1;
    analysis::AnalysisOptions ao_;
};
#endif

}  // namespace filmgrain::cli

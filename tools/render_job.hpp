// `filmgrain render` as a job that can be cut into parts: the CLI renders all of it, the
// Python module's distributed render (python/filmgrain/distributed.py) renders frames and
// tiles of it on Dask workers. Grains are seeded per cell from the frame, the plane and
// --seed (physical/boolean_model.hpp), so any tile of any frame renders to the same samples
// as in the whole picture: the parts join into the CLI's output byte for byte.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "physical/boolean_model.hpp"
#include "still_image.hpp"

namespace filmgrain::cli {

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

// The render subcommand's options (the CLI's, and through parse_subcommand_arguments the Python module's).
void add_render_options(CLI::App* sub, RenderOptions& o);
// Parses `args` (the render subcommand's arguments: input, -o, options) as the CLI does.

// The model's parameters from the options, checked (Error(kInvalidArgument) naming the option).
physical::BooleanModelParams render_model_params(const RenderOptions& o);

// What the renderer did, summed over parts (the CLI's report line).
struct RenderTotals {
    double pixels = 0, samples = 0;
    int min_n = 1 << 30, max_n = 0;
    physical::BooleanAlgorithm algorithm = physical::BooleanAlgorithm::kAuto;
    void add(const physical::RenderReport& r, double px);
};

class RenderJob {
public:
    // Checks the options and reads what the job's shape needs: a video's header, or the
    // still itself. Throws Error naming the option or file at fault.
    explicit RenderJob(const RenderOptions& options);
    ~RenderJob();

    bool video() const { return video_; }
    const RenderOptions& options() const { return o_; }
    const physical::BooleanModelParams& model() const { return p_; }
    // The output picture: the region of the zoomed picture (--roi, else all of it).
    int output_width() const { return region_.w; }
    int output_height() const { return region_.h; }
    // video
    const VideoInfo& input_info() const { return in_info_; }
    VideoInfo output_info() const;
    bool output_y4m() const;
    // Frames in the input (a regular file's size; -1 when not known).
    long long frame_count() const;
    // Output tiles must start on a chroma sample: the alignment of x and y.
    int tile_alignment_x() const;
    int tile_alignment_y() const;
    // still
    const StillImage& still() const { return *still_; }

    // Renders `tile` (output coordinates, relative to the output picture) of video frame k,
    // read from `input` (frame k of the clip). out: the tile's planes.
    void render_video_tile(const FrameBuffer& input, int k, const physical::OutputRegion& tile, FrameBuffer& out,
                           RenderTotals& totals) const;
    // Renders `tile` of still channel c into out (tile size).
    void render_still_tile(int c, const physical::OutputRegion& tile, FloatPlane& out, RenderTotals& totals) const;

    // The whole job, as `filmgrain render` runs it.
    void run_all(RenderTotals& totals);

private:
    RenderOptions o_;
    physical::BooleanModelParams p_;
    bool video_ = false;
    VideoInfo in_info_;
    std::unique_ptr<StillImage> still_;
    std::unique_ptr<VideoReader> reader_;  // video: opened by the constructor, read by run_all()
    physical::OutputRegion region_;
};

}  // namespace filmgrain::cli

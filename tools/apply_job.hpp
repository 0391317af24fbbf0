// `filmgrain apply` as a job that can be cut into ranges of pictures: the CLI runs all of
// it (pipelined); the Python module's distributed apply runs ranges on Dask workers. A range
// starts in the state the stream has there, found by following the metadata of the pictures
// before it (Session::skip_picture), not by synthesizing them: the joined ranges equal the
// CLI's output byte for byte, whatever the split.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "filmgrain/session.hpp"
#include "session/parameter_file_feed.hpp"

namespace filmgrain::cli {

struct ApplyOptions {
    std::string input, output, params;
    std::vector<std::string> sei;
    std::vector<std::string> afgs1;
    std::string sei_codec = "hevc";
    std::string flavour = "rdd5";
    std::string on_invalid = "error";
    std::string persistence = "reference";
    int block_size = 0;
    int single_line_blocks = 0;
    std::string coded_size;
    int threads = 0;
    bool quiet = false;
    // vfgs flavour: the reference tool's own options
    std::optional<uint32_t> seed;
    int gain = 100;
    std::string output_pix_fmt;
    bool pattern_interpolation = false;
    // AV1
    int matrix_coefficients = -1;
    int clip_to_restricted_range = -1;
    RawVideoOptions raw;
};

// The apply subcommand's options (the CLI's, and through parse_subcommand_arguments the Python module's).
void add_apply_options(CLI::App* sub, ApplyOptions& o);

class ApplyJob {
public:
    // Checks the options and reads the parameter files. Throws Error naming what is wrong.
    explicit ApplyJob(const ApplyOptions& options);
    ~ApplyJob();
    VideoInfo output_info() const;
    bool output_y4m() const;
    long long frame_count() const;  // -1: not known (a pipe)
    // The whole input, as `filmgrain apply`.
    int run_all();
    // Pictures [from, to) written to `part` as raw frames (no header); returns how many.
    int run_range(int from, int to, const std::string& part);

private:
    std::string model_name() const;
    const VideoInfo& input_info() const;
    std::unique_ptr<session::ParameterFileFeed> take_feed();
    void synthesize(session::ParameterFileFeed& feed, Session& session, int k, const VideoInfo& info, FrameBuffer& in,
                    FrameBuffer& out) const;
    ApplyOptions o_;
    FgcFlavour flavour_ = FgcFlavour::kRdd5;
    session::FeedModel model_ = session::FeedModel::kFgc;
    SessionOptions session_options_;
    bool override_format_ = false;
    VideoInfo out_override_;
    std::unique_ptr<session::ParameterFileFeed> feed_;
    mutable std::optional<VideoInfo> input_info_;  // read on first use (never for the CLI's stdin)
};

}  // namespace filmgrain::cli

// Shared pieces of the `filmgrain` subcommands: option parsing helpers and error exits.
#pragma once
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"
#include "io/video_file.hpp"

namespace filmgrain::cli {

// Raw-video options shared by every command that reads YUV.
struct RawVideoOptions {
    std::string size;     // WxH
    std::string pix_fmt = "yuv420p";
    std::string fps = "25";
    VideoInfo to_info() const;  // throws Error on a malformed value
    void add_to(CLI::App* app);
};

FgcFlavour parse_flavour(const std::string& s);
// The AV1 picture facts (color_config()) of a pixel format, as the tool's AV1 parameter files
// carry them.
Av1ColorInfo av1_color_of(const PixelFormat& format, int matrix_coefficients = 2);

// Parses `args` (in order, without a program name) with `app`. CLI11's parse errors become
// Error(kInvalidArgument) with its message; a command's own exit status (CLI::RuntimeError)
// passes through to the caller.
void parse_arguments(CLI::App& app, const std::vector<std::string>& args);

// One subcommand's options from `args` by the definitions the CLI registers for it: how the
// Python module turns keyword arguments into the CLI's options, checks and messages.
template <typename Options>
Options parse_subcommand_arguments(const char* name, void (*add_options)(CLI::App*, Options&),
                                   const std::vector<std::string>& args) {
    Options o;
    CLI::App app(name);
    add_options(&app, o);
    parse_arguments(app, args);
    return o;
}

// A subcommand whose options `add_options` defines (the same definitions
// parse_subcommand_arguments parses) and `run` carries out, returning the exit code.
template <typename Options, typename Run>
void register_subcommand(CLI::App& app, const char* name, const char* description,
                         void (*add_options)(CLI::App*, Options&), Run run) {
    auto o = std::make_shared<Options>();
    CLI::App* sub = app.add_subcommand(name, description);
    add_options(sub, *o);
    sub->callback([o, run]() {
        if (const int rc = run(*o)) throw CLI::RuntimeError(rc);
    });
}

void register_apply(CLI::App& app);
void register_render(CLI::App& app);
void register_stats(CLI::App& app);
void register_tradeoff(CLI::App& app);
void register_analyze(CLI::App& app);
void register_preset(CLI::App& app);
void register_params(CLI::App& app);
void register_demo(CLI::App& app, bool* ran_default);
void register_inspect(CLI::App& app);
void register_decode(CLI::App& app);
void register_verify(CLI::App& app);
int run_demo();

// Writes a PNG with the clean and the grainy crop side by side (through the image module).
// Returns false with a reason when it cannot (no OpenImageIO in this build, or a failed write).
bool write_preview_png(const std::string& path, const FrameBuffer& clean, const FrameBuffer& grainy, std::string* why);

}  // namespace filmgrain::cli

// The tool's still-picture and plot I/O lives in a module loaded on first use
// (filmgrain-oiio.so, tools/image_module/). OpenImageIO brings about 250 shared libraries
// with it; linked into the tool, their loading and relocation cost every `filmgrain`
// process about 0.3 s before main() (measured: 0.30–0.38 s for `filmgrain --help`), which
// only the commands reading or writing stills or plots need to pay.
//
// Both sides are built together from this tree (same compiler and C++ runtime), so the
// interface passes C++ types; kImageModuleVersion changes whenever this header does.
#pragma once
#include <string>
#include <vector>

#include "still_image.hpp"
#include "tradeoff_plot.hpp"

namespace filmgrain::cli {

inline constexpr int kImageModuleVersion = 1;

// Each call returns an empty string on success, otherwise the reason it failed; none throws.
struct ImageModule {
    int version;
    std::string (*read_image)(const std::string& path, StillImage& out);
    // write_path: where to write (a temporary beside the target, or the target itself when
    // that is a pipe or device); format: the target's extension without the dot, which picks
    // the file format since a temporary or device name may not carry it.
    std::string (*write_image)(const std::string& write_path, const std::string& format, const StillImage& image);
    std::string (*write_plot)(const std::string& write_path, const std::string& format,
                              const std::vector<PlotPoint>& points);
};

// The module, loaded once per process; nullptr with the reason (which paths were tried, or
// that this build has no OpenImageIO) when it cannot be loaded.
const ImageModule* image_module(std::string* why);

}  // namespace filmgrain::cli

// The module's one exported symbol: its table when `version` is the one it was built with.
extern "C" const filmgrain::cli::ImageModule* filmgrain_image_module(int version);

// Still pictures through OpenImageIO (PNG, TIFF, EXR, DPX, JPEG, ...), in the image module
// loaded on first use (image_module.hpp): channels as float planes in [0, 1] (float files
// keep their values), written back in the input's sample format through OutputFile.
#pragma once
#include <string>
#include <vector>

#include "core/float_plane.hpp"

namespace filmgrain::cli {

struct StillImage {
    std::vector<FloatPlane> channels;
    std::vector<std::string> channel_names;
    int alpha_channel = -1;
    std::string format = "uint8";  // OpenImageIO TypeDesc name of the file's samples
    bool floating = false;
};

bool have_still_image_support();  // whether the image module loads
// The file format a target's name asks for: its extension without the dot ("" if none).
std::string image_format_of(const std::string& path);
bool is_video_path(const std::string& path);  // .y4m, .yuv, or "-"
// Throws Error(kIo / kUnsupported) with the reason.
StillImage read_still_image(const std::string& path);
void write_still_image(const std::string& path, const StillImage& image);

}  // namespace filmgrain::cli

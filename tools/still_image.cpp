#include "still_image.hpp"

#include <filesystem>

#include "filmgrain/error.hpp"
#include "image_module.hpp"
#include "io/output_file.hpp"

namespace filmgrain::cli {

bool is_video_path(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    return path == "-" || ext == ".y4m" || ext == ".yuv" || ext == ".Y4M" || ext == ".YUV";
}

bool have_still_image_support() { return image_module(nullptr) != nullptr; }

namespace {
const ImageModule& module_for(const std::string& what, const std::string& path) {
    std::string why;
    const ImageModule* m = image_module(&why);
    if (!m) throw Error(ErrorCode::kUnsupported, "cannot " + what + " " + path + ": " + why);
    return *m;
}
}  // namespace

std::string image_format_of(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty()) ext.erase(0, 1);
    return ext;
}

StillImage read_still_image(const std::string& path) {
    const ImageModule& m = module_for("read", path);
    StillImage img;
    if (std::string why = m.read_image(path, img); !why.empty()) throw Error(ErrorCode::kIo, why);
    return img;
}

void write_still_image(const std::string& path, const StillImage& img) {
    const ImageModule& m = module_for("write", path);
    OutputFile file(path);
    if (std::string why = m.write_image(file.write_path(), image_format_of(path), img); !why.empty())
        throw Error(ErrorCode::kIo, "cannot write " + path + ": " + why);
    file.commit();
}

}  // namespace filmgrain::cli

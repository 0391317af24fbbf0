#include "image_module.hpp"

#ifdef FILMGRAIN_IMAGE_MODULE_NAME
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>
#endif

namespace filmgrain::cli {

#ifndef FILMGRAIN_IMAGE_MODULE_NAME
const ImageModule* image_module(std::string* why) {
    if (why) *why = "this build of filmgrain has no OpenImageIO (stills and plots)";
    return nullptr;
}
#else
namespace {

struct Loaded {
    const ImageModule* module = nullptr;
    std::string why;
};

// Beside the executable (the build tree), then where `cmake --install` puts it relative to
// the installed executable; FILMGRAIN_IMAGE_MODULE names a file that overrides both.
Loaded load() {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("FILMGRAIN_IMAGE_MODULE"); env && *env) {
        candidates.push_back(env);
    } else {
        std::error_code ec;
        const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec) {
            candidates.push_back((exe.parent_path() / FILMGRAIN_IMAGE_MODULE_NAME).string());
            candidates.push_back(
                (exe.parent_path() / FILMGRAIN_IMAGE_MODULE_DIR_FROM_BINDIR / FILMGRAIN_IMAGE_MODULE_NAME)
                    .lexically_normal()
                    .string());
        }
    }
    Loaded r;
    r.why = "the image module " FILMGRAIN_IMAGE_MODULE_NAME " (OpenImageIO) could not be loaded:";
    for (const std::string& path : candidates) {
        if (!std::filesystem::exists(path)) {
            r.why += " " + path + " does not exist;";
            continue;
        }
        // kept loaded once its table is in use: the table lives as long as the process
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            r.why += " " + std::string(dlerror()) + ";";
            continue;
        }
        using Entry = const ImageModule* (*)(int);
        const auto entry = reinterpret_cast<Entry>(dlsym(handle, "filmgrain_image_module"));
        const ImageModule* m = entry ? entry(kImageModuleVersion) : nullptr;
        if (!m) {
            dlclose(handle);
            r.why += " " + path + " is not this build's module (interface version " +
                     std::to_string(kImageModuleVersion) + ");";
            continue;
        }
        r.module = m;
        r.why.clear();
        return r;
    }
    r.why.pop_back();
    return r;
}

}  // namespace

const ImageModule* image_module(std::string* why) {
    static const Loaded loaded = load();  // once per process, thread-safe
    if (!loaded.module && why) *why = loaded.why;
    return loaded.module;
}
#endif

}  // namespace filmgrain::cli

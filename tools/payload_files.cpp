#include "payload_files.hpp"

#include <cstdio>
#include <filesystem>

#include "filmgrain/error.hpp"
#include "io/xz_file.hpp"

namespace filmgrain::cli {

std::string format_pattern(const std::string& pattern, int k) {
    // Exactly one conversion, and it must be an integer one.
    const auto pos = pattern.find('%');
    if (pos == std::string::npos || pattern.find('%', pos + 1) != std::string::npos ||
        pattern.find_first_of("dui", pos) == std::string::npos ||
        pattern.find_first_not_of("0123456789", pos + 1) != pattern.find_first_of("dui", pos))
        throw Error(ErrorCode::kInvalidArgument,
                    "file pattern '" + pattern + "' must hold exactly one %d (optionally %0Nd)");
    char name[4096];
    std::snprintf(name, sizeof name, pattern.c_str(), k);
    return name;
}

PayloadFiles::PayloadFiles(std::vector<std::string> files) : files_(std::move(files)) {
    pattern_ = files_.size() == 1 && files_[0].find('%') != std::string::npos;
    if (pattern_) {
        format_pattern(files_[0], 0);  // validates
        return;
    }
    for (const auto& f : files_) fixed_.push_back(read_whole_file(f));
}

std::string PayloadFiles::name_for(int k) const {
    if (pattern_) return format_pattern(files_[0], k);
    if (fixed_.size() == 1) return files_[0];
    return std::size_t(k) < files_.size() ? files_[std::size_t(k)] : std::string();
}

std::optional<std::vector<uint8_t>> PayloadFiles::for_picture(int k) const {
    if (pattern_) {
        const std::string name = format_pattern(files_[0], k);
        if (!std::filesystem::exists(name)) return std::nullopt;
        return read_whole_file(name);
    }
    if (fixed_.size() == 1) return fixed_[0];
    if (std::size_t(k) < fixed_.size()) return fixed_[std::size_t(k)];
    return std::nullopt;
}

std::vector<std::vector<uint8_t>> PayloadFiles::all() const {
    if (!pattern_) return fixed_;
    std::vector<std::vector<uint8_t>> out;
    for (int k = 0;; ++k) {
        auto p = for_picture(k);
        if (!p) break;
        out.push_back(std::move(*p));
    }
    return out;
}

}  // namespace filmgrain::cli

#include "io/payload_files.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "filmgrain/error.hpp"

namespace filmgrain::io {

std::vector<uint8_t> read_payload_file(const std::string& path) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw Error(ErrorCode::kIo, "cannot open payload file '" + path + "': " + std::strerror(errno));
    std::vector<uint8_t> out;
    uint8_t buf[1 << 14];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) {
        if (out.size() + n > kMaxPayloadFileBytes)
            throw Error(ErrorCode::kInvalidParams, "payload file '" + path + "' is larger than " +
                                                       std::to_string(kMaxPayloadFileBytes) +
                                                       " bytes, the most an SEI or T.35 payload file may have");
        out.insert(out.end(), buf, buf + n);
    }
    if (std::ferror(f.get())) throw Error(ErrorCode::kIo, "read error on '" + path + "': " + std::strerror(errno));
    return out;
}

PayloadFiles::PayloadFiles(std::vector<std::string> files) : files_(std::move(files)) {
    if (files_.size() == 1) pattern_ = FilePattern::parse(files_[0]);
    if (pattern_) return;
    for (const auto& f : files_) fixed_.push_back(read_payload_file(f));
}

std::string PayloadFiles::name_for(int k) const {
    if (pattern_) return pattern_->name_for(k);
    if (fixed_.size() == 1) return files_[0];
    return std::size_t(k) < files_.size() ? files_[std::size_t(k)] : std::string();
}

std::optional<std::vector<uint8_t>> PayloadFiles::for_picture(int k) const {
    if (pattern_) {
        const std::string name = pattern_->name_for(k);
        if (!std::filesystem::exists(name)) return std::nullopt;
        return read_payload_file(name);
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

}  // namespace filmgrain::io

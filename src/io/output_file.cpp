#include "io/output_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "filmgrain/error.hpp"

namespace filmgrain {

bool is_stream_target(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    return !ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st) &&
           !std::filesystem::is_directory(st);
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
    direct_ = is_stdout() || is_stream_target(path_);
    if (direct_) {
        write_path_ = path_;
        return;
    }
    const std::filesystem::path p(path_);
    write_path_ = (p.parent_path() / (".filmgrain-partial-" + std::to_string(::getpid()) + "-" + p.filename().string()))
                      .string();
}

OutputFile::~OutputFile() {
    if (stream_ && stream_ != stdout) std::fclose(stream_);  // before its file is removed
    if (!direct_ && !committed_) std::remove(write_path_.c_str());
}

std::FILE* OutputFile::stream() {
    if (stream_) return stream_;
    stream_ = is_stdout() ? stdout : std::fopen(write_path_.c_str(), "wb");
    if (!stream_)
        throw Error(ErrorCode::kIo, "cannot open '" + path_ + "' for writing: " + std::strerror(errno));
    return stream_;
}

void OutputFile::commit() {
    if (stream_) {
        bool ok = std::fflush(stream_) == 0 && !std::ferror(stream_);
        if (stream_ != stdout) ok = std::fclose(stream_) == 0 && ok;
        stream_ = nullptr;
        if (!ok) throw Error(ErrorCode::kIo, "write error on '" + path_ + "'");  // the destructor removes it
    }
    if (!direct_ && std::rename(write_path_.c_str(), path_.c_str()) != 0) {
        const int err = errno;
        std::remove(write_path_.c_str());
        throw Error(ErrorCode::kIo, "cannot rename output into '" + path_ + "': " + std::strerror(err));
    }
    committed_ = true;
}

}  // namespace filmgrain

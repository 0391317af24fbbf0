#include "libav/stream_window.hpp"

#include <algorithm>
#include <cstring>

#include "filmgrain/error.hpp"

extern "C" {
#include <libavformat/avio.h>
#include <libavutil/error.h>
#include <libavutil/mem.h>
}

namespace filmgrain::libav {

namespace {
constexpr int kBufferSize = 1 << 16;
}

StreamWindowReader::StreamWindowReader(const std::string& path, StreamWindow window) : window_(std::move(window)) {
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) throw Error(ErrorCode::kIo, "cannot open '" + path + "': " + std::strerror(errno));
    if (fseeko(file_, 0, SEEK_END) == 0) file_size_ = ftello(file_);
    if (window_.offset < 0 || window_.offset > file_size_) {
        std::fclose(file_);
        throw Error(ErrorCode::kIo, "'" + path + "': offset " + std::to_string(window_.offset) + " lies beyond its " +
                                        std::to_string(file_size_) + " bytes");
    }
    auto* buffer = static_cast<uint8_t*>(av_malloc(kBufferSize));
    io_ = buffer ? avio_alloc_context(buffer, kBufferSize, 0, this, &StreamWindowReader::read, nullptr,
                                      &StreamWindowReader::seek)
                 : nullptr;
    if (!io_) {
        av_free(buffer);
        std::fclose(file_);
        throw Error(ErrorCode::kOutOfMemory, "avio_alloc_context failed");
    }
}

StreamWindowReader::~StreamWindowReader() {
    if (io_) av_freep(&io_->buffer);
    avio_context_free(&io_);
    if (file_) std::fclose(file_);
}

int StreamWindowReader::read(void* opaque, uint8_t* buf, int size) {
    auto& r = *static_cast<StreamWindowReader*>(opaque);
    const auto prefix = int64_t(r.window_.prefix.size());
    int done = 0;
    if (r.pos_ < prefix) {
        done = int(std::min<int64_t>(size, prefix - r.pos_));
        std::memcpy(buf, r.window_.prefix.data() + r.pos_, std::size_t(done));
        r.pos_ += done;
    }
    if (done < size) {
        if (fseeko(r.file_, r.window_.offset + (r.pos_ - prefix), SEEK_SET) != 0) return done ? done : AVERROR(EIO);
        const std::size_t got = std::fread(buf + done, 1, std::size_t(size - done), r.file_);
        if (got == 0 && std::ferror(r.file_)) return done ? done : AVERROR(EIO);
        done += int(got);
        r.pos_ += int64_t(got);
    }
    return done ? done : AVERROR_EOF;
}

int64_t StreamWindowReader::seek(void* opaque, int64_t pos, int whence) {
    auto& r = *static_cast<StreamWindowReader*>(opaque);
    const int64_t size = int64_t(r.window_.prefix.size()) + (r.file_size_ - r.window_.offset);
    if (whence & AVSEEK_SIZE) return size;
    whence &= ~AVSEEK_FORCE;
    const int64_t base = whence == SEEK_CUR ? r.pos_ : whence == SEEK_END ? size : 0;
    if (whence != SEEK_SET && whence != SEEK_CUR && whence != SEEK_END) return AVERROR(EINVAL);
    const int64_t to = base + pos;
    if (to < 0 || to > size) return AVERROR(EINVAL);
    r.pos_ = to;
    return to;
}

}  // namespace filmgrain::libav

// A decoder's input that starts part-way into a file: a few bytes of our own (an IVF file
// header, the parameter sets the skipped part held) followed by the file from an offset, read
// as one stream by libavformat through its custom I/O. Decoding a range of a coded stream
// then starts at a random access point instead of at the stream's start (decode_restart.hpp).
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

struct AVIOContext;

namespace filmgrain::libav {

struct StreamWindow {
    std::vector<uint8_t> prefix;  // read first
    int64_t offset = 0;           // then the file from this byte on
};

// The custom I/O of one window. Throws Error(kIo) naming the file when it cannot be opened
// or the offset lies beyond its end.
class StreamWindowReader {
public:
    StreamWindowReader(const std::string& path, StreamWindow window);
    ~StreamWindowReader();
    StreamWindowReader(const StreamWindowReader&) = delete;
    StreamWindowReader& operator=(const StreamWindowReader&) = delete;

    AVIOContext* io() const { return io_; }

private:
    static int read(void* opaque, uint8_t* buf, int size);
    static int64_t seek(void* opaque, int64_t pos, int whence);
    std::FILE* file_ = nullptr;
    StreamWindow window_;
    int64_t file_size_ = 0;
    int64_t pos_ = 0;  // in the window: prefix, then the file from window_.offset
    AVIOContext* io_ = nullptr;
};

}  // namespace filmgrain::libav

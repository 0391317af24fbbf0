// Y4M stream and frame headers (src/io/y4m_header), and the reader on top of them. The
// input's first line is a stream header; every header that parses must lie within the
// documented limits and read back the same from the form the writer gives it. The
// following lines are frame headers. Then the whole input is read as a file through
// VideoReader (a memfd: a regular file, so frame sizes are checked against it before
// anything is allocated), a few frames at most.
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "filmgrain/error.hpp"
#include "io/video_file.hpp"
#include "io/y4m_header.hpp"

namespace {

void check(bool ok) {
    if (!ok) std::abort();
}

std::string writer_form(const filmgrain::Y4mHeader& h) {
    std::string s = "YUV4MPEG2 W" + std::to_string(h.width) + " H" + std::to_string(h.height);
    if (h.fps_num) s += " F" + std::to_string(h.fps_num) + ":" + std::to_string(h.fps_den);
    return s + h.extra + " C" + filmgrain::y4m_colorspace_tag(h.format);
}

void stream_header(std::string_view line) {
    filmgrain::Y4mHeader h;
    try {
        h = filmgrain::parse_y4m_header(line);
    } catch (const filmgrain::Error&) {
        return;
    }
    check(h.width >= 1 && h.width <= filmgrain::kMaxPictureDimension);
    check(h.height >= 1 && h.height <= filmgrain::kMaxPictureDimension);
    check(static_cast<long long>(h.width) * h.height <= filmgrain::kMaxPictureSamples);
    check(h.format.bit_depth >= 8 && h.format.bit_depth <= 16);
    check((h.fps_num == 0) == (h.fps_den == 0) && h.fps_num >= 0 && h.fps_den >= 0);
    filmgrain::Y4mHeader again;
    try {
        again = filmgrain::parse_y4m_header(writer_form(h));
    } catch (const filmgrain::Error&) {
        std::abort();  // what the writer writes must read back
    }
    check(again.width == h.width && again.height == h.height && again.fps_num == h.fps_num &&
          again.fps_den == h.fps_den && again.format.chroma == h.format.chroma &&
          again.format.bit_depth == h.format.bit_depth && again.extra == h.extra);
}

void through_reader(const uint8_t* data, std::size_t size) {
    const int fd = ::memfd_create("y4m", MFD_CLOEXEC);
    if (fd < 0) return;
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, data + done, size - done);
        if (n <= 0) break;
        done += std::size_t(n);
    }
    try {
        filmgrain::VideoReader reader("/proc/self/fd/" + std::to_string(fd), filmgrain::VideoInfo{});
        filmgrain::FrameBuffer frame;
        for (int k = 0; k < 4 && reader.read(frame); k++)
            check(frame.byte_size() == filmgrain::FrameBuffer::frame_bytes(reader.info().width, reader.info().height,
                                                                           reader.info().format));
    } catch (const filmgrain::Error&) {
    }
    ::close(fd);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view all(reinterpret_cast<const char*>(data), size);
    std::size_t nl = all.find('\n');
    stream_header(all.substr(0, nl));
    for (int lines = 0; nl != std::string_view::npos && lines < 16; lines++) {
        const std::size_t start = nl + 1;
        nl = all.find('\n', start);
        try {
            filmgrain::parse_y4m_frame_header(all.substr(start, nl == std::string_view::npos ? nl : nl - start));
        } catch (const filmgrain::Error&) {
        }
    }
    through_reader(data, size);
    return 0;
}

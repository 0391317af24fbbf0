#include "io/video_file.hpp"

#include <limits.h>
#include <unistd.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain {

bool has_y4m_extension(const std::string& p) {
    return p.size() >= 4 && (p.compare(p.size() - 4, 4, ".y4m") == 0 || p.compare(p.size() - 4, 4, ".Y4M") == 0);
}

namespace {
// Files hold 16-bit samples little-endian; memory holds them in host order.
[[maybe_unused]] void swap_bytes_16(uint8_t* p, std::size_t n) {
    for (std::size_t i = 0; i + 1 < n; i += 2) std::swap(p[i], p[i + 1]);
}

std::string frame_description(const VideoInfo& info) {
    return std::to_string(info.width) + "x" + std::to_string(info.height) + " " + pix_fmt_name(info.format);
}

// A 16-bit word above the declared bit depth: the data is not in the format named (a wrong
// --pix-fmt or Y4M C tag, or samples in the high bits of their words, as P010 stores them).
// Refused here, where a file is read anyway: the library does not scan pictures for such
// samples (a pass over every picture) and blends them as the references' integers do, as
// unsigned 16-bit values, which is rarely what was meant.
void check_sample_range(FrameBuffer& frame, const std::string& path, int index) {
    const std::optional<SampleAboveBitDepth> above = find_sample_above_bit_depth(frame.view());
    if (!above) return;
    const int bit_depth = frame.format().bit_depth;
    throw Error(ErrorCode::kInvalidArgument,
                "'" + path + "' frame " + std::to_string(index) + ": " + plane_name(above->plane) + " sample " +
                    std::to_string(above->value) + " at x " + std::to_string(above->x) + ", y " +
                    std::to_string(above->y) + " is above the " + std::to_string(bit_depth) + "-bit range 0.." +
                    std::to_string((1u << bit_depth) - 1) + ": is the data " + pix_fmt_name(frame.format()) +
                    "? (each sample in the low " + std::to_string(bit_depth) +
                    " bits of a little-endian 16-bit word; data in the high bits, as P010 stores it, "
                    "reads as values up to 65535)");
}
}  // namespace

std::optional<SampleAboveBitDepth> find_sample_above_bit_depth(const FrameView& v) {
    if (v.bit_depth <= 8 || v.bit_depth >= 16) return std::nullopt;
    const unsigned max_value = (1u << v.bit_depth) - 1;
    std::optional<SampleAboveBitDepth> first;
    for (int p = 0; p < v.plane_count(); p++)
        for (int y = 0; y < v.planes[p].height; y++) {
            const uint16_t* row = v.planes[p].row<const uint16_t>(y);
            unsigned any = 0;
            for (int x = 0; x < v.planes[p].width; x++) any |= row[x];
            if (any <= max_value) continue;
            for (int x = 0; x < v.planes[p].width; x++) {
                if (row[x] <= max_value) continue;
                if (!first) first = SampleAboveBitDepth{p, x, y, row[x], 0};
                first->count++;
            }
        }
    return first;
}

VideoReader::VideoReader(const std::string& path, const VideoInfo& raw_info, bool force_raw) : path_(path) {
    in_ = std::make_unique<InputFile>(path);
    info_ = raw_info;
    info_.y4m = false;
    if (!force_raw && (in_->peek() == 'Y' || has_y4m_extension(path))) {
        read_y4m_header();
        return;
    }
    if (info_.width <= 0 || info_.height <= 0)
        throw Error(ErrorCode::kInvalidArgument, "raw input '" + path + "' needs --size WxH and --pix-fmt");
    try {
        check_picture_size(info_.width, info_.height);
    } catch (const Error& e) {
        throw Error(e.code(), "raw input '" + path + "': " + e.what());
    }
}

VideoReader::~VideoReader() = default;

void VideoReader::read_y4m_header() {
    std::string line;
    int c;
    while ((c = in_->get()) >= 0 && c != '\n') {
        line.push_back(char(c));
        if (line.size() > kMaxY4mHeaderBytes)
            throw Error(ErrorCode::kIo, "Y4M header of '" + path_ + "' is longer than " +
                                            std::to_string(kMaxY4mHeaderBytes) + " bytes");
    }
    if (line.rfind("YUV4MPEG2", 0) != 0)
        throw Error(ErrorCode::kIo, "'" + path_ + "' has a .y4m name but no YUV4MPEG2 header");
    if (c < 0) throw Error(ErrorCode::kIo, "'" + path_ + "' ends inside its Y4M header");
    Y4mHeader h;
    try {
        h = parse_y4m_header(line);
    } catch (const Error& e) {
        throw Error(ErrorCode::kIo, "'" + path_ + "': " + e.what());
    }
    info_.y4m = true;
    info_.width = h.width;
    info_.height = h.height;
    info_.format = h.format;
    if (h.fps_num > 0) {
        info_.fps_num = h.fps_num;
        info_.fps_den = h.fps_den;
    }
    info_.y4m_extra = h.extra;
}

long long frame_count_from_size(const std::string& path, const VideoInfo& info) {
    if (path == "-") return -1;
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) return -1;
    const std::size_t fb = FrameBuffer::frame_bytes(info.width, info.height, info.format);
    return (long long)(size / (fb + (info.y4m ? 6 : 0)));
}

// A Y4M frame's "FRAME..." line: false at a clean end of the file; throws on a malformed
// line or one the file ends in.
bool VideoReader::read_y4m_frame_line() {
    int c = in_->get();
    if (c < 0) return false;
    std::string line(1, char(c));
    while ((c = in_->get()) >= 0 && c != '\n') {
        line.push_back(char(c));
        if (line.size() > kMaxY4mHeaderBytes) break;
    }
    try {
        parse_y4m_frame_header(line);
    } catch (const Error& e) {
        throw Error(ErrorCode::kIo, "'" + path_ + "': frame " + std::to_string(frames_) + ": " + e.what());
    }
    if (c < 0)
        throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " has no data");
    return true;
}

bool VideoReader::skip_frames(int n) {
    const std::size_t bytes = FrameBuffer::frame_bytes(info_.width, info_.height, info_.format);
    for (int i = 0; i < n; i++) {
        if (info_.y4m && !read_y4m_frame_line()) return false;
        if (in_->skip(bytes) != bytes) {
            if (!info_.y4m) return false;
            throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " is incomplete");
        }
        frames_++;
    }
    return true;
}

bool VideoReader::read(FrameBuffer& frame) {
    if (info_.y4m && !read_y4m_frame_line()) return false;
    const std::size_t want = FrameBuffer::frame_bytes(info_.width, info_.height, info_.format);
    // A regular file tells how much it holds: a frame it cannot hold fails here, before the
    // frame is allocated.
    if (const auto left = in_->remaining()) {
        if (*left == 0 && !info_.y4m) return false;
        if (*left < want) {
            if (frames_ == 0)
                throw Error(ErrorCode::kIo, "'" + path_ + "' holds " + std::to_string(*left) + " bytes" +
                                                (info_.y4m ? " of frame data" : "") + ", less than one " +
                                                frame_description(info_) + " frame (" + std::to_string(want) +
                                                " bytes)");
            throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " has " +
                                            std::to_string(*left) + " of " + std::to_string(want) + " bytes (" +
                                            frame_description(info_) + ")");
        }
    }
    if (frame.width() != info_.width || frame.height() != info_.height ||
        frame.format().chroma != info_.format.chroma || frame.format().bit_depth != info_.format.bit_depth)
        frame = FrameBuffer::uninitialized(info_.width, info_.height, info_.format);
    const std::size_t got = in_->read(frame.bytes(), want);
    if (got == 0 && !info_.y4m) return false;
    if (got != want)
        throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " has " +
                                        std::to_string(got) + " of " + std::to_string(want) + " bytes (" +
                                        frame_description(info_) + ")");
    if constexpr (std::endian::native == std::endian::big)
        if (info_.format.bit_depth > 8) swap_bytes_16(frame.bytes(), want);
    if (!keep_above_bit_depth_) check_sample_range(frame, path_, frames_);
    frames_++;
    return true;
}

VideoWriter::VideoWriter(const std::string& path, const VideoInfo& info, bool y4m)
    : out_(path), info_(info), y4m_(y4m) {
    f_ = out_.stream();
    if (y4m_) {
        std::string hdr = "YUV4MPEG2 W" + std::to_string(info.width) + " H" + std::to_string(info.height) + " F" +
                          std::to_string(info.fps_num) + ":" + std::to_string(info.fps_den) +
                          (info.y4m_extra.empty() ? std::string(" Ip A1:1") : info.y4m_extra) + " C" +
                          y4m_colorspace_tag(info.format) + "\n";
        std::fwrite(hdr.data(), 1, hdr.size(), f_);
    }
}

namespace {

// A clip holds one size and format: a picture of another would write bytes a reader splits
// into the wrong pictures.
void check_frame_fits(const std::string& path, const VideoInfo& info, int width, int height, PixelFormat format) {
    if (width == info.width && height == info.height && format.chroma == info.format.chroma &&
        format.bit_depth == info.format.bit_depth)
        return;
    throw Error(ErrorCode::kInvalidArgument, "a " + std::to_string(width) + "x" + std::to_string(height) + " " +
                                                 pix_fmt_name(format) + " picture for '" + path + "', which holds " +
                                                 std::to_string(info.width) + "x" + std::to_string(info.height) + " " +
                                                 pix_fmt_name(info.format));
}

}  // namespace

void VideoWriter::write(const FrameBuffer& frame) {
    check_frame_fits(out_.path(), info_, frame.width(), frame.height(), frame.format());
    if (y4m_) std::fwrite("FRAME\n", 1, 6, f_);
    bool ok;
    if (std::endian::native == std::endian::big && frame.format().bit_depth > 8) {
        std::vector<uint8_t> le(frame.bytes(), frame.bytes() + frame.byte_size());
        swap_bytes_16(le.data(), le.size());
        ok = std::fwrite(le.data(), 1, le.size(), f_) == le.size();
    } else {
        ok = std::fwrite(frame.bytes(), 1, frame.byte_size(), f_) == frame.byte_size();
    }
    if (!ok) throw Error(ErrorCode::kIo, "write error on '" + out_.path() + "': " + std::strerror(errno));
}

void VideoWriter::write(const FrameView& frame) {
    check_frame_fits(out_.path(), info_, frame.width, frame.height, PixelFormat{frame.format, frame.bit_depth});
    const int bps = frame.bytes_per_sample();
    if (std::endian::native == std::endian::big && bps > 1) {
        FrameBuffer packed(frame.width, frame.height, PixelFormat{frame.format, frame.bit_depth});
        copy_frame(frame, packed.view());
        return write(packed);
    }
    if (y4m_) std::fwrite("FRAME\n", 1, 6, f_);
    if (std::fflush(f_) != 0) throw Error(ErrorCode::kIo, "write error on '" + out_.path() + "': " + std::strerror(errno));
    // One gathering write per IOV_MAX rows, straight from the picture's rows.
    std::vector<iovec>& rows = rows_;
    rows.clear();
    for (int p = 0; p < frame.plane_count(); p++) {
        const std::size_t row_bytes = std::size_t(plane_width(frame.format, p, frame.width)) * std::size_t(bps);
        for (int y = 0; y < plane_height(frame.format, p, frame.height); y++)
            rows.push_back(iovec{frame.planes[p].row<uint8_t>(y), row_bytes});
    }
    const int fd = fileno(f_);
    std::size_t i = 0;
    while (i < rows.size()) {
        const int count = int(std::min<std::size_t>(rows.size() - i, IOV_MAX));
        const ssize_t n = ::writev(fd, rows.data() + i, count);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(ErrorCode::kIo, "write error on '" + out_.path() + "': " + std::strerror(errno));
        }
        // Skip what was written; a partial write leaves the rest of a row for the next call.
        std::size_t done = std::size_t(n);
        while (done > 0 && i < rows.size()) {
            if (done >= rows[i].iov_len) {
                done -= rows[i].iov_len;
                i++;
            } else {
                rows[i].iov_base = static_cast<uint8_t*>(rows[i].iov_base) + done;
                rows[i].iov_len -= done;
                done = 0;
            }
        }
    }
}

void VideoWriter::commit() {
    f_ = nullptr;
    out_.commit();
}

}  // namespace filmgrain

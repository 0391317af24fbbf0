#include "io/video_file.hpp"

#include <limits.h>
#include <unistd.h>

#include <bit>
#include <cctype>
#include <cstring>
#include <utility>
#include <sstream>
#include <vector>

#include "filmgrain/error.hpp"

namespace filmgrain {

bool has_y4m_extension(const std::string& p) {
    return p.size() >= 4 && (p.compare(p.size() - 4, 4, ".y4m") == 0 || p.compare(p.size() - 4, 4, ".Y4M") == 0);
}

std::string y4m_colorspace_tag(const PixelFormat& f) {
    std::string base = f.chroma == ChromaFormat::k400   ? "mono"
                       : f.chroma == ChromaFormat::k420 ? "420"
                       : f.chroma == ChromaFormat::k422 ? "422"
                                                        : "444";
    if (f.bit_depth == 8) return f.chroma == ChromaFormat::k420 ? "420jpeg" : base;
    return base + "p" + std::to_string(f.bit_depth);
}

namespace {
// Files hold 16-bit samples little-endian; memory holds them in host order.
[[maybe_unused]] void swap_bytes_16(uint8_t* p, std::size_t n) {
    for (std::size_t i = 0; i + 1 < n; i += 2) std::swap(p[i], p[i + 1]);
}

PixelFormat parse_y4m_colorspace(const std::string& c) {
    PixelFormat f;
    std::string base = c;
    int bd = 8;
    auto p = c.find('p');
    if (c.rfind("mono", 0) == 0) {
        f.chroma = ChromaFormat::k400;
        if (c.size() > 4) bd = std::atoi(c.c_str() + 4);
    } else {
        if (c.rfind("420", 0) == 0) f.chroma = ChromaFormat::k420;
        else if (c.rfind("422", 0) == 0) f.chroma = ChromaFormat::k422;
        else if (c.rfind("444", 0) == 0) f.chroma = ChromaFormat::k444;
        else throw Error(ErrorCode::kIo, "Y4M colour space C" + c + " is not supported (allowed 420*, 422*, 444*, mono*)");
        if (p != std::string::npos && p + 1 < c.size() && std::isdigit((unsigned char)c[p + 1])) bd = std::atoi(c.c_str() + p + 1);
        if (c == "444alpha") throw Error(ErrorCode::kIo, "Y4M colour space C444alpha is not supported");
    }
    if (bd != 8 && bd != 9 && bd != 10 && bd != 12 && bd != 14 && bd != 16)
        throw Error(ErrorCode::kIo, "Y4M colour space C" + c + " has bit depth " + std::to_string(bd) + " (allowed 8..16)");
    f.bit_depth = bd;
    return f;
}
}  // namespace

VideoReader::VideoReader(const std::string& path, const VideoInfo& raw_info, bool force_raw) : path_(path) {
    if (path == "-") {
        f_ = stdin;
    } else {
        f_ = std::fopen(path.c_str(), "rb");
        if (!f_) throw Error(ErrorCode::kIo, "cannot open input '" + path + "': " + std::strerror(errno));
        owns_ = true;
    }
    info_ = raw_info;
    info_.y4m = false;
    if (!force_raw) {
        int c = std::fgetc(f_);
        if (c != EOF) std::ungetc(c, f_);
        if (c == 'Y' || has_y4m_extension(path)) {
            parse_y4m_header();
            return;
        }
    }
    if (info_.width <= 0 || info_.height <= 0)
        throw Error(ErrorCode::kInvalidArgument, "raw input '" + path + "' needs --size WxH and --pix-fmt");
}

VideoReader::~VideoReader() {
    if (owns_ && f_) std::fclose(f_);
}

void VideoReader::parse_y4m_header() {
    std::string line;
    int c;
    while ((c = std::fgetc(f_)) != EOF && c != '\n') {
        line.push_back(char(c));
        if (line.size() > 4096) throw Error(ErrorCode::kIo, "Y4M header of '" + path_ + "' is longer than 4096 bytes");
    }
    if (line.rfind("YUV4MPEG2", 0) != 0)
        throw Error(ErrorCode::kIo, "'" + path_ + "' has a .y4m name but no YUV4MPEG2 header");
    std::istringstream ss(line.substr(9));
    std::string tok;
    info_.y4m = true;
    info_.width = info_.height = 0;
    info_.format = PixelFormat{ChromaFormat::k420, 8};
    info_.y4m_extra.clear();
    while (ss >> tok) {
        switch (tok[0]) {
            case 'W': info_.width = std::atoi(tok.c_str() + 1); break;
            case 'H': info_.height = std::atoi(tok.c_str() + 1); break;
            case 'C': info_.format = parse_y4m_colorspace(tok.substr(1)); break;
            case 'F': {
                int n = 0, d = 0;
                if (std::sscanf(tok.c_str() + 1, "%d:%d", &n, &d) == 2 && n > 0 && d > 0) {
                    info_.fps_num = n;
                    info_.fps_den = d;
                }
                break;
            }
            default: info_.y4m_extra += " " + tok; break;
        }
    }
    if (info_.width <= 0 || info_.height <= 0 || info_.width > 65536 || info_.height > 65536)
        throw Error(ErrorCode::kIo, "Y4M header of '" + path_ + "' has an invalid size " + std::to_string(info_.width) +
                                        "x" + std::to_string(info_.height));
}

bool VideoReader::read(FrameBuffer& frame) {
    if (info_.y4m) {
        char hdr[6];
        std::size_t n = std::fread(hdr, 1, 5, f_);
        if (n == 0) return false;
        if (n < 5 || std::memcmp(hdr, "FRAME", 5) != 0)
            throw Error(ErrorCode::kIo, "'" + path_ + "': frame " + std::to_string(frames_) + " does not start with FRAME");
        int c;
        int guard = 0;
        while ((c = std::fgetc(f_)) != EOF && c != '\n')
            if (++guard > 4096) throw Error(ErrorCode::kIo, "'" + path_ + "': FRAME header too long");
        if (c == EOF)
            throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " has no data");
    }
    if (frame.width() != info_.width || frame.height() != info_.height ||
        frame.format().chroma != info_.format.chroma || frame.format().bit_depth != info_.format.bit_depth)
        frame = FrameBuffer(info_.width, info_.height, info_.format);
    const std::size_t want = frame.byte_size();
    std::size_t got = std::fread(frame.bytes(), 1, want, f_);
    if (got == 0 && !info_.y4m) return false;
    if (got != want)
        throw Error(ErrorCode::kIo, "'" + path_ + "' is truncated: frame " + std::to_string(frames_) + " has " +
                                        std::to_string(got) + " of " + std::to_string(want) + " bytes (" +
                                        std::to_string(info_.width) + "x" + std::to_string(info_.height) + " " +
                                        pix_fmt_name(info_.format) + ")");
    if constexpr (std::endian::native == std::endian::big)
        if (info_.format.bit_depth > 8) swap_bytes_16(frame.bytes(), want);
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

void VideoWriter::write(const FrameBuffer& frame) {
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

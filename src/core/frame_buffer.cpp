#include "core/frame_buffer.hpp"

#include <algorithm>
#include <cstring>

#include "filmgrain/error.hpp"

namespace filmgrain {

PixelFormat parse_pix_fmt(const std::string& name) {
    struct Entry { const char* name; ChromaFormat c; int bd; };
    static const Entry kTable[] = {
        {"gray", ChromaFormat::k400, 8},        {"gray10le", ChromaFormat::k400, 10},
        {"gray12le", ChromaFormat::k400, 12},   {"gray16le", ChromaFormat::k400, 16},
        {"yuv420p", ChromaFormat::k420, 8},     {"yuv420p10le", ChromaFormat::k420, 10},
        {"yuv420p12le", ChromaFormat::k420, 12},{"yuv420p16le", ChromaFormat::k420, 16},
        {"yuv422p", ChromaFormat::k422, 8},     {"yuv422p10le", ChromaFormat::k422, 10},
        {"yuv422p12le", ChromaFormat::k422, 12},{"yuv422p16le", ChromaFormat::k422, 16},
        {"yuv444p", ChromaFormat::k444, 8},     {"yuv444p10le", ChromaFormat::k444, 10},
        {"yuv444p12le", ChromaFormat::k444, 12},{"yuv444p16le", ChromaFormat::k444, 16},
    };
    for (const auto& e : kTable)
        if (name == e.name) return {e.c, e.bd};
    throw Error(ErrorCode::kInvalidArgument,
                "pix_fmt '" + name +
                    "' is not supported (allowed: gray, yuv420p, yuv422p, yuv444p and their 10le/12le/16le forms)");
}

std::string pix_fmt_name(const PixelFormat& f) {
    std::string base = f.chroma == ChromaFormat::k400   ? "gray"
                       : f.chroma == ChromaFormat::k420 ? "yuv420p"
                       : f.chroma == ChromaFormat::k422 ? "yuv422p"
                                                        : "yuv444p";
    if (f.bit_depth == 8) return base;
    return base + std::to_string(f.bit_depth) + "le";
}

std::size_t FrameBuffer::frame_bytes(int width, int height, PixelFormat fmt) {
    std::size_t bps = fmt.bit_depth > 8 ? 2 : 1, total = 0;
    for (int p = 0; p < num_planes(fmt.chroma); p++)
        total += std::size_t(plane_width(fmt.chroma, p, width)) * plane_height(fmt.chroma, p, height) * bps;
    return total;
}

void check_picture_size(int width, int height) {
    if (width <= 0 || height <= 0 || width > kMaxPictureDimension || height > kMaxPictureDimension ||
        (long long)width * height > kMaxPictureSamples)
        throw Error(ErrorCode::kInvalidArgument,
                    "picture size " + std::to_string(width) + "x" + std::to_string(height) +
                        " is out of range (allowed width and height 1.." + std::to_string(kMaxPictureDimension) +
                        " and at most " + std::to_string(kMaxPictureSamples) + " = 2^28 luma samples, e.g. 16384x16384)");
}

FrameBuffer::FrameBuffer(int width, int height, PixelFormat fmt) : FrameBuffer(width, height, fmt, Uninitialized{}) {
    std::fill(bytes_.begin(), bytes_.end(), uint8_t(0));
}

FrameBuffer FrameBuffer::uninitialized(int width, int height, PixelFormat fmt) {
    return FrameBuffer(width, height, fmt, Uninitialized{});
}

FrameBuffer::FrameBuffer(int width, int height, PixelFormat fmt, Uninitialized)
    : width_(width), height_(height), fmt_(fmt) {
    check_picture_size(width, height);
    if (fmt.bit_depth < 8 || fmt.bit_depth > 16)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("bit_depth", fmt.bit_depth, 8, 16));
    std::size_t bps = fmt.bit_depth > 8 ? 2 : 1, off = 0;
    for (int p = 0; p < num_planes(fmt.chroma); p++) {
        offsets_[p] = off;
        off += std::size_t(plane_width(fmt.chroma, p, width)) * plane_height(fmt.chroma, p, height) * bps;
    }
    bytes_.resize(off);  // DefaultInitAllocator: not zero-filled
}

std::size_t FrameBuffer::plane_bytes(int p) const {
    std::size_t bps = fmt_.bit_depth > 8 ? 2 : 1;
    return std::size_t(plane_width(fmt_.chroma, p, width_)) * plane_height(fmt_.chroma, p, height_) * bps;
}

FrameView FrameBuffer::view() {
    FrameView v;
    v.format = fmt_.chroma;
    v.bit_depth = fmt_.bit_depth;
    v.width = width_;
    v.height = height_;
    int bps = fmt_.bit_depth > 8 ? 2 : 1;
    for (int p = 0; p < num_planes(fmt_.chroma); p++) {
        v.planes[p].data = bytes_.data() + offsets_[p];
        v.planes[p].width = plane_width(fmt_.chroma, p, width_);
        v.planes[p].height = plane_height(fmt_.chroma, p, height_);
        v.planes[p].stride = std::ptrdiff_t(v.planes[p].width) * bps;
    }
    return v;
}

void copy_frame(const FrameView& src, const FrameView& dst) {
    for (int p = 0; p < src.plane_count(); p++) {
        // A synthesizer called in place (src == dst) copies nothing.
        if (src.planes[p].data == dst.planes[p].data && src.planes[p].stride == dst.planes[p].stride) continue;
        const std::size_t row_bytes = std::size_t(plane_width(src.format, p, src.width)) * src.bytes_per_sample();
        for (int y = 0; y < plane_height(src.format, p, src.height); y++)
            std::memmove(dst.planes[p].row<uint8_t>(y), src.planes[p].row<const uint8_t>(y), row_bytes);
    }
}

void fill_frame(const FrameView& dst, int value) {
    for (int p = 0; p < dst.plane_count(); p++)
        for (int y = 0; y < dst.planes[p].height; y++) {
            if (dst.bit_depth > 8)
                std::fill_n(dst.planes[p].row<uint16_t>(y), dst.planes[p].width, uint16_t(value));
            else
                std::fill_n(dst.planes[p].row<uint8_t>(y), dst.planes[p].width, uint8_t(value));
        }
}

}  // namespace filmgrain

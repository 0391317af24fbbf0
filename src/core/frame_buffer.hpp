// An owning, tightly packed planar frame, laid out exactly as FFmpeg's raw planar
// pix_fmts (Y, then U, then V), so one frame's bytes are what a .yuv file holds.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "filmgrain/frame.hpp"

namespace filmgrain {

struct PixelFormat {
    ChromaFormat chroma = ChromaFormat::k420;
    int bit_depth = 8;
};

// FFmpeg pix_fmt name <-> format. Accepts gray, gray10le, gray12le, gray16le,
// yuv4{20,22,44}p and their 10/12/16-bit little-endian forms. Throws Error naming the value.
PixelFormat parse_pix_fmt(const std::string& name);
std::string pix_fmt_name(const PixelFormat& f);

class FrameBuffer {
public:
    FrameBuffer() = default;
    FrameBuffer(int width, int height, PixelFormat fmt);

    int width() const { return width_; }
    int height() const { return height_; }
    PixelFormat format() const { return fmt_; }
    std::size_t byte_size() const { return bytes_.size(); }
    uint8_t* bytes() { return bytes_.data(); }
    const uint8_t* bytes() const { return bytes_.data(); }

    FrameView view();
    std::size_t plane_offset(int p) const { return offsets_[p]; }
    std::size_t plane_bytes(int p) const;

    static std::size_t frame_bytes(int width, int height, PixelFormat fmt);

private:
    int width_ = 0, height_ = 0;
    PixelFormat fmt_;
    std::vector<uint8_t> bytes_;
    std::size_t offsets_[3] = {0, 0, 0};
};

// Copies every plane of src into dst (same format and size, any strides; nothing when they
// are the same planes).
void copy_frame(const FrameView& src, const FrameView& dst);

// Sets every sample of every plane of dst to `value` (a flat picture, e.g. the mid-grey one
// grain is calibrated on).
void fill_frame(const FrameView& dst, int value);

}  // namespace filmgrain

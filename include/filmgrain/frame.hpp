// Frame and plane views handed to every synthesis model.
// Samples are uint8_t when bit_depth == 8 and little-endian-in-memory uint16_t
// (host order) when bit_depth > 8, as in FFmpeg's planar pix_fmts. Samples must lie below
// 1 << bit_depth: larger ones are not scanned for, get unspecified grain, and are never used
// to read outside a table.
#pragma once
#include <cstddef>
#include <cstdint>

namespace filmgrain {

enum class ChromaFormat : int { k400 = 0, k420 = 1, k422 = 2, k444 = 3 };

inline int chroma_shift_x(ChromaFormat f) { return (f == ChromaFormat::k420 || f == ChromaFormat::k422) ? 1 : 0; }
inline int chroma_shift_y(ChromaFormat f) { return f == ChromaFormat::k420 ? 1 : 0; }
inline int num_planes(ChromaFormat f) { return f == ChromaFormat::k400 ? 1 : 3; }

// One plane. `stride` is in bytes and may be negative (bottom-up buffers).
struct PlaneView {
    uint8_t* data = nullptr;
    std::ptrdiff_t stride = 0;
    int width = 0;
    int height = 0;

    template <typename T> T* row(int y) const { return reinterpret_cast<T*>(data + stride * y); }
};

struct FrameView {
    ChromaFormat format = ChromaFormat::k420;
    int bit_depth = 8;
    int width = 0;   // luma width
    int height = 0;  // luma height
    PlaneView planes[3];

    int bytes_per_sample() const { return bit_depth > 8 ? 2 : 1; }
    int plane_count() const { return num_planes(format); }
};

// Sizes of plane p for a luma size; chroma rounds up as in FFmpeg (AV_CEIL_RSHIFT).
inline int plane_width(ChromaFormat f, int p, int w) { return p == 0 ? w : (w + chroma_shift_x(f)) >> chroma_shift_x(f); }
inline int plane_height(ChromaFormat f, int p, int h) { return p == 0 ? h : (h + chroma_shift_y(f)) >> chroma_shift_y(f); }

}  // namespace filmgrain

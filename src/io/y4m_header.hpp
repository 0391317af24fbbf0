// YUV4MPEG2 (Y4M) stream and frame headers, parsed from text (no file), strictly: every
// number is digits only and range-checked, and an error (Error(kIo)) names the tag, the
// value and what is allowed.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

#include "core/frame_buffer.hpp"

namespace filmgrain {

// The longest stream or frame header line read (without its newline).
inline constexpr std::size_t kMaxY4mHeaderBytes = 4096;

struct Y4mHeader {
    int width = 0, height = 0;  // W, H: required, within the picture limit (check_picture_size)
    PixelFormat format{ChromaFormat::k420, 8};  // C; absent: 4:2:0 8-bit
    int fps_num = 0, fps_den = 0;  // F n:d, each 1..2^31-1; 0:0 (F absent or F0:0, "unknown")
    // Every other tag (I, A, X..., in order, each with a leading space), carried into a Y4M
    // written from this stream. XYSCSS (FFmpeg's copy of C) is left out: the writer writes C.
    std::string extra;
};

// `line` is the header line without its newline: "YUV4MPEG2" and space-separated tags.
Y4mHeader parse_y4m_header(std::string_view line);

// A frame header line without its newline: "FRAME", optionally followed by space-separated
// tags (which are ignored).
void parse_y4m_frame_header(std::string_view line);

// The C tag value written for a format: 420jpeg, 422, 444, mono for 8-bit; 420p10, 422p12,
// 444p16, mono10, mono12, mono16... above (the names FFmpeg writes and reads).
std::string y4m_colorspace_tag(const PixelFormat& f);

// A C tag value as a format: the above, plus 420mpeg2, 420paldv, 420 and the 9- and 14-bit
// forms, and monopN (what filmgrain wrote before it used FFmpeg's names).
PixelFormat parse_y4m_colorspace(std::string_view value);

}  // namespace filmgrain

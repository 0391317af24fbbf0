// Raw planar YUV and YUV4MPEG2 (Y4M) streams, read and written frame by frame so that a
// file of any length is processed in constant memory. "-" is stdin / stdout.
#pragma once
#include <sys/uio.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/frame_buffer.hpp"
#include "io/input_file.hpp"
#include "io/output_file.hpp"
#include "io/y4m_header.hpp"

namespace filmgrain {

struct VideoInfo {
    int width = 0;
    int height = 0;
    PixelFormat format;
    int fps_num = 25, fps_den = 1;
    bool y4m = false;
    std::string y4m_extra;  // interlacing / aspect / colour-range tags to carry over
};

// The first sample above the bit depth of a picture of 9 to 15 bits (none at 8 or 16 bits),
// and how many there are.
struct SampleAboveBitDepth {
    int plane = 0, x = 0, y = 0;
    unsigned value = 0;
    long long count = 0;
};
std::optional<SampleAboveBitDepth> find_sample_above_bit_depth(const FrameView& picture);

class VideoReader {
public:
    // Raw input needs `raw_info` (size and format); Y4M input (".y4m" or a YUV4MPEG2
    // header) describes itself and `raw_info` is ignored except for fps when absent.
    // The picture size is checked against the limit (check_picture_size) here, before
    // anything is allocated. "-" is standard input.
    VideoReader(const std::string& path, const VideoInfo& raw_info, bool force_raw = false);
    ~VideoReader();
    const VideoInfo& info() const { return info_; }
    // false at a clean end of file; throws Error(kIo) on a truncated frame. A regular file
    // too short for the frame fails before the frame is allocated; `frame` is (re)allocated
    // without zero fill when its size or format differs. Reads wait cancellably on a pipe
    // (ReadCancellation, input_file.hpp).
    bool read(FrameBuffer& frame);
    // Passes over the next n frames without reading their samples (a seek in a regular
    // file): a range of a clip starts where it starts. false when the input ends first.
    bool skip_frames(int n);
    int frames_read() const { return frames_; }
    // read() refuses a sample above the bit depth (the data is not in the format named)
    // unless this is called: a decoder's output under verification may hold such samples,
    // which are then a finding about the decoder (a missing clip), not an input error.
    void keep_samples_above_bit_depth() { keep_above_bit_depth_ = true; }

private:
    void read_y4m_header();
    bool read_y4m_frame_line();
    std::unique_ptr<InputFile> in_;
    std::string path_;
    VideoInfo info_;
    int frames_ = 0;
    bool keep_above_bit_depth_ = false;
};

class VideoWriter {
public:
    // Writes to a temporary file beside `path`; commit() renames it into place. Without
    // commit() (an error) the temporary is removed and `path` is never created (OutputFile;
    // "-" is stdout, and a device or pipe is written directly).
    VideoWriter(const std::string& path, const VideoInfo& info, bool y4m);
    void write(const FrameBuffer& frame);
    // The same bytes from a picture with any strides (e.g. a decoder's own), written row
    // by row without copying it first.
    void write(const FrameView& frame);
    void commit();

private:
    OutputFile out_;
    std::FILE* f_ = nullptr;  // out_.stream()
    VideoInfo info_;
    bool y4m_;
    std::vector<iovec> rows_;  // write(FrameView)'s row list, kept so frames do not allocate
};

bool has_y4m_extension(const std::string& path);
// Frames in a regular file of this format, from its size (Y4M: "FRAME\n" before each frame);
// -1 for standard input or a file whose size cannot be read.
long long frame_count_from_size(const std::string& path, const VideoInfo& info);

}  // namespace filmgrain

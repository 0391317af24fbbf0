// Loading the conformance cases of conformance/ (see conformance/README.md) for the tests:
// case.json, the decompressed clean input, the optional full golden output, and a
// first-difference report that names frame, plane, x, y and both values.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/frame_buffer.hpp"

namespace filmgrain::test_support {

std::string conformance_dir();  // <repo>/conformance
// Case folder names starting with `prefix`, sorted.
std::vector<std::string> list_cases(const std::string& prefix);

struct ConformanceCase {
    std::string name, dir;
    nlohmann::json json;
    int width = 0, height = 0, frames = 0;
    PixelFormat format;
    PixelFormat output_format;  // differs only for vfgs --outdepth 8 cases
    std::vector<uint8_t> input;     // all frames, packed
    std::vector<uint8_t> expected;  // empty unless expected.yuv.xz exists

    std::size_t frame_bytes() const { return FrameBuffer::frame_bytes(width, height, format); }
    std::size_t output_frame_bytes() const { return FrameBuffer::frame_bytes(width, height, output_format); }
    FrameBuffer input_frame(int k) const;
    const nlohmann::json& frame_info(int k) const { return json.at("frames_info").at(std::size_t(k)); }
    std::string expected_md5(int k) const { return frame_info(k).at("expected_md5").get<std::string>(); }
};

// case.json and what it says (size, frames, formats), for the cases whose input is a stream
// (ffmpeg71-*) or that only need the description; `input` and `expected` stay empty.
ConformanceCase load_case_description(const std::string& name);
// The description, the clean input and the full golden output when the case has them.
ConformanceCase load_case(const std::string& name);

// "" when equal; otherwise where the first sample differs, against expected.yuv.xz when
// the case has it.
std::string describe_mismatch(const ConformanceCase& c, int frame, const uint8_t* got, std::size_t bytes);

// Runs a command line; returns its exit status. Output goes to `log` when given.
int run_command(const std::string& cmd, std::string* log = nullptr);

// Makes a FIFO at `fifo`, runs `cmd` (which should write into it) and returns what a reader
// of the FIFO received; *status gets the command's exit status and *still_fifo whether the
// path is still a FIFO afterwards. The reader sees the end of the data only once the command
// is done, whatever the command did with the path (so a replaced FIFO cannot hang the test).
// The FIFO is removed before returning.
std::string read_through_fifo(const std::string& fifo, const std::string& cmd, int* status, bool* still_fifo,
                              std::string* log = nullptr);

}  // namespace filmgrain::test_support

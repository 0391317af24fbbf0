#include "afgs1_case.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/md5.hpp"

namespace filmgrain::test_support {

std::optional<std::vector<uint8_t>> afgs1_payload(const ConformanceCase& c, int k) {
    const std::filesystem::path file = std::filesystem::path(c.dir) / ("afgs1_" + std::to_string(k) + ".bin");
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int run_afgs1_case(const ConformanceCase& c, const SessionOptions& options, bool in_place) {
    Session session(options);
    int mismatches = 0;
    for (int k = 0; k < c.frames; k++) {
        if (const auto payload = afgs1_payload(c, k)) session.receive_afgs1_t35(payload->data(), payload->size());
        FrameBuffer in = c.input_frame(k), out(c.width, c.height, c.format);
        FrameInfo info;
        info.ids.poc = k;
        FrameBuffer& result = in_place ? in : out;
        session.apply(in.view(), result.view(), &info);
        if (md5_hex(result.bytes(), result.byte_size()) != c.expected_md5(k)) {
            mismatches++;
            ADD_FAILURE() << describe_mismatch(c, k, result.bytes(), result.byte_size());
        }
    }
    return mismatches;
}

}  // namespace filmgrain::test_support

// The decoder input that starts part-way into a file (libav/stream_window.hpp): libavformat
// reads the prefix, then the file from the offset, as one stream, and can seek in it.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "filmgrain/error.hpp"
#include "libav/stream_window.hpp"

extern "C" {
#include <libavformat/avio.h>
}

using namespace filmgrain;
using namespace filmgrain::libav;
namespace fs = std::filesystem;

namespace {

fs::path file_with(const std::string& bytes) {
    const fs::path p = fs::temp_directory_path() / ("filmgrain-window-" + std::to_string(::getpid()) + ".bin");
    std::FILE* f = std::fopen(p.c_str(), "wb");
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
    return p;
}

std::string read_all(AVIOContext* io) {
    std::string out;
    char buf[7];  // smaller than the prefix and the rest: reads cross the boundary
    for (int n; (n = avio_read(io, reinterpret_cast<unsigned char*>(buf), sizeof buf)) > 0;) out.append(buf, std::size_t(n));
    return out;
}

}  // namespace

TEST(StreamWindow, PrefixThenTheFileFromTheOffset) {
    const fs::path p = file_with("0123456789abcdefghij");
    StreamWindowReader r(p.string(), StreamWindow{{'H', 'D', 'R'}, 10});
    EXPECT_EQ(avio_size(r.io()), 13);
    EXPECT_EQ(read_all(r.io()), "HDRabcdefghij");
    // back into the prefix, and into the file part
    EXPECT_EQ(avio_seek(r.io(), 1, SEEK_SET), 1);
    EXPECT_EQ(read_all(r.io()), "DRabcdefghij");
    EXPECT_EQ(avio_seek(r.io(), 8, SEEK_SET), 8);
    EXPECT_EQ(read_all(r.io()), "fghij");
    fs::remove(p);
}

TEST(StreamWindow, NoPrefixAndAnOffsetAtTheEnd) {
    const fs::path p = file_with("0123456789");
    {
        StreamWindowReader r(p.string(), StreamWindow{{}, 4});
        EXPECT_EQ(read_all(r.io()), "456789");
    }
    {
        StreamWindowReader r(p.string(), StreamWindow{{'x'}, 10});
        EXPECT_EQ(read_all(r.io()), "x");
    }
    fs::remove(p);
}

TEST(StreamWindow, BadOffsetOrMissingFileIsAnErrorNamingIt) {
    const fs::path p = file_with("0123456789");
    try {
        StreamWindowReader r(p.string(), StreamWindow{{}, 11});
        FAIL() << "offset beyond the end accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("offset 11 lies beyond its 10 bytes"), std::string::npos) << e.what();
    }
    fs::remove(p);
    EXPECT_THROW(StreamWindowReader(p.string(), StreamWindow{{}, 0}), Error);
}

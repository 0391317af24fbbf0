#include "io/xz_file.hpp"

#include <lzma.h>

#include "filmgrain/error.hpp"

namespace filmgrain {

std::vector<uint8_t> read_whole_file(const std::string& path) {
    return read_whole_file(path, kDefaultMaxFileBytes, "a file read whole");
}

std::vector<uint8_t> read_xz_file(const std::string& path) {
    std::vector<uint8_t> in = read_whole_file(path);
    lzma_stream strm = LZMA_STREAM_INIT;
    if (lzma_stream_decoder(&strm, UINT64_MAX, 0) != LZMA_OK)
        throw Error(ErrorCode::kInternal, "lzma_stream_decoder failed");
    std::vector<uint8_t> out;
    uint8_t buf[1 << 16];
    strm.next_in = in.data();
    strm.avail_in = in.size();
    for (;;) {
        strm.next_out = buf;
        strm.avail_out = sizeof buf;
        lzma_ret r = lzma_code(&strm, LZMA_FINISH);
        const std::size_t n = sizeof buf - strm.avail_out;
        if (n > kMaxXzContentBytes - out.size()) {
            lzma_end(&strm);
            throw Error(ErrorCode::kIo, "'" + path + "' decompresses to more than " +
                                            std::to_string(kMaxXzContentBytes) + " bytes (1 GiB), the limit");
        }
        out.insert(out.end(), buf, buf + n);
        if (r == LZMA_STREAM_END) break;
        if (r != LZMA_OK) {
            lzma_end(&strm);
            throw Error(ErrorCode::kIo, "'" + path + "' is not a valid .xz file (lzma error " + std::to_string(r) + ")");
        }
    }
    lzma_end(&strm);
    return out;
}

}  // namespace filmgrain

// scan_stream_file (stream_scan.hpp): reading a coded stream from a file, pipe or device.
// Tool side: file I/O is not part of libfilmgrain.
#include <algorithm>
#include <memory>

#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"
#include "io/input_file.hpp"

namespace filmgrain::bitstream {

StreamScan scan_stream_file(const std::string& path, std::optional<StreamCodec> codec) {
    auto check_container = [&](const std::vector<uint8_t>& bytes) {
        if (const char* container = container_name(bytes.data(), bytes.size()))
            throw Error(ErrorCode::kUnsupported,
                        "'" + path + "' is a container file (" + container +
                            "); inspect and params extract read elementary streams (H.264/H.265/H.266 Annex B, AV1 IVF, low-overhead "
                            "OBUs or Annex B): extract one with `ffmpeg -i " + path +
                            " -c:v copy -f ivf out.ivf` (AV1) or `-f hevc out.hevc` (H.265), or decode it with "
                            "`filmgrain decode`");
    };
    auto unknown_codec = [&] {
        return Error(ErrorCode::kInvalidArgument,
                     "cannot tell the codec of '" + path + "' (give --codec h264|h265|h266|av1)");
    };
    std::vector<uint8_t> bytes;
    const auto in = std::make_unique<InputFile>(path);  // Error(kIo) naming it when it cannot be opened
    const std::string limit = "; the limit for a coded stream is " + std::to_string(kMaxStreamFileBytes) + " bytes (1 GiB)";
    if (const auto left = in->remaining()) {
        if (*left > kMaxStreamFileBytes)
            throw Error(ErrorCode::kIo, "'" + path + "' holds " + std::to_string(*left) + " bytes" + limit);
        bytes.resize(std::size_t(*left));
        bytes.resize(in->read(bytes.data(), bytes.size()));
        check_container(bytes);
        if (!codec) codec = detect_stream_codec(bytes.data(), bytes.size(), path);
        if (!codec) throw unknown_codec();
        return scan_stream(bytes.data(), bytes.size(), *codec);
    }
    // A pipe or device: its beginning first, which tells a stream from anything else.
    constexpr std::size_t kChunk = std::size_t(1) << 20, kProbe = std::size_t(16) << 20;
    bool probed = false;
    for (;;) {
        const std::size_t at = bytes.size();
        const std::size_t room = std::min(kChunk, kMaxStreamFileBytes + 1 - at);
        bytes.resize(at + room);
        const std::size_t got = in->read(bytes.data() + at, room);  // fewer only at the end
        bytes.resize(at + got);
        if (bytes.size() > kMaxStreamFileBytes)
            throw Error(ErrorCode::kIo, "'" + path + "' holds more than " + std::to_string(kMaxStreamFileBytes) +
                                            " bytes" + limit);
        const bool end = got < room;
        if (!probed && (end || bytes.size() >= kProbe)) {
            probed = true;
            check_container(bytes);
            if (!codec) codec = detect_stream_codec(bytes.data(), bytes.size(), path);
            if (!codec) throw unknown_codec();
        }
        if (end) break;
    }
    check_container(bytes);
    return scan_stream(bytes.data(), bytes.size(), *codec);
}

}  // namespace filmgrain::bitstream

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
    const auto in = std::make_unique<InputFile>(path);  // Error(kIo) naming it when it cannot be opened
    const std::string limit = "; the limit for an AV1 low-overhead or Annex B stream is " + std::to_string(kMaxStreamFileBytes) + " bytes (1 GiB)";
    // Its beginning first, which tells a stream from anything else (a pipe or device whose
    // first 16 MiB are neither, e.g. /dev/zero, fails there).
    constexpr std::size_t kChunk = std::size_t(1) << 20, kProbe = std::size_t(16) << 20;
    std::vector<uint8_t> bytes;
    bool end = false;
    while (!end && bytes.size() < kProbe) {
        const std::size_t at = bytes.size();
        bytes.resize(at + kChunk);
        const std::size_t got = in->read(bytes.data() + at, kChunk);  // fewer only at the end
        bytes.resize(at + got);
        end = got < kChunk;
    }
    check_container(bytes);
    if (!codec) codec = detect_stream_codec(bytes.data(), bytes.size(), path);
    if (!codec) throw unknown_codec();
    // H.26x and AV1 IVF: scanned as read, whatever the size (a broadcast title runs to tens of GB)
    if (*codec != StreamCodec::kAv1 || looks_like_ivf(bytes.data(), bytes.size()))
        return scan_stream_incrementally(*codec, std::move(bytes), [&](uint8_t* dst, std::size_t n) {
            return end ? std::size_t(0) : in->read(dst, n);
        });
    // other AV1 containers are scanned whole
    if (const auto left = in->remaining(); left && bytes.size() + *left > kMaxStreamFileBytes)
        throw Error(ErrorCode::kIo, "'" + path + "' holds " + std::to_string(bytes.size() + *left) + " bytes" + limit);
    while (!end) {
        const std::size_t at = bytes.size();
        const std::size_t room = std::min(kChunk, kMaxStreamFileBytes + 1 - at);
        bytes.resize(at + room);
        const std::size_t got = in->read(bytes.data() + at, room);
        bytes.resize(at + got);
        if (bytes.size() > kMaxStreamFileBytes)
            throw Error(ErrorCode::kIo, "'" + path + "' holds more than " + std::to_string(kMaxStreamFileBytes) +
                                            " bytes" + limit);
        end = got < room;
    }
    return scan_stream(bytes.data(), bytes.size(), *codec);
}

}  // namespace filmgrain::bitstream

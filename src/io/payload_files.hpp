// Per-picture binary payload files, as --sei and --afgs1 take them: one file for
// every picture, several for pictures 0, 1, ..., or one pattern (frame%d.bin, see
// FilePattern) where a missing file means no payload for that picture. A name with a '%'
// that is not a valid pattern (strength100%.bin) is a plain file.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/file_pattern.hpp"

namespace filmgrain::io {

// The largest payload file read: an SEI or T.35 payload is at most a few kilobytes, so a
// larger file (or /dev/zero) is not one.
inline constexpr std::size_t kMaxPayloadFileBytes = 1u << 20;

// Reads a payload file of at most kMaxPayloadFileBytes (Error naming the file otherwise).
std::vector<uint8_t> read_payload_file(const std::string& path);

class PayloadFiles {
public:
    explicit PayloadFiles(std::vector<std::string> files);
    // The payload that arrives with picture k, if any.
    std::optional<std::vector<uint8_t>> for_picture(int k) const;
    bool is_pattern() const { return pattern_.has_value(); }
    bool one_for_every_picture() const { return !pattern_ && fixed_.size() == 1; }
    // Payloads that exist, in picture order (a pattern is scanned from 0 until the first gap).
    std::vector<std::vector<uint8_t>> all() const;
    std::string name_for(int k) const;

private:
    std::vector<std::string> files_;
    std::optional<FilePattern> pattern_;
    std::vector<std::vector<uint8_t>> fixed_;
};

}  // namespace filmgrain::io

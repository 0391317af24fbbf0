// Per-picture binary payload files, as --sei and --afgs1 take them: one file for
// every picture, several for pictures 0, 1, ..., or one printf pattern
// (frame%d.bin) where a missing file means no payload for that picture.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace filmgrain::cli {

class PayloadFiles {
public:
    explicit PayloadFiles(std::vector<std::string> files);
    // The payload that arrives with picture k, if any.
    std::optional<std::vector<uint8_t>> for_picture(int k) const;
    bool is_pattern() const { return pattern_; }
    bool one_for_every_picture() const { return !pattern_ && fixed_.size() == 1; }
    // Payloads that exist, in picture order (a pattern is scanned from 0 until the first gap).
    std::vector<std::vector<uint8_t>> all() const;
    std::string name_for(int k) const;

private:
    std::vector<std::string> files_;
    bool pattern_ = false;
    std::vector<std::vector<uint8_t>> fixed_;
};

// printf-formats a %d pattern with k (throws Error(kInvalidArgument) on a bad pattern).
std::string format_pattern(const std::string& pattern, int k);

}  // namespace filmgrain::cli

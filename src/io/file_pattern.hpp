// Per-picture file names (frame%04d.bin): how --sei / --afgs1 payload files, per-frame
// outputs and the GStreamer element's payload properties name picture k.
#pragma once
#include <optional>
#include <string>

namespace filmgrain::io {

// A per-picture file name pattern: exactly one conversion %d / %u / %i, optionally padded
// to a width of one or two digits (%4d, %04d: at most 99), and "%%" for a literal '%'. A
// name with no valid conversion, or with any other '%', is not a pattern but a plain file
// name.
class FilePattern {
public:
    static std::optional<FilePattern> parse(const std::string& name);
    // The name of picture k (k >= 0).
    std::string name_for(long long k) const;
    const std::string& text() const { return text_; }

private:
    std::string text_, prefix_, suffix_;
    int width_ = 0;
    bool zero_pad_ = false;
};

}  // namespace filmgrain::io

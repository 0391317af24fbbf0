// Strict parsing of the tool's option values (sizes, frame rates, regions, file patterns):
// the whole text must match, every number is range-checked before it is stored, and an
// error names the option, what was given and what is allowed. No sscanf (it accepts
// trailing text and wraps on overflow) and no user text as a printf format.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "core/frame_buffer.hpp"
#include "io/file_pattern.hpp"

namespace filmgrain::cli {

// The largest picture dimension an option may give is the library's (kMaxPictureDimension,
// core/frame_buffer.hpp); the picture's area is checked where the frame is allocated.
using filmgrain::kMaxPictureDimension;
// Frame rates N/D with 1 <= N, D <= kMaxFrameRateTerm (Y4M's 30000:1001 and 120000:1001 fit).
inline constexpr int kMaxFrameRateTerm = 1000000;

// A non-negative decimal number without sign, spaces or leading '+' in lo..hi; `what` names it
// in the error (Error(kInvalidArgument)).
long long parse_decimal(std::string_view text, long long lo, long long hi, const std::string& what);

struct PictureSize {
    int width = 0, height = 0;
};
// "WxH" (or "WXH"), each 1..kMaxPictureDimension.
PictureSize parse_picture_size(std::string_view text, const std::string& option);

struct FrameRate {
    int num = 25, den = 1;
};
// "N" or "N/D".
FrameRate parse_frame_rate(std::string_view text, const std::string& option);

struct Region {
    int x = 0, y = 0, w = 0, h = 0;
};
// "x,y,w,h" with x, y in 0..2^30 and w, h in 1..2^30; the caller checks it against the
// picture (in 64-bit arithmetic, so x + w cannot overflow).
Region parse_region(std::string_view text, const std::string& option);

using io::FilePattern;

}  // namespace filmgrain::cli

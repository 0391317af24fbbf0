#include "option_parsing.hpp"

#include "filmgrain/error.hpp"

namespace filmgrain::cli {
namespace {

[[noreturn]] void bad(const std::string& option, std::string_view text, const std::string& allowed) {
    throw Error(ErrorCode::kInvalidArgument, option + " '" + std::string(text) + "' is not " + allowed);
}

// The text up to `sep` (or the end) and the rest after it.
std::pair<std::string_view, std::string_view> split_at(std::string_view s, char sep) {
    const auto p = s.find(sep);
    if (p == std::string_view::npos) return {s, {}};
    return {s.substr(0, p), s.substr(p + 1)};
}

bool all_digits(std::string_view s) {
    if (s.empty()) return false;
    for (char c : s)
        if (c < '0' || c > '9') return false;
    return true;
}

}  // namespace

long long parse_decimal(std::string_view text, long long lo, long long hi, const std::string& what) {
    if (!all_digits(text))
        throw Error(ErrorCode::kInvalidArgument,
                    what + " '" + std::string(text) + "' is not a whole number (allowed " + std::to_string(lo) + ".." +
                        std::to_string(hi) + ")");
    // digits beyond what hi needs mean out of range; no accumulation can overflow
    long long v = 0;
    for (char c : text) {
        v = v * 10 + (c - '0');
        if (v > hi) break;
    }
    if (v < lo || v > hi)
        throw Error(ErrorCode::kInvalidArgument, what + " = " + std::string(text) + " is out of range (allowed " +
                                                     std::to_string(lo) + ".." + std::to_string(hi) + ")");
    return v;
}

PictureSize parse_picture_size(std::string_view text, const std::string& option) {
    const auto x = text.find_first_of("xX");
    const std::string allowed = "WxH with 1.." + std::to_string(kMaxPictureDimension) + " in each dimension";
    if (x == std::string_view::npos || !all_digits(text.substr(0, x)) || !all_digits(text.substr(x + 1)))
        bad(option, text, allowed);
    PictureSize s;
    s.width = int(parse_decimal(text.substr(0, x), 1, kMaxPictureDimension, option + " width"));
    s.height = int(parse_decimal(text.substr(x + 1), 1, kMaxPictureDimension, option + " height"));
    return s;
}

FrameRate parse_frame_rate(std::string_view text, const std::string& option) {
    const auto [n, d] = split_at(text, '/');
    const std::string allowed = "N or N/D with whole numbers 1.." + std::to_string(kMaxFrameRateTerm);
    if (!all_digits(n) || (text.find('/') != std::string_view::npos && !all_digits(d))) bad(option, text, allowed);
    FrameRate r;
    r.num = int(parse_decimal(n, 1, kMaxFrameRateTerm, option + " numerator"));
    r.den = d.empty() ? 1 : int(parse_decimal(d, 1, kMaxFrameRateTerm, option + " denominator"));
    return r;
}

Region parse_region(std::string_view text, const std::string& option) {
    constexpr long long kMax = 1LL << 30;
    std::string_view parts[4];
    std::string_view rest = text;
    for (int i = 0; i < 4; i++) {
        auto [head, tail] = split_at(rest, ',');
        parts[i] = head;
        rest = tail;
        if (i < 3 && rest.data() == nullptr) bad(option, text, "x,y,w,h");
    }
    if (!rest.empty() || text.back() == ',') bad(option, text, "x,y,w,h");
    for (auto p : parts)
        if (!all_digits(p)) bad(option, text, "x,y,w,h with whole numbers x, y >= 0 and w, h >= 1");
    Region r;
    r.x = int(parse_decimal(parts[0], 0, kMax, option + " x"));
    r.y = int(parse_decimal(parts[1], 0, kMax, option + " y"));
    r.w = int(parse_decimal(parts[2], 1, kMax, option + " w"));
    r.h = int(parse_decimal(parts[3], 1, kMax, option + " h"));
    return r;
}

}  // namespace filmgrain::cli

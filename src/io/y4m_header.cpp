#include "io/y4m_header.hpp"

#include <cstdint>

#include "filmgrain/error.hpp"

namespace filmgrain {

namespace {

constexpr long long kMaxFrameRateTerm = 2147483647;  // 2^31 - 1, FFmpeg's bound too

// Printable form of a (possibly hostile) value for a message: at most 40 bytes, other bytes
// than printable ASCII as \xNN.
std::string shown(std::string_view v) {
    std::string out;
    for (std::size_t i = 0; i < v.size() && i < 40; i++) {
        const unsigned char c = static_cast<unsigned char>(v[i]);
        if (c >= 0x20 && c < 0x7f) {
            out.push_back(char(c));
        } else {
            static const char* hex = "0123456789abcdef";
            out += "\\x";
            out.push_back(hex[c >> 4]);
            out.push_back(hex[c & 15]);
        }
    }
    if (v.size() > 40) out += "...";
    return out;
}

[[noreturn]] void fail(char tag, std::string_view value, const std::string& allowed, const char* problem) {
    throw Error(ErrorCode::kIo, std::string("Y4M header tag ") + tag + ": value '" + shown(value) + "' " + problem +
                                    " (allowed " + allowed + ")");
}

// Digits only (no sign, no spaces), lo..hi; the value is never converted past hi.
long long parse_number(char tag, std::string_view whole, std::string_view digits, long long lo, long long hi,
                       const std::string& allowed) {
    if (digits.empty()) fail(tag, whole, allowed, "is not a number");
    long long v = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') fail(tag, whole, allowed, "is not a number");
        v = v * 10 + (c - '0');
        if (v > hi) fail(tag, whole, allowed, "is out of range");
    }
    if (v < lo) fail(tag, whole, allowed, "is out of range");
    return v;
}

const char* kColourSpaces =
    "420jpeg, 420paldv, 420mpeg2, 420, 422, 444, mono, and 420pN, 422pN, 444pN, monoN with N = 9, 10, 12, 14, 16";

}  // namespace

std::string y4m_colorspace_tag(const PixelFormat& f) {
    const std::string base = f.chroma == ChromaFormat::k400   ? "mono"
                             : f.chroma == ChromaFormat::k420 ? "420"
                             : f.chroma == ChromaFormat::k422 ? "422"
                                                              : "444";
    if (f.bit_depth == 8) return f.chroma == ChromaFormat::k420 ? "420jpeg" : base;
    if (f.chroma == ChromaFormat::k400) return base + std::to_string(f.bit_depth);
    return base + "p" + std::to_string(f.bit_depth);
}

PixelFormat parse_y4m_colorspace(std::string_view c) {
    PixelFormat f;
    std::string_view depth;  // after the chroma part: "" (8-bit) or the digits of N
    if (c.substr(0, 4) == "mono") {
        f.chroma = ChromaFormat::k400;
        depth = c.substr(4);
        if (depth.substr(0, 1) == "p") depth = depth.substr(1);  // monopN: filmgrain before 1.1
        if (c == "monop") fail('C', c, kColourSpaces, "is not supported");
    } else {
        const std::string_view base = c.substr(0, 3);
        if (base == "420") f.chroma = ChromaFormat::k420;
        else if (base == "422") f.chroma = ChromaFormat::k422;
        else if (base == "444") f.chroma = ChromaFormat::k444;
        else fail('C', c, kColourSpaces, "is not supported");
        const std::string_view rest = c.substr(3);
        if (f.chroma == ChromaFormat::k420 && (rest == "jpeg" || rest == "paldv" || rest == "mpeg2")) return f;
        if (!rest.empty()) {
            if (rest[0] != 'p' || rest.size() < 2) fail('C', c, kColourSpaces, "is not supported");
            depth = rest.substr(1);
        }
    }
    if (depth.empty()) return f;
    if (depth != "9" && depth != "10" && depth != "12" && depth != "14" && depth != "16")
        fail('C', c, kColourSpaces, "is not supported");
    f.bit_depth = int(parse_number('C', c, depth, 9, 16, kColourSpaces));
    return f;
}

Y4mHeader parse_y4m_header(std::string_view line) {
    constexpr std::string_view kMagic = "YUV4MPEG2";
    if (line.substr(0, kMagic.size()) != kMagic)
        throw Error(ErrorCode::kIo, "not a Y4M stream: the header does not start with YUV4MPEG2");
    if (line.size() > kMaxY4mHeaderBytes)
        throw Error(ErrorCode::kIo, "Y4M header is longer than " + std::to_string(kMaxY4mHeaderBytes) + " bytes");
    std::string_view rest = line.substr(kMagic.size());
    if (!rest.empty() && rest[0] != ' ')
        throw Error(ErrorCode::kIo, "Y4M header: '" + shown(line.substr(0, 20)) + "' is not YUV4MPEG2 followed by a space");
    Y4mHeader h;
    bool have_w = false, have_h = false;
    const std::string dim = "1.." + std::to_string(kMaxPictureDimension);
    while (!rest.empty()) {
        const std::size_t sp = rest.find(' ');
        const std::string_view tok = rest.substr(0, sp);
        rest = sp == std::string_view::npos ? std::string_view() : rest.substr(sp + 1);
        if (tok.empty()) continue;  // repeated spaces
        for (char ch : tok)
            if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) == 0x7f)
                throw Error(ErrorCode::kIo, "Y4M header: tag '" + shown(tok) + "' holds a control character");
        const char tag = tok[0];
        const std::string_view value = tok.substr(1);
        switch (tag) {
            case 'W':
                h.width = int(parse_number('W', value, value, 1, kMaxPictureDimension, dim));
                have_w = true;
                break;
            case 'H':
                h.height = int(parse_number('H', value, value, 1, kMaxPictureDimension, dim));
                have_h = true;
                break;
            case 'C': h.format = parse_y4m_colorspace(value); break;
            case 'F': {
                const std::string allowed = "N:D with N and D 1..2147483647, or 0:0 for unknown";
                const std::size_t colon = value.find(':');
                if (colon == std::string_view::npos) fail('F', value, allowed, "is not a frame rate");
                const long long n = parse_number('F', value, value.substr(0, colon), 0, kMaxFrameRateTerm, allowed);
                const long long d = parse_number('F', value, value.substr(colon + 1), 0, kMaxFrameRateTerm, allowed);
                if ((n == 0) != (d == 0)) fail('F', value, allowed, "is out of range");
                h.fps_num = int(n);
                h.fps_den = int(d);
                break;
            }
            default:
                if (tok.substr(0, 7) == "XYSCSS=") break;  // FFmpeg's copy of C
                h.extra += ' ';
                h.extra += tok;
                break;
        }
    }
    if (!have_w || !have_h)
        throw Error(ErrorCode::kIo, std::string("Y4M header has no ") + (have_w ? "H (height)" : "W (width)") + " tag");
    check_picture_size(h.width, h.height);
    return h;
}

void parse_y4m_frame_header(std::string_view line) {
    if (line.size() > kMaxY4mHeaderBytes)
        throw Error(ErrorCode::kIo, "Y4M frame header is longer than " + std::to_string(kMaxY4mHeaderBytes) + " bytes");
    if (line.substr(0, 5) != "FRAME" || (line.size() > 5 && line[5] != ' '))
        throw Error(ErrorCode::kIo, "Y4M frame header '" + shown(line) + "' is not FRAME (with optional tags)");
}

}  // namespace filmgrain

// The tool's option values (tools/option_parsing, tools/cli_common): picture sizes, frame
// rates, regions, pixel formats, flavours and per-picture file patterns. The input is
// split at NUL bytes into the values of one command line. Only filmgrain::Error may come
// out, and whatever is accepted must be inside the documented ranges.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "filmgrain/error.hpp"
#include "option_parsing.hpp"

using namespace filmgrain;
using namespace filmgrain::cli;

namespace {

template <typename Fn>
void expect_error_or(Fn&& fn) {
    try {
        fn();
    } catch (const Error&) {
    }
}

void check(bool ok) {
    if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<std::string> v(1);
    for (size_t i = 0; i < size; i++) {
        if (data[i] == 0) v.emplace_back();
        else v.back().push_back(char(data[i]));
    }
    while (v.size() < 6) v.emplace_back();
    expect_error_or([&] {
        const PictureSize s = parse_picture_size(v[0], "--size");
        check(s.width >= 1 && s.width <= kMaxPictureDimension && s.height >= 1 && s.height <= kMaxPictureDimension);
    });
    expect_error_or([&] {
        const FrameRate r = parse_frame_rate(v[1], "--fps");
        check(r.num >= 1 && r.num <= kMaxFrameRateTerm && r.den >= 1 && r.den <= kMaxFrameRateTerm);
    });
    expect_error_or([&] {
        const Region g = parse_region(v[2], "--roi");
        check(g.x >= 0 && g.y >= 0 && g.w >= 1 && g.h >= 1);
    });
    expect_error_or([&] {
        RawVideoOptions o;
        o.size = v[0];
        o.pix_fmt = v[3];
        o.fps = v[1];
        const VideoInfo info = o.to_info();
        check(info.format.bit_depth >= 8 && info.format.bit_depth <= 16);
    });
    expect_error_or([&] { (void)parse_flavour(v[4]); });
    expect_error_or([&] {
        if (const auto p = FilePattern::parse(v[5])) {
            for (long long k : {0LL, 7LL, 123456789LL}) {
                const std::string name = p->name_for(k);
                // the name is the pattern's literal text around the number: never longer
                // than the pattern plus the number's padded width (at most 99)
                check(name.size() <= v[5].size() + 99 + 20);
            }
        }
    });
    return 0;
}

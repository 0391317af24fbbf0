#include "verify/picture_comparison.hpp"

#include <cstdlib>

#include "core/md5.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::verify {
namespace {

void check_same_shape(const FrameView& a, const FrameView& b) {
    if (a.width != b.width || a.height != b.height || a.format != b.format || a.bit_depth != b.bit_depth)
        throw Error(ErrorCode::kInvalidArgument,
                    "decoded picture " + std::to_string(b.width) + "x" + std::to_string(b.height) + " at " +
                        std::to_string(b.bit_depth) + " bits does not match the reference's " +
                        std::to_string(a.width) + "x" + std::to_string(a.height) + " at " +
                        std::to_string(a.bit_depth) + " bits (same size, format and bit depth needed)");
}

int sample(const PlaneView& p, int x, int y, bool wide) {
    return wide ? p.row<const uint16_t>(y)[x] : p.row<const uint8_t>(y)[x];
}

}  // namespace

bool PictureComparison::exact() const {
    for (const PlaneComparison& p : planes)
        if (!p.exact()) return false;
    return true;
}

int64_t PictureComparison::differing() const {
    int64_t n = 0;
    for (const PlaneComparison& p : planes) n += p.differing;
    return n;
}

PictureComparison compare_pictures(const FrameView& expected, const FrameView& decoded, int luma_block) {
    check_same_shape(expected, decoded);
    if (luma_block < 2) throw Error(ErrorCode::kInvalidArgument, "luma_block " + std::to_string(luma_block) + " (allowed 2 and above)");
    const bool wide = expected.bit_depth > 8;
    PictureComparison out;
    out.planes.resize(std::size_t(expected.plane_count()));
    for (int pl = 0; pl < expected.plane_count(); pl++) {
        const PlaneView& e = expected.planes[pl];
        const PlaneView& d = decoded.planes[pl];
        PlaneComparison& c = out.planes[std::size_t(pl)];
        const int sx = pl ? chroma_shift_x(expected.format) : 0, sy = pl ? chroma_shift_y(expected.format) : 0;
        c.block_width = luma_block >> sx;
        c.block_height = luma_block >> sy;
        c.blocks_x = (e.width + c.block_width - 1) / c.block_width;
        c.blocks_y = (e.height + c.block_height - 1) / c.block_height;
        c.differing_per_block.assign(std::size_t(c.blocks_x) * std::size_t(c.blocks_y), 0);
        c.samples = int64_t(e.width) * e.height;
        for (int y = 0; y < e.height; y++) {
            for (int x = 0; x < e.width; x++) {
                const int a = sample(e, x, y, wide), b = sample(d, x, y, wide);
                if (a == b) continue;
                const int diff = std::abs(a - b);
                c.differing++;
                out.squared_error += double(diff) * diff;
                if (diff > c.max_abs_difference) c.max_abs_difference = diff;
                if (c.first.x < 0) c.first = FirstDifference{x, y, a, b};
                c.differing_per_block[std::size_t(y / c.block_height) * std::size_t(c.blocks_x) +
                                      std::size_t(x / c.block_width)]++;
            }
        }
    }
    return out;
}

Distance picture_distance(const FrameView& a, const FrameView& b) {
    check_same_shape(a, b);
    Distance d;
    for (int pl = 0; pl < a.plane_count(); pl++) {
        const PlaneView& pa = a.planes[pl];
        const PlaneView& pb = b.planes[pl];
        for (int y = 0; y < pa.height; y++) {
            if (a.bit_depth > 8) {
                const uint16_t* ra = pa.row<const uint16_t>(y);
                const uint16_t* rb = pb.row<const uint16_t>(y);
                for (int x = 0; x < pa.width; x++) {
                    const int diff = int(ra[x]) - int(rb[x]);
                    d.differing += diff != 0;
                    d.squared_error += double(diff * diff);
                }
            } else {
                const uint8_t* ra = pa.row<const uint8_t>(y);
                const uint8_t* rb = pb.row<const uint8_t>(y);
                for (int x = 0; x < pa.width; x++) {
                    const int diff = int(ra[x]) - int(rb[x]);
                    d.differing += diff != 0;
                    d.squared_error += double(diff * diff);
                }
            }
        }
    }
    return d;
}

std::string picture_md5(const FrameView& picture) {
    Md5 md5;
    const int bytes = picture.bytes_per_sample();
    std::vector<uint8_t> row;
    for (int pl = 0; pl < picture.plane_count(); pl++) {
        const PlaneView& p = picture.planes[pl];
        row.resize(std::size_t(p.width) * std::size_t(bytes));
        for (int y = 0; y < p.height; y++) {
            if (bytes == 1) {
                md5.update(p.row<const uint8_t>(y), std::size_t(p.width));
                continue;
            }
            // little-endian whatever the host (the order raw YUV files and FFmpeg's md5 use)
            const uint16_t* r = p.row<const uint16_t>(y);
            for (int x = 0; x < p.width; x++) {
                row[std::size_t(2 * x)] = uint8_t(r[x] & 0xFF);
                row[std::size_t(2 * x + 1)] = uint8_t(r[x] >> 8);
            }
            md5.update(row.data(), row.size());
        }
    }
    return md5.hex_digest();
}

}  // namespace filmgrain::verify

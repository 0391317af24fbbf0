// The whole path a decoder drives, from metadata to grainy pictures: a Session receives an
// FGC SEI payload, an AFGS1 T.35 payload or an AV1 film_grain_params() set whose fields are
// taken raw from the input (any value, as a C or C++ caller may pass), and applies it to a
// few pictures of any small size, chroma format and bit depth, in place or not, on one or
// two threads. The parsers have their own harnesses; this one is for the synthesis behind
// them: whatever a set that passes validation holds and whatever the picture, only
// filmgrain::Error may come out, a picture the session refuses (throwing) or leaves without
// grain is as it was, and the source of an out-of-place synthesis is never written.
//
// Input: byte 0 the metadata kind (bits 0-1: 0 and 3 FGC SEI, 1 AV1 fields, 2 AFGS1), the
// FGC codec (bits 2-3, modulo 3), the flavour (bits 4-6, modulo 5), two threads (bit 7);
// byte 1 the chroma format (bits 0-1), the bit depth (bits 2-4: 8, 9, 10, 12, 16, 8, 10, 12),
// in place (bit 5), samples above the bit depth (bit 6), invalid sets passed through
// (bit 7); byte 2 the width - 1 (0..127), byte 3 the height - 1 (0..95), byte 4 the
// pictures (1..4, bits 0-1) and the samples' seed; the rest the metadata (AV1 fields: its
// last byte is also the matrix_coefficients the set arrives with).
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/session.hpp"

using namespace filmgrain;

namespace {

constexpr int kBitDepths[8] = {8, 9, 10, 12, 16, 8, 10, 12};

// The fields of an AV1 set, each from the next byte (or two), unchecked: the session's
// validation is what is under test. Small values most of the time, so that valid sets
// with every stage in use are common.
Av1FilmGrainParams av1_fields(const uint8_t* data, std::size_t size) {
    std::size_t at = 0;
    auto next = [&]() -> int { return at < size ? data[at++] : 0; };
    auto small = [&](int range) {  // mostly 0..range-1, now and then any byte
        const int v = next();
        return v >= 240 ? v - 240 + range : v % range;
    };
    auto fill = [&](auto& values) {
        for (auto& v : values) v = next();
    };
    // a scaling function: its point count (0..most, or beyond), values and scalings
    auto points = [&](int& count, int most, auto& values, auto& scalings) {
        count = small(most + 1);
        fill(values);
        fill(scalings);
    };
    Av1FilmGrainParams p;
    p.apply_grain = small(2);
    p.grain_seed = next();
    p.grain_seed |= next() << 8;  // (two statements: the operands of | are unsequenced)
    p.update_grain = 1;
    points(p.num_y_points, 14, p.point_y_value, p.point_y_scaling);
    p.chroma_scaling_from_luma = small(2);
    points(p.num_cb_points, 10, p.point_cb_value, p.point_cb_scaling);
    points(p.num_cr_points, 10, p.point_cr_value, p.point_cr_scaling);
    p.grain_scaling_minus_8 = small(4);
    p.ar_coeff_lag = small(4);
    fill(p.ar_coeffs_y_plus_128);
    fill(p.ar_coeffs_cb_plus_128);
    fill(p.ar_coeffs_cr_plus_128);
    p.ar_coeff_shift_minus_6 = small(4);
    p.grain_scale_shift = small(4);
    auto offset = [&] {  // 9 bits
        const int low = next();
        return low | (next() & 1) << 8;
    };
    p.cb_mult = next(), p.cb_luma_mult = next(), p.cb_offset = offset();
    p.cr_mult = next(), p.cr_luma_mult = next(), p.cr_offset = offset();
    p.overlap_flag = small(2);
    p.clip_to_restricted_range = small(2);
    p.chroma_point_counts_signalled = next() & 1;
    return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 5) return 0;
    const int kind = data[0] & 3;
    const auto codec = static_cast<FgcCodec>(((data[0] >> 2) & 3) % 3);
    SessionOptions options;
    options.flavour = static_cast<FgcFlavour>(((data[0] >> 4) & 7) % 5);
    options.threads = data[0] & 0x80 ? 2 : 1;
    options.passthrough_invalid = data[1] & 0x80;
    const auto chroma = static_cast<ChromaFormat>(data[1] & 3);
    const int bit_depth = kBitDepths[(data[1] >> 2) & 7];
    const bool in_place = data[1] & 0x20, above_bit_depth = data[1] & 0x40;
    const int width = 1 + (data[2] & 127), height = 1 + data[3] % 96;
    const int pictures = 1 + (data[4] & 3);
    uint32_t state = 0x9E3779B9u * (data[4] | 1u);
    const uint8_t* meta = data + 5;
    const std::size_t meta_size = size - 5;

    const PixelFormat format{chroma, bit_depth};
    FrameBuffer src(width, height, format), dst(width, height, format);
    const uint32_t top = above_bit_depth ? 0xFFFFu : (1u << bit_depth) - 1;
    for (std::size_t i = 0; i < src.byte_size(); i += bit_depth > 8 ? 2 : 1) {
        state = state * 1664525u + 1013904223u;
        const uint32_t v = (state >> 8) % (top + 1);
        if (bit_depth > 8) {
            const uint16_t s = uint16_t(v);
            std::memcpy(src.bytes() + i, &s, 2);
        } else {
            src.bytes()[i] = uint8_t(v);
        }
    }
    try {
        Session session(options);
        try {
            if (kind == 1)
                session.receive_av1_params(av1_fields(meta, meta_size), 0, meta_size ? meta[meta_size - 1] : 2);
            else if (kind == 2)
                session.receive_afgs1_t35(meta, meta_size);
            else
                session.receive_fgc_sei_payload(meta, meta_size, codec);
        } catch (const Error&) {
            // a set refused on arrival: the pictures still go through the session
        }
        for (int k = 0; k < pictures; ++k) {
            const std::vector<uint8_t> before(src.bytes(), src.bytes() + src.byte_size());
            FrameView in = src.view();
            FrameView out = in_place ? in : dst.view();
            ApplyResult result;
            try {
                result = session.apply(in, out);
            } catch (const Error&) {
                // refused before synthesis: no picture half-written, in place or not
                if (std::memcmp(src.bytes(), before.data(), before.size()) != 0) std::abort();
                continue;
            }
            // a picture without grain is the source as it was (copied when out of place)
            if (!result.grain_applied) {
                const uint8_t* got = in_place ? src.bytes() : dst.bytes();
                if (std::memcmp(got, before.data(), before.size()) != 0) std::abort();
            }
            if (in_place) continue;
            // the source of an out-of-place picture is never written
            if (std::memcmp(src.bytes(), before.data(), before.size()) != 0) std::abort();
        }
    } catch (const Error&) {
    }
    return 0;
}

// What the H.264, H.265 and H.266 picture order count decoders share: a ue(v) read bounded
// by the range its semantics allow, and the lsb wrap-around that recovers PicOrderCntMsb
// (H.264 8.2.1.1, H.265 8.3.1, H.266 8.3.1 state the same rule).
#pragma once
#include <cstdint>

#include "filmgrain/error.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {

inline uint32_t ue_in_range(BitReader& r, const char* field, uint32_t hi) {
    const uint32_t v = r.ue(field);
    if (v > hi) throw Error(ErrorCode::kMalformedPayload, out_of_range_message(field, v, 0, hi));
    return v;
}

// PicOrderCntMsb of a picture with pic_order_cnt_lsb `lsb`, given the msb and lsb of the
// previous picture the standard refers to (prevPicOrderCnt / prevTid0Pic).
inline int poc_msb(int prev_msb, int prev_lsb, int lsb, int max_lsb) {
    if (lsb < prev_lsb && prev_lsb - lsb >= max_lsb / 2) return prev_msb + max_lsb;
    if (lsb > prev_lsb && lsb - prev_lsb > max_lsb / 2) return prev_msb - max_lsb;
    return prev_msb;
}

}  // namespace filmgrain::bitstream

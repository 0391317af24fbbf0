// The facts of an AV1 sequence_header_obu() (AV1 5.5) a film grain consumer needs: the
// picture size and format the frames are decoded to (for AFGS1 set selection, AFGS1 7.3)
// and whether frame headers carry film_grain_params() (film_grain_params_present). The
// whole header is walked, since film_grain_params_present is its last field.
#pragma once
#include <cstdint>
#include <vector>

namespace filmgrain::bitstream {

struct Av1SequenceHeader {
    int seq_profile = 0;
    int max_frame_width = 0, max_frame_height = 0;  // max_frame_*_minus_1 + 1
    int bit_depth = 8;
    int mono_chrome = 0;
    int subsampling_x = 1, subsampling_y = 1;
    int color_description_present_flag = 0;
    int color_primaries = 2, transfer_characteristics = 2, matrix_coefficients = 2;  // 2: unspecified
    int color_range = 0;
    int film_grain_params_present = 0;
    bool operator==(const Av1SequenceHeader&) const = default;
};

// `payload` is the OBU payload (after the OBU header). Throws Error(kMalformedPayload)
// naming the syntax element on truncation or a value AV1 forbids (seq_profile > 2).
Av1SequenceHeader parse_av1_sequence_header(const std::vector<uint8_t>& payload);

}  // namespace filmgrain::bitstream

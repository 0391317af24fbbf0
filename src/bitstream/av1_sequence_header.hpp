// The facts of an AV1 sequence_header_obu() (AV1 5.5) a film grain consumer needs: the
// picture size and format the frames are decoded to (for AFGS1 set selection, AFGS1 7.3)
// and whether frame headers carry film_grain_params() (film_grain_params_present). The
// whole header is walked, since film_grain_params_present is its last field.
#pragma once
#include <array>
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

    // What uncompressed_header() (AV1 5.9) depends on.
    int reduced_still_picture_header = 0;
    int decoder_model_info_present_flag = 0;
    int equal_picture_interval = 0;
    int buffer_removal_time_length = 0;        // buffer_removal_time_length_minus_1 + 1
    int frame_presentation_time_length = 0;    // frame_presentation_time_length_minus_1 + 1
    int operating_points = 1;                  // operating_points_cnt_minus_1 + 1
    std::array<int, 32> operating_point_idc{};
    std::array<int, 32> decoder_model_present_for_this_op{};
    int frame_width_bits = 1, frame_height_bits = 1;
    int frame_id_numbers_present_flag = 0;
    int delta_frame_id_length = 0;             // delta_frame_id_length_minus_2 + 2
    int frame_id_length = 0;                   // idLen
    int use_128x128_superblock = 0;
    int enable_warped_motion = 0;
    int enable_order_hint = 0;
    int enable_ref_frame_mvs = 0;
    int seq_force_screen_content_tools = 2;    // 2 = SELECT_SCREEN_CONTENT_TOOLS
    int seq_force_integer_mv = 2;              // 2 = SELECT_INTEGER_MV
    int order_hint_bits = 0;
    int enable_superres = 0, enable_cdef = 0, enable_restoration = 0;
    int separate_uv_delta_q = 0;
    bool operator==(const Av1SequenceHeader&) const = default;
};

// `payload` is the OBU payload (after the OBU header). Throws Error(kMalformedPayload)
// naming the syntax element on truncation or a value AV1 forbids (seq_profile > 2).
Av1SequenceHeader parse_av1_sequence_header(const std::vector<uint8_t>& payload);

}  // namespace filmgrain::bitstream

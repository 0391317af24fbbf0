#include "bitstream/av1_sequence_header.hpp"

#include <string>

#include "filmgrain/error.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {
namespace {

// AV1 4.10.3 uvlc(): only skipped here (num_ticks_per_picture_minus_1).
void skip_uvlc(BitReader& r, const char* field) {
    int leading_zeros = 0;
    while (!r.flag(field)) {
        if (++leading_zeros >= 32) return;  // the value is then 2^32 - 1, with no bits after
    }
    r.u(leading_zeros, field);
}

// AV1 5.5.2 color_config()
void read_color_config(BitReader& r, Av1SequenceHeader& h) {
    const bool high_bitdepth = r.flag("high_bitdepth");
    if (h.seq_profile == 2 && high_bitdepth)
        h.bit_depth = r.flag("twelve_bit") ? 12 : 10;
    else
        h.bit_depth = high_bitdepth ? 10 : 8;
    h.mono_chrome = h.seq_profile == 1 ? 0 : int(r.u(1, "mono_chrome"));
    h.color_description_present_flag = int(r.u(1, "color_description_present_flag"));
    if (h.color_description_present_flag) {
        h.color_primaries = int(r.u(8, "color_primaries"));
        h.transfer_characteristics = int(r.u(8, "transfer_characteristics"));
        h.matrix_coefficients = int(r.u(8, "matrix_coefficients"));
    }
    if (h.mono_chrome) {
        h.color_range = int(r.u(1, "color_range"));
        h.subsampling_x = h.subsampling_y = 1;
        return;  // no separate_uv_delta_q for monochrome
    }
    // sRGB: BT.709 primaries, sRGB transfer, identity matrix is 4:4:4 full range by definition
    if (h.color_primaries == 1 && h.transfer_characteristics == 13 && h.matrix_coefficients == 0) {
        h.color_range = 1;
        h.subsampling_x = h.subsampling_y = 0;
    } else {
        h.color_range = int(r.u(1, "color_range"));
        if (h.seq_profile == 0) {
            h.subsampling_x = h.subsampling_y = 1;
        } else if (h.seq_profile == 1) {
            h.subsampling_x = h.subsampling_y = 0;
        } else if (h.bit_depth == 12) {
            h.subsampling_x = int(r.u(1, "subsampling_x"));
            h.subsampling_y = h.subsampling_x ? int(r.u(1, "subsampling_y")) : 0;
        } else {
            h.subsampling_x = 1;
            h.subsampling_y = 0;
        }
        if (h.subsampling_x && h.subsampling_y) r.u(2, "chroma_sample_position");
    }
    h.separate_uv_delta_q = int(r.u(1, "separate_uv_delta_q"));
}

}  // namespace

Av1SequenceHeader parse_av1_sequence_header(const std::vector<uint8_t>& payload) {
    BitReader r(payload);
    Av1SequenceHeader h;
    h.seq_profile = int(r.u(3, "seq_profile"));
    if (h.seq_profile > 2)
        throw Error(ErrorCode::kMalformedPayload, out_of_range_message("seq_profile", h.seq_profile, 0, 2));
    r.u(1, "still_picture");
    const bool reduced = r.flag("reduced_still_picture_header");
    h.reduced_still_picture_header = reduced;
    if (reduced) {
        r.u(5, "seq_level_idx[0]");
    } else {
        bool decoder_model_info_present = false;
        int buffer_delay_length = 0;
        if (r.flag("timing_info_present_flag")) {
            r.u(32, "num_units_in_display_tick");
            r.u(32, "time_scale");
            h.equal_picture_interval = int(r.u(1, "equal_picture_interval"));
            if (h.equal_picture_interval) skip_uvlc(r, "num_ticks_per_picture_minus_1");
            decoder_model_info_present = r.flag("decoder_model_info_present_flag");
            if (decoder_model_info_present) {
                buffer_delay_length = int(r.u(5, "buffer_delay_length_minus_1")) + 1;
                r.u(32, "num_units_in_decoding_tick");
                h.buffer_removal_time_length = int(r.u(5, "buffer_removal_time_length_minus_1")) + 1;
                h.frame_presentation_time_length = int(r.u(5, "frame_presentation_time_length_minus_1")) + 1;
            }
        }
        h.decoder_model_info_present_flag = decoder_model_info_present;
        const bool initial_display_delay_present = r.flag("initial_display_delay_present_flag");
        const int operating_points = int(r.u(5, "operating_points_cnt_minus_1")) + 1;
        h.operating_points = operating_points;
        for (int i = 0; i < operating_points; i++) {
            h.operating_point_idc[std::size_t(i)] = int(r.u(12, "operating_point_idc[i]"));
            if (r.u(5, "seq_level_idx[i]") > 7) r.u(1, "seq_tier[i]");
            if (decoder_model_info_present && r.flag("decoder_model_present_for_this_op[i]")) {
                h.decoder_model_present_for_this_op[std::size_t(i)] = 1;
                r.u(buffer_delay_length, "decoder_buffer_delay[i]");
                r.u(buffer_delay_length, "encoder_buffer_delay[i]");
                r.u(1, "low_delay_mode_flag[i]");
            }
            if (initial_display_delay_present && r.flag("initial_display_delay_present_for_this_op[i]"))
                r.u(4, "initial_display_delay_minus_1[i]");
        }
    }
    const int width_bits = int(r.u(4, "frame_width_bits_minus_1")) + 1;
    const int height_bits = int(r.u(4, "frame_height_bits_minus_1")) + 1;
    h.frame_width_bits = width_bits;
    h.frame_height_bits = height_bits;
    h.max_frame_width = int(r.u(width_bits, "max_frame_width_minus_1")) + 1;
    h.max_frame_height = int(r.u(height_bits, "max_frame_height_minus_1")) + 1;
    if (!reduced && r.flag("frame_id_numbers_present_flag")) {
        h.frame_id_numbers_present_flag = 1;
        h.delta_frame_id_length = int(r.u(4, "delta_frame_id_length_minus_2")) + 2;
        h.frame_id_length = int(r.u(3, "additional_frame_id_length_minus_1")) + 1 + h.delta_frame_id_length;
    }
    h.use_128x128_superblock = int(r.u(1, "use_128x128_superblock"));
    r.u(1, "enable_filter_intra");
    r.u(1, "enable_intra_edge_filter");
    if (!reduced) {
        r.u(1, "enable_interintra_compound");
        r.u(1, "enable_masked_compound");
        h.enable_warped_motion = int(r.u(1, "enable_warped_motion"));
        r.u(1, "enable_dual_filter");
        const bool order_hint = r.flag("enable_order_hint");
        h.enable_order_hint = order_hint;
        if (order_hint) {
            r.u(1, "enable_jnt_comp");
            h.enable_ref_frame_mvs = int(r.u(1, "enable_ref_frame_mvs"));
        }
        // seq_force_screen_content_tools is SELECT_SCREEN_CONTENT_TOOLS (2) when chosen per frame
        int force_screen_content_tools = 2;
        if (!r.flag("seq_choose_screen_content_tools"))
            force_screen_content_tools = int(r.u(1, "seq_force_screen_content_tools"));
        h.seq_force_screen_content_tools = force_screen_content_tools;
        h.seq_force_integer_mv = 2;
        if (force_screen_content_tools > 0 && !r.flag("seq_choose_integer_mv"))
            h.seq_force_integer_mv = int(r.u(1, "seq_force_integer_mv"));
        if (order_hint) h.order_hint_bits = int(r.u(3, "order_hint_bits_minus_1")) + 1;
    }
    h.enable_superres = int(r.u(1, "enable_superres"));
    h.enable_cdef = int(r.u(1, "enable_cdef"));
    h.enable_restoration = int(r.u(1, "enable_restoration"));
    read_color_config(r, h);
    h.film_grain_params_present = int(r.u(1, "film_grain_params_present"));
    return h;
}

}  // namespace filmgrain::bitstream

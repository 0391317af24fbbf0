#include "bitstream/h265_poc.hpp"

#include "filmgrain/error.hpp"
#include "bitstream/poc_syntax.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {
namespace {

// profile_tier_level(1, sps_max_sub_layers_minus1), H.265 7.3.3: skipped, its length
// depends only on which sub-layer profiles and levels are present.
void skip_profile_tier_level(BitReader& r, int max_sub_layers_minus1) {
    r.u(8, "general_profile_space/tier/idc");
    r.u(32, "general_profile_compatibility_flags");
    r.u(24, "general constraint flags");
    r.u(24, "general constraint flags");
    r.u(8, "general_level_idc");
    bool profile_present[8] = {}, level_present[8] = {};
    for (int i = 0; i < max_sub_layers_minus1; i++) {
        profile_present[i] = r.flag("sub_layer_profile_present_flag");
        level_present[i] = r.flag("sub_layer_level_present_flag");
    }
    if (max_sub_layers_minus1 > 0)
        for (int i = max_sub_layers_minus1; i < 8; i++) r.u(2, "reserved_zero_2bits");
    for (int i = 0; i < max_sub_layers_minus1; i++) {
        if (profile_present[i]) {
            r.u(24, "sub_layer profile");
            r.u(32, "sub_layer profile");
            r.u(32, "sub_layer profile");
        }
        if (level_present[i]) r.u(8, "sub_layer_level_idc");
    }
}

bool is_irap(int t) { return t >= 16 && t <= 23; }
bool is_idr(int t) { return t == 19 || t == 20; }
bool is_rasl(int t) { return t == 8 || t == 9; }
bool is_radl(int t) { return t == 6 || t == 7; }
// Sub-layer non-reference pictures: the even types up to RSV_VCL_N14 (7.4.2.2).
bool is_sub_layer_non_reference(int t) { return t <= 14 && t % 2 == 0; }

}  // namespace

void H265PocDecoder::parse_sps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(16, "nal_unit_header");
    r.u(4, "sps_video_parameter_set_id");
    const int max_sub_layers_minus1 = int(r.u(3, "sps_max_sub_layers_minus1"));
    if (max_sub_layers_minus1 > 6)
        throw Error(ErrorCode::kMalformedPayload,
                    out_of_range_message("sps_max_sub_layers_minus1", max_sub_layers_minus1, 0, 6));
    r.flag("sps_temporal_id_nesting_flag");
    skip_profile_tier_level(r, max_sub_layers_minus1);
    const uint32_t id = ue_in_range(r, "sps_seq_parameter_set_id", 15);
    Sps s;
    const uint32_t chroma_format_idc = ue_in_range(r, "chroma_format_idc", 3);
    if (chroma_format_idc == 3) s.separate_colour_plane = r.flag("separate_colour_plane_flag");
    r.ue("pic_width_in_luma_samples");
    r.ue("pic_height_in_luma_samples");
    if (r.flag("conformance_window_flag"))
        for (int i = 0; i < 4; i++) r.ue("conf_win_offset");
    ue_in_range(r, "bit_depth_luma_minus8", 8);
    ue_in_range(r, "bit_depth_chroma_minus8", 8);
    s.log2_max_poc_lsb = int(ue_in_range(r, "log2_max_pic_order_cnt_lsb_minus4", 12)) + 4;
    s.valid = true;
    sps_[id] = s;
}

void H265PocDecoder::parse_pps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(16, "nal_unit_header");
    const uint32_t id = ue_in_range(r, "pps_pic_parameter_set_id", 63);
    Pps p;
    p.sps_id = int(ue_in_range(r, "pps_seq_parameter_set_id", 15));
    p.dependent_slice_segments_enabled = r.flag("dependent_slice_segments_enabled_flag");
    p.output_flag_present = r.flag("output_flag_present_flag");
    p.num_extra_slice_header_bits = int(r.u(3, "num_extra_slice_header_bits"));
    p.valid = true;
    pps_[id] = p;
}

H265PictureOrder H265PocDecoder::picture(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(1, "forbidden_zero_bit");
    H265PictureOrder o;
    o.nal_unit_type = int(r.u(6, "nal_unit_type"));
    r.u(6, "nuh_layer_id");
    const int temporal_id = int(r.u(3, "nuh_temporal_id_plus1")) - 1;
    if (!r.flag("first_slice_segment_in_pic_flag"))
        throw Error(ErrorCode::kInvalidArgument, "slice segment is not the first of its picture");
    const int t = o.nal_unit_type;
    if (is_irap(t)) r.flag("no_output_of_prior_pics_flag");
    const uint32_t pps_id = ue_in_range(r, "slice_pic_parameter_set_id", 63);
    const Pps& pps = pps_[pps_id];
    if (!pps.valid)
        throw Error(ErrorCode::kMalformedPayload, "slice refers to PPS " + std::to_string(pps_id) + ", not received");
    const Sps& sps = sps_[pps.sps_id];
    if (!sps.valid)
        throw Error(ErrorCode::kMalformedPayload, "PPS " + std::to_string(pps_id) + " refers to SPS " +
                                                      std::to_string(pps.sps_id) + ", not received");
    if (pps.num_extra_slice_header_bits > 0) r.u(pps.num_extra_slice_header_bits, "slice_reserved_flag");
    ue_in_range(r, "slice_type", 2);
    bool pic_output_flag = true;
    if (pps.output_flag_present) pic_output_flag = r.flag("pic_output_flag");
    if (sps.separate_colour_plane) r.u(2, "colour_plane_id");
    int lsb = 0;
    if (!is_idr(t)) lsb = int(r.u(sps.log2_max_poc_lsb, "slice_pic_order_cnt_lsb"));

    // 8.1.3: IDR and BLA always start afresh; a CRA only when first in the stream or
    // after an end of sequence (HandleCraAsBlaFlag is an external means, taken as 0).
    o.irap = is_irap(t);
    if (o.irap) {
        o.no_rasl_output = is_idr(t) || (t >= 16 && t <= 18) || first_picture_ || after_eos_;
        last_irap_no_rasl_output_ = o.no_rasl_output;
        o.starts_sequence = o.no_rasl_output;
    } else if (first_picture_ || after_eos_) {
        o.starts_sequence = true;  // a stream not starting with an IRAP: counted from here
    }
    first_picture_ = false;
    after_eos_ = false;

    // 8.3.1
    const int max_lsb = 1 << sps.log2_max_poc_lsb;
    int msb = 0;
    if (!(o.irap && o.no_rasl_output)) {
        const int prev_lsb = prev_tid0_poc_ & (max_lsb - 1);
        msb = poc_msb(prev_tid0_poc_ - prev_lsb, prev_lsb, lsb, max_lsb);
    }
    o.poc = msb + lsb;
    if (temporal_id == 0 && !is_rasl(t) && !is_radl(t) && !is_sub_layer_non_reference(t)) prev_tid0_poc_ = o.poc;
    // 8.1.3: RASL pictures of an IRAP with NoRaslOutputFlag = 1 are not output.
    o.output = pic_output_flag && !(is_rasl(t) && last_irap_no_rasl_output_);
    return o;
}

}  // namespace filmgrain::bitstream

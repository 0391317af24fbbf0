#include "bitstream/h264_poc.hpp"

#include <algorithm>

#include "filmgrain/error.hpp"
#include "bitstream/poc_syntax.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {
namespace {

bool has_chroma_format_syntax(int profile_idc) {
    switch (profile_idc) {
    case 100: case 110: case 122: case 244: case 44: case 83: case 86: case 118: case 128: case 138: case 139:
    case 134: case 135:
        return true;
    default:
        return false;
    }
}

// scaling_list() (7.3.2.1.1.1): only its length matters here.
void skip_scaling_list(BitReader& r, int size) {
    int last = 8, next = 8;
    for (int j = 0; j < size; j++) {
        if (next != 0) {
            const int delta = r.se("delta_scale");
            if (delta < -128 || delta > 127)
                throw Error(ErrorCode::kMalformedPayload, out_of_range_message("delta_scale", delta, -128, 127));
            next = (last + delta + 256) % 256;
        }
        last = next == 0 ? last : next;
    }
}

}  // namespace

void H264PocDecoder::parse_sps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(8, "nal_unit_header");
    const int profile_idc = int(r.u(8, "profile_idc"));
    r.u(8, "constraint_set_flags");
    r.u(8, "level_idc");
    const uint32_t id = ue_in_range(r, "seq_parameter_set_id", 31);
    Sps s;
    if (has_chroma_format_syntax(profile_idc)) {
        const uint32_t chroma_format_idc = ue_in_range(r, "chroma_format_idc", 3);
        if (chroma_format_idc == 3) s.separate_colour_plane = r.flag("separate_colour_plane_flag");
        ue_in_range(r, "bit_depth_luma_minus8", 6);
        ue_in_range(r, "bit_depth_chroma_minus8", 6);
        r.flag("qpprime_y_zero_transform_bypass_flag");
        if (r.flag("seq_scaling_matrix_present_flag")) {
            const int lists = chroma_format_idc != 3 ? 8 : 12;
            for (int i = 0; i < lists; i++)
                if (r.flag("seq_scaling_list_present_flag")) skip_scaling_list(r, i < 6 ? 16 : 64);
        }
    }
    s.log2_max_frame_num = int(ue_in_range(r, "log2_max_frame_num_minus4", 12)) + 4;
    s.poc_type = int(ue_in_range(r, "pic_order_cnt_type", 2));
    if (s.poc_type == 0) {
        s.log2_max_poc_lsb = int(ue_in_range(r, "log2_max_pic_order_cnt_lsb_minus4", 12)) + 4;
    } else if (s.poc_type == 1) {
        s.delta_pic_order_always_zero = r.flag("delta_pic_order_always_zero_flag");
        s.offset_for_non_ref_pic = r.se("offset_for_non_ref_pic");
        s.offset_for_top_to_bottom_field = r.se("offset_for_top_to_bottom_field");
        const uint32_t n = ue_in_range(r, "num_ref_frames_in_pic_order_cnt_cycle", 255);
        for (uint32_t i = 0; i < n; i++) s.offset_for_ref_frame.push_back(r.se("offset_for_ref_frame"));
    }
    r.ue("max_num_ref_frames");
    r.flag("gaps_in_frame_num_value_allowed_flag");
    r.ue("pic_width_in_mbs_minus1");
    r.ue("pic_height_in_map_units_minus1");
    s.frame_mbs_only = r.flag("frame_mbs_only_flag");
    s.valid = true;
    sps_[id] = s;
}

void H264PocDecoder::parse_pps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(8, "nal_unit_header");
    const uint32_t id = ue_in_range(r, "pic_parameter_set_id", 255);
    Pps p;
    p.sps_id = int(ue_in_range(r, "seq_parameter_set_id", 31));
    r.flag("entropy_coding_mode_flag");
    p.bottom_field_pic_order_in_frame_present = r.flag("bottom_field_pic_order_in_frame_present_flag");
    p.valid = true;
    pps_[id] = p;
}

H264PocDecoder::SliceFields H264PocDecoder::read_slice(const std::vector<uint8_t>& rbsp) const {
    BitReader r(rbsp);
    r.u(1, "forbidden_zero_bit");
    SliceFields f;
    f.o.nal_ref_idc = int(r.u(2, "nal_ref_idc"));
    const int nal_unit_type = int(r.u(5, "nal_unit_type"));
    f.o.idr = nal_unit_type == 5;
    f.o.first_mb_in_slice = int(r.ue("first_mb_in_slice"));
    ue_in_range(r, "slice_type", 9);
    f.o.pps_id = int(ue_in_range(r, "pic_parameter_set_id", 255));
    const Pps& pps = pps_[f.o.pps_id];
    if (!pps.valid)
        throw Error(ErrorCode::kMalformedPayload, "slice refers to PPS " + std::to_string(f.o.pps_id) + ", not received");
    const Sps& sps = sps_[pps.sps_id];
    if (!sps.valid)
        throw Error(ErrorCode::kMalformedPayload, "PPS " + std::to_string(f.o.pps_id) + " refers to SPS " +
                                                      std::to_string(pps.sps_id) + ", not received");
    f.sps = &sps;
    if (sps.separate_colour_plane) r.u(2, "colour_plane_id");
    f.o.frame_num = int(r.u(sps.log2_max_frame_num, "frame_num"));
    if (!sps.frame_mbs_only) {
        f.field_pic = r.flag("field_pic_flag");
        if (f.field_pic) r.flag("bottom_field_flag");
    }
    f.o.idr_pic_id = latest_idr_pic_id_;
    if (f.o.idr) f.o.idr_pic_id = int(ue_in_range(r, "idr_pic_id", 65535));
    if (sps.poc_type == 0) {
        f.poc_lsb = int(r.u(sps.log2_max_poc_lsb, "pic_order_cnt_lsb"));
        if (pps.bottom_field_pic_order_in_frame_present && !f.field_pic) f.delta_bottom = r.se("delta_pic_order_cnt_bottom");
    }
    if (sps.poc_type == 1 && !sps.delta_pic_order_always_zero) {
        f.delta[0] = r.se("delta_pic_order_cnt[0]");
        if (pps.bottom_field_pic_order_in_frame_present && !f.field_pic) f.delta[1] = r.se("delta_pic_order_cnt[1]");
    }
    return f;
}

H264PictureOrder H264PocDecoder::peek_slice(const std::vector<uint8_t>& rbsp) const { return read_slice(rbsp).o; }

H264PictureOrder H264PocDecoder::picture(const std::vector<uint8_t>& rbsp) {
    SliceFields f = read_slice(rbsp);
    const Sps& sps = *f.sps;
    H264PictureOrder o = f.o;
    if (o.idr) latest_idr_pic_id_ = o.idr_pic_id;
    const long long max_frame_num = 1LL << sps.log2_max_frame_num;

    // FrameNumOffset, shared by types 1 and 2 (8-6, 8-11)
    long long frame_num_offset = 0;
    if (!o.idr) frame_num_offset = prev_frame_num_offset_ + (prev_frame_num_ > o.frame_num ? max_frame_num : 0);

    long long top = 0, bottom = 0;
    if (sps.poc_type == 0) {
        const int max_lsb = 1 << sps.log2_max_poc_lsb;
        const int prev_msb = o.idr ? 0 : prev_poc_msb_, prev_lsb = o.idr ? 0 : prev_poc_lsb_;
        const int msb = poc_msb(prev_msb, prev_lsb, f.poc_lsb, max_lsb);
        top = msb + f.poc_lsb;
        bottom = top + f.delta_bottom;
        if (o.nal_ref_idc != 0) {
            prev_poc_msb_ = msb;
            prev_poc_lsb_ = f.poc_lsb;
        }
    } else if (sps.poc_type == 1) {
        const long long n = static_cast<long long>(sps.offset_for_ref_frame.size());
        long long abs_frame_num = n != 0 ? frame_num_offset + o.frame_num : 0;
        if (o.nal_ref_idc == 0 && abs_frame_num > 0) abs_frame_num--;
        long long expected = 0;
        if (abs_frame_num > 0) {
            long long per_cycle = 0;
            for (int v : sps.offset_for_ref_frame) per_cycle += v;
            const long long cycle = (abs_frame_num - 1) / n, in_cycle = (abs_frame_num - 1) % n;
            expected = cycle * per_cycle;
            for (long long i = 0; i <= in_cycle; i++) expected += sps.offset_for_ref_frame[std::size_t(i)];
        }
        if (o.nal_ref_idc == 0) expected += sps.offset_for_non_ref_pic;
        top = expected + f.delta[0];
        bottom = top + sps.offset_for_top_to_bottom_field + f.delta[1];
    } else {
        long long temp = 0;
        if (!o.idr) temp = o.nal_ref_idc == 0 ? 2 * (frame_num_offset + o.frame_num) - 1 : 2 * (frame_num_offset + o.frame_num);
        top = bottom = temp;
    }
    prev_frame_num_offset_ = int(frame_num_offset);
    prev_frame_num_ = o.frame_num;
    if (!f.field_pic) o.poc = int(std::min(top, bottom));
    return o;
}

}  // namespace filmgrain::bitstream

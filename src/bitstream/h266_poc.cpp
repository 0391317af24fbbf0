#include "bitstream/h266_poc.hpp"

#include <string>

#include "filmgrain/error.hpp"
#include "bitstream/poc_syntax.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {
namespace {

void skip_bits(BitReader& r, std::size_t n, const char* field) {
    for (; n >= 32; n -= 32) r.u(32, field);
    if (n) r.u(int(n), field);
}

void align(BitReader& r, const char* field) {
    if (!r.byte_aligned()) r.u(int(8 - r.bit_position() % 8), field);
}

// profile_tier_level(1, sps_max_sublayers_minus1), H.266 7.3.3.1, with
// general_constraints_info() of 7.3.3.2 (71 flag bits in this version, then
// gci_num_reserved_bits): skipped, only its length matters here.
void skip_profile_tier_level(BitReader& r, int max_sublayers_minus1) {
    r.u(8, "general_profile_idc/general_tier_flag");
    r.u(8, "general_level_idc");
    r.u(2, "ptl_frame_only_constraint_flag/ptl_multilayer_enabled_flag");
    if (r.flag("gci_present_flag")) {
        skip_bits(r, 71, "general_constraints_info");
        skip_bits(r, r.u(8, "gci_num_reserved_bits"), "gci_reserved_zero_bit");
    }
    align(r, "gci_alignment_zero_bit");
    bool level_present[8] = {};
    for (int i = max_sublayers_minus1 - 1; i >= 0; i--) level_present[i] = r.flag("ptl_sublayer_level_present_flag");
    align(r, "ptl_reserved_zero_bit");
    for (int i = max_sublayers_minus1 - 1; i >= 0; i--)
        if (level_present[i]) r.u(8, "sublayer_level_idc");
    const uint32_t sub_profiles = r.u(8, "ptl_num_sub_profiles");
    for (uint32_t i = 0; i < sub_profiles; i++) r.u(32, "general_sub_profile_idc");
}

int ceil_log2(uint32_t v) {
    int n = 0;
    while ((uint64_t(1) << n) < v) n++;
    return n;
}

// H.266 Table 5: VCL types.
bool is_radl(int t) { return t == 2; }
bool is_rasl(int t) { return t == 3; }
bool is_idr(int t) { return t == 7 || t == 8; }
bool is_cra(int t) { return t == 9; }
bool is_gdr(int t) { return t == 10; }

}  // namespace

void H266PocDecoder::parse_sps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(16, "nal_unit_header");
    const uint32_t id = r.u(4, "sps_seq_parameter_set_id");
    r.u(4, "sps_video_parameter_set_id");
    const int max_sublayers_minus1 = int(r.u(3, "sps_max_sublayers_minus1"));
    if (max_sublayers_minus1 > 6)
        throw Error(ErrorCode::kMalformedPayload,
                    out_of_range_message("sps_max_sublayers_minus1", max_sublayers_minus1, 0, 6));
    r.u(2, "sps_chroma_format_idc");
    const int ctb_log2 = int(r.u(2, "sps_log2_ctu_size_minus5")) + 5;
    if (r.flag("sps_ptl_dpb_hrd_params_present_flag")) skip_profile_tier_level(r, max_sublayers_minus1);
    r.flag("sps_gdr_enabled_flag");
    if (r.flag("sps_ref_pic_resampling_enabled_flag")) r.flag("sps_res_change_in_clvs_allowed_flag");
    const uint32_t width = r.ue("sps_pic_width_max_in_luma_samples");
    const uint32_t height = r.ue("sps_pic_height_max_in_luma_samples");
    if (r.flag("sps_conformance_window_flag"))
        for (int i = 0; i < 4; i++) r.ue("sps_conf_win_offset");
    if (r.flag("sps_subpic_info_present_flag")) {
        const uint32_t ctb = 1u << ctb_log2;
        const uint32_t num_minus1 = ue_in_range(r, "sps_num_subpics_minus1", 599);
        bool independent = true, same_size = false;
        if (num_minus1 > 0) {
            independent = r.flag("sps_independent_subpics_flag");
            same_size = r.flag("sps_subpic_same_size_flag");
        }
        const int x_bits = ceil_log2((width + ctb - 1) / ctb), y_bits = ceil_log2((height + ctb - 1) / ctb);
        for (uint32_t i = 0; num_minus1 > 0 && i <= num_minus1; i++) {
            if (!same_size || i == 0) {
                if (i > 0 && width > ctb) skip_bits(r, x_bits, "sps_subpic_ctu_top_left_x");
                if (i > 0 && height > ctb) skip_bits(r, y_bits, "sps_subpic_ctu_top_left_y");
                if (i < num_minus1 && width > ctb) skip_bits(r, x_bits, "sps_subpic_width_minus1");
                if (i < num_minus1 && height > ctb) skip_bits(r, y_bits, "sps_subpic_height_minus1");
            }
            if (!independent) r.u(2, "sps_subpic_treated_as_pic_flag/sps_loop_filter_across_subpic_enabled_flag");
        }
        const uint32_t id_len = ue_in_range(r, "sps_subpic_id_len_minus1", 15) + 1;
        if (r.flag("sps_subpic_id_mapping_explicitly_signalled_flag") && r.flag("sps_subpic_id_mapping_present_flag"))
            skip_bits(r, std::size_t(id_len) * (num_minus1 + 1), "sps_subpic_id");
    }
    ue_in_range(r, "sps_bitdepth_minus8", 8);
    r.u(2, "sps_entropy_coding_sync_enabled_flag/sps_entry_point_offsets_present_flag");
    Sps s;
    s.log2_max_poc_lsb = int(r.u(4, "sps_log2_max_pic_order_cnt_lsb_minus4")) + 4;
    if (s.log2_max_poc_lsb > 16)
        throw Error(ErrorCode::kMalformedPayload,
                    out_of_range_message("sps_log2_max_pic_order_cnt_lsb_minus4", s.log2_max_poc_lsb - 4, 0, 12));
    s.poc_msb_cycle = r.flag("sps_poc_msb_cycle_flag");
    if (s.poc_msb_cycle) {
        const int lim = 32 - s.log2_max_poc_lsb;
        s.poc_msb_cycle_len = int(ue_in_range(r, "sps_poc_msb_cycle_len_minus1", uint32_t(lim - 1))) + 1;
    }
    const int extra_ph_bytes = int(r.u(2, "sps_num_extra_ph_bytes"));
    for (int i = 0; i < extra_ph_bytes * 8; i++) s.num_extra_ph_bits += r.flag("sps_extra_ph_bit_present_flag");
    s.valid = true;
    sps_[id] = s;
}

void H266PocDecoder::parse_pps(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(16, "nal_unit_header");
    const uint32_t id = r.u(6, "pps_pic_parameter_set_id");
    Pps p;
    p.sps_id = int(r.u(4, "pps_seq_parameter_set_id"));
    p.valid = true;
    pps_[id] = p;
}

H266PocDecoder::PictureHeader H266PocDecoder::read_picture_header(BitReader& r) const {
    PictureHeader h;
    h.gdr_or_irap = r.flag("ph_gdr_or_irap_pic_flag");
    r.flag("ph_non_ref_pic_flag");
    if (h.gdr_or_irap) h.gdr = r.flag("ph_gdr_pic_flag");
    if (r.flag("ph_inter_slice_allowed_flag")) r.flag("ph_intra_slice_allowed_flag");
    const uint32_t pps_id = ue_in_range(r, "ph_pic_parameter_set_id", 63);
    const Pps& pps = pps_[pps_id];
    if (!pps.valid)
        throw Error(ErrorCode::kMalformedPayload, "picture header refers to PPS " + std::to_string(pps_id) + ", not received");
    const Sps& sps = sps_[pps.sps_id];
    if (!sps.valid)
        throw Error(ErrorCode::kMalformedPayload, "PPS " + std::to_string(pps_id) + " refers to SPS " +
                                                      std::to_string(pps.sps_id) + ", not received");
    h.log2_max_poc_lsb = sps.log2_max_poc_lsb;
    h.lsb = int(r.u(sps.log2_max_poc_lsb, "ph_pic_order_cnt_lsb"));
    if (h.gdr) r.ue("ph_recovery_poc_cnt");
    if (sps.num_extra_ph_bits) skip_bits(r, std::size_t(sps.num_extra_ph_bits), "ph_extra_bit");
    if (sps.poc_msb_cycle && r.flag("ph_poc_msb_cycle_present_flag"))
        h.msb_cycle = int(r.u(sps.poc_msb_cycle_len, "ph_poc_msb_cycle_val"));
    return h;
}

void H266PocDecoder::parse_picture_header_unit(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(16, "nal_unit_header");
    pending_.reset();
    pending_ = read_picture_header(r);
}

H266PictureOrder H266PocDecoder::picture(const std::vector<uint8_t>& rbsp) {
    BitReader r(rbsp);
    r.u(8, "forbidden_zero_bit/nuh_reserved_zero_bit/nuh_layer_id");
    H266PictureOrder o;
    o.nal_unit_type = int(r.u(5, "nal_unit_type"));
    const int temporal_id = int(r.u(3, "nuh_temporal_id_plus1")) - 1;
    PictureHeader h;
    if (r.flag("sh_picture_header_in_slice_header_flag")) {
        h = read_picture_header(r);
    } else if (pending_) {
        h = *pending_;
    } else {
        throw Error(ErrorCode::kMalformedPayload, "slice without a picture header (no PH NAL unit before it)");
    }
    pending_.reset();
    const int t = o.nal_unit_type;

    // 8.1.1: an IDR always starts a CLVS; a CRA or GDR when first in the stream or after an
    // end of sequence (HandleCraAsClvsStartFlag, an external means, taken as 0).
    o.clvs_start = is_idr(t) || ((is_cra(t) || is_gdr(t)) && (first_picture_ || after_eos_));
    if (is_cra(t)) last_cra_starts_clvs_ = o.clvs_start;
    if (is_idr(t) || is_gdr(t)) last_cra_starts_clvs_ = false;
    const bool counted_from_here = !o.clvs_start && (first_picture_ || after_eos_);
    first_picture_ = false;
    after_eos_ = false;

    // 8.3.1
    const int max_lsb = 1 << h.log2_max_poc_lsb;
    int msb = 0;
    if (h.msb_cycle) {
        msb = *h.msb_cycle * max_lsb;
    } else if (!o.clvs_start && !counted_from_here) {
        const int prev_lsb = prev_tid0_poc_ & (max_lsb - 1);
        msb = poc_msb(prev_tid0_poc_ - prev_lsb, prev_lsb, h.lsb, max_lsb);
    }
    o.poc = msb + h.lsb;
    if (temporal_id == 0 && !is_rasl(t) && !is_radl(t)) prev_tid0_poc_ = o.poc;
    // 8.1.1: RASL pictures associated with a CRA that starts a CLVS are not output.
    o.output = !(is_rasl(t) && last_cra_starts_clvs_);
    return o;
}

}  // namespace filmgrain::bitstream

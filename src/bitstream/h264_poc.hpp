// H.264 picture order count of frame pictures from the SPS, PPS and slice header
// (H.264 7.3.2.1.1, 7.3.2.2, 7.3.3, 8.2.1). Supported: pic_order_cnt_type 0, 1 and 2 for
// frames (frame_mbs_only or field_pic_flag = 0), with IDR pictures resetting the state.
// Not supported: field pictures (reported without a POC) and memory_management_control_
// operation 5, which sits behind ref_pic_list_modification and pred_weight_table in the
// slice header; a stream using MMCO 5 gets POCs continuing across that picture.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace filmgrain::bitstream {

struct H264PictureOrder {
    std::optional<int> poc;  // PicOrderCnt = Min(TopFieldOrderCnt, BottomFieldOrderCnt) of the frame
    bool idr = false;
    int idr_pic_id = 0;      // of this IDR picture, or of the latest IDR picture
    int first_mb_in_slice = 0;
    int frame_num = 0;
    int pps_id = 0;
    int nal_ref_idc = 0;
};

class H264PocDecoder {
public:
    // `rbsp` is the whole NAL unit without emulation prevention (header byte included).
    void parse_sps(const std::vector<uint8_t>& rbsp);
    void parse_pps(const std::vector<uint8_t>& rbsp);
    // The slice header only (first_mb_in_slice .. idr_pic_id), no state change.
    H264PictureOrder peek_slice(const std::vector<uint8_t>& rbsp) const;
    // The first slice of a picture: derives the POC and advances the state.
    H264PictureOrder picture(const std::vector<uint8_t>& rbsp);

private:
    struct Sps {
        bool valid = false;
        bool separate_colour_plane = false;
        int log2_max_frame_num = 4;
        int poc_type = 0;
        int log2_max_poc_lsb = 4;
        bool delta_pic_order_always_zero = false;
        int offset_for_non_ref_pic = 0;
        int offset_for_top_to_bottom_field = 0;
        std::vector<int> offset_for_ref_frame;
        bool frame_mbs_only = true;
    };
    struct Pps {
        bool valid = false;
        int sps_id = 0;
        bool bottom_field_pic_order_in_frame_present = false;
    };
    struct SliceFields {
        H264PictureOrder o;
        bool field_pic = false;
        int poc_lsb = 0;
        int delta_bottom = 0;
        int delta[2] = {0, 0};
        const Sps* sps = nullptr;
    };
    SliceFields read_slice(const std::vector<uint8_t>& rbsp) const;

    std::array<Sps, 32> sps_{};
    std::array<Pps, 256> pps_{};
    int latest_idr_pic_id_ = 0;
    // state of the previous (reference) picture, 8.2.1.1 / 8.2.1.2
    int prev_poc_msb_ = 0, prev_poc_lsb_ = 0;
    int prev_frame_num_offset_ = 0, prev_frame_num_ = 0;
};

}  // namespace filmgrain::bitstream

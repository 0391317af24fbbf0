// H.265 picture order count from the parameter sets and the first slice segment header
// of each picture (H.265 7.3.2.2, 7.3.2.3, 7.3.6.1, 8.1.3, 8.3.1). Only the syntax up to
// the fields POC needs is read: SPS up to log2_max_pic_order_cnt_lsb_minus4, PPS up to
// num_extra_slice_header_bits, slice header up to slice_pic_order_cnt_lsb.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace filmgrain::bitstream {

struct H265PictureOrder {
    int poc = 0;
    int nal_unit_type = 0;
    bool irap = false;
    bool no_rasl_output = false;  // NoRaslOutputFlag of an IRAP picture
    bool output = true;           // PicOutputFlag (RASL after a NoRaslOutputFlag IRAP, pic_output_flag)
    bool starts_sequence = false; // an IRAP with NoRaslOutputFlag = 1: a new coded video sequence
};

class H265PocDecoder {
public:
    // `rbsp` is the whole NAL unit without emulation prevention (header included).
    // Throw filmgrain::Error on a truncated or out-of-range field.
    void parse_sps(const std::vector<uint8_t>& rbsp);
    void parse_pps(const std::vector<uint8_t>& rbsp);
    // An end of sequence NAL unit: the next picture gets NoRaslOutputFlag = 1.
    void end_of_sequence() { after_eos_ = true; }
    // The first slice segment of a picture (first_slice_segment_in_pic_flag = 1).
    H265PictureOrder picture(const std::vector<uint8_t>& slice_rbsp);

private:
    struct Sps {
        bool valid = false;
        bool separate_colour_plane = false;
        int log2_max_poc_lsb = 4;
    };
    struct Pps {
        bool valid = false;
        int sps_id = 0;
        bool dependent_slice_segments_enabled = false;
        bool output_flag_present = false;
        int num_extra_slice_header_bits = 0;
    };
    std::array<Sps, 16> sps_{};
    std::array<Pps, 64> pps_{};
    bool first_picture_ = true;
    bool after_eos_ = false;
    bool last_irap_no_rasl_output_ = true;
    int prev_tid0_poc_ = 0;
};

}  // namespace filmgrain::bitstream

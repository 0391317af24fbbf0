// NAL unit headers and the nal_unit_type classes access-unit splitting needs
// (H.264 7.3.1 / 7.4.1.2.3, H.265 7.3.1.2 / 7.4.2.4.4, H.266 7.3.1.2 / 7.4.2.4.3).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace filmgrain::bitstream {

enum class NalCodec { kH264, kH265, kH266 };

struct NalHeader {
    int type = 0;
    int layer_id = 0;
    int temporal_id = 0;
    int ref_idc = 0;        // H.264 nal_ref_idc
    int header_bytes = 1;
    bool forbidden_bit = false;
};

// False when the NAL unit is shorter than its header.
bool parse_nal_header(NalCodec codec, const uint8_t* nal, std::size_t size, NalHeader& h);

bool is_vcl(NalCodec codec, int type);
bool is_sps(NalCodec codec, int type);
bool is_pps(NalCodec codec, int type);
// Every parameter set a later picture may refer to: SPS, PPS, H.265/H.266 VPS, H.266 APS.
bool is_parameter_set(NalCodec codec, int type);
// An IDR picture: H.264 nal_unit_type 5, H.265/H.266 IDR_W_RADL and IDR_N_LP. Decoding can
// start at it: no picture after it in decoding order refers to one before it.
bool is_idr(NalCodec codec, int type);
bool is_prefix_sei(NalCodec codec, int type);
bool is_suffix_sei(NalCodec codec, int type);
bool is_end_of_sequence(NalCodec codec, int type);
// A NAL unit of this type, after a VCL NAL unit, begins the next access unit.
bool starts_access_unit(NalCodec codec, int type);
// For a VCL NAL unit: does it begin a new picture? Reads the first slice header bits
// (H.264 first_mb_in_slice == 0, H.265 first_slice_segment_in_pic_flag, H.266
// sh_picture_header_in_slice_header_flag; with a picture header NAL unit the PH itself
// starts the access unit).
bool vcl_starts_picture(NalCodec codec, const uint8_t* rbsp, std::size_t size);

std::string nal_type_name(NalCodec codec, int type);

}  // namespace filmgrain::bitstream

#include "bitstream/nal_header.hpp"

namespace filmgrain::bitstream {

bool parse_nal_header(NalCodec codec, const uint8_t* nal, std::size_t size, NalHeader& h) {
    h = NalHeader{};
    if (codec == NalCodec::kH264) {
        if (size < 1) return false;
        h.forbidden_bit = nal[0] & 0x80;
        h.ref_idc = (nal[0] >> 5) & 3;
        h.type = nal[0] & 31;
        h.header_bytes = 1;
        return true;
    }
    if (size < 2) return false;
    h.header_bytes = 2;
    h.forbidden_bit = nal[0] & 0x80;
    if (codec == NalCodec::kH265) {
        h.type = (nal[0] >> 1) & 63;
        h.layer_id = ((nal[0] & 1) << 5) | (nal[1] >> 3);
    } else {
        h.layer_id = nal[0] & 63;
        h.type = nal[1] >> 3;
    }
    h.temporal_id = (nal[1] & 7) - 1;
    return true;
}

bool is_vcl(NalCodec codec, int t) {
    switch (codec) {
    case NalCodec::kH264: return t == 1 || t == 5;  // data partitions 2..4 are not followed
    case NalCodec::kH265: return t <= 31;
    case NalCodec::kH266: return t <= 11;
    }
    return false;
}
bool is_sps(NalCodec codec, int t) { return t == (codec == NalCodec::kH264 ? 7 : codec == NalCodec::kH265 ? 33 : 15); }
bool is_pps(NalCodec codec, int t) { return t == (codec == NalCodec::kH264 ? 8 : codec == NalCodec::kH265 ? 34 : 16); }
bool is_parameter_set(NalCodec codec, int t) {
    if (is_sps(codec, t) || is_pps(codec, t)) return true;
    if (codec == NalCodec::kH265) return t == 32;               // VPS
    if (codec == NalCodec::kH266) return t == 14 || t == 17 || t == 18;  // VPS, prefix and suffix APS
    return false;
}
bool is_idr(NalCodec codec, int t) {
    if (codec == NalCodec::kH264) return t == 5;
    return codec == NalCodec::kH265 ? t == 19 || t == 20 : t == 7 || t == 8;
}
bool is_prefix_sei(NalCodec codec, int t) { return t == (codec == NalCodec::kH264 ? 6 : codec == NalCodec::kH265 ? 39 : 23); }
bool is_suffix_sei(NalCodec codec, int t) { return codec != NalCodec::kH264 && t == (codec == NalCodec::kH265 ? 40 : 24); }
bool is_end_of_sequence(NalCodec codec, int t) {
    return t == (codec == NalCodec::kH264 ? 10 : codec == NalCodec::kH265 ? 36 : 21);
}

bool starts_access_unit(NalCodec codec, int t) {
    switch (codec) {
    case NalCodec::kH264:  // 7.4.1.2.3: AUD, SPS, PPS, SEI, 14..18
        return t == 9 || t == 7 || t == 8 || t == 6 || (t >= 14 && t <= 18);
    case NalCodec::kH265:  // 7.4.2.4.4: AUD, VPS, SPS, PPS, prefix SEI, 41..44, 48..55
        return (t >= 32 && t <= 35) || t == 39 || (t >= 41 && t <= 44) || (t >= 48 && t <= 55);
    case NalCodec::kH266:  // 7.4.2.4.3: AUD, OPI, DCI, VPS, SPS, PPS, prefix APS, PH, prefix SEI, 26, 28, 29
        return (t >= 12 && t <= 17) || t == 19 || t == 20 || t == 23 || t == 26 || t == 28 || t == 29;
    }
    return false;
}

bool vcl_starts_picture(NalCodec codec, const uint8_t* rbsp, std::size_t size) {
    switch (codec) {
    case NalCodec::kH264:
        // first_mb_in_slice ue(v) == 0 is the single bit '1'
        return size >= 2 && (rbsp[1] & 0x80);
    case NalCodec::kH265: return size >= 3 && (rbsp[2] & 0x80);
    case NalCodec::kH266: return size >= 3 && (rbsp[2] & 0x80);
    }
    return false;
}

std::string nal_type_name(NalCodec codec, int t) {
    if (codec == NalCodec::kH264) {
        if (t == 5) return "IDR";
        if (t == 1) return "non-IDR";
        return "type " + std::to_string(t);
    }
    if (codec == NalCodec::kH265) {
        static const char* const names[] = {"TRAIL_N", "TRAIL_R", "TSA_N",  "TSA_R",     "STSA_N",    "STSA_R",
                                            "RADL_N",  "RADL_R",  "RASL_N", "RASL_R",    "RSV_VCL_N10", "RSV_VCL_R11",
                                            "RSV_VCL_N12", "RSV_VCL_R13", "RSV_VCL_N14", "RSV_VCL_R15", "BLA_W_LP",
                                            "BLA_W_RADL", "BLA_N_LP", "IDR_W_RADL", "IDR_N_LP", "CRA_NUT"};
        if (t >= 0 && t < int(sizeof names / sizeof names[0])) return names[t];
        return "type " + std::to_string(t);
    }
    static const char* const names[] = {"TRAIL", "STSA", "RADL", "RASL", "RSV_VCL_4", "RSV_VCL_5", "RSV_VCL_6",
                                        "IDR_W_RADL", "IDR_N_LP", "CRA", "GDR"};
    if (t >= 0 && t < int(sizeof names / sizeof names[0])) return names[t];
    return "type " + std::to_string(t);
}

}  // namespace filmgrain::bitstream

// H.266 picture order count from the SPS, the PPS and the picture header (H.266 7.3.2.4,
// 7.3.2.5, 7.3.2.8, 7.3.7.1, 8.3.1). Only the syntax up to the fields POC needs is read:
// SPS up to sps_num_extra_ph_bytes (profile_tier_level, subpicture layout and extra bits
// included, since their lengths move what follows), PPS up to pps_seq_parameter_set_id,
// picture header up to ph_poc_msb_cycle_val. The picture header comes either in its own
// PH NAL unit before the slices or inside the first slice
// (sh_picture_header_in_slice_header_flag).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace filmgrain {
class BitReader;
}

namespace filmgrain::bitstream {

struct H266PictureOrder {
    int poc = 0;
    int nal_unit_type = 0;
    bool clvs_start = false;  // IRAP or GDR with NoOutputBeforeRecoveryFlag = 1 (a new CLVS)
    bool output = true;       // false for RASL pictures of a CLVS-starting CRA (8.1.1)
};

class H266PocDecoder {
public:
    // Whole NAL units without emulation prevention (the 2-byte header included). Throw
    // filmgrain::Error on a truncated or out-of-range field, or on syntax not followed.
    void parse_sps(const std::vector<uint8_t>& rbsp);
    void parse_pps(const std::vector<uint8_t>& rbsp);
    // A PH NAL unit: the header is kept for the picture whose first slice comes next.
    void parse_picture_header_unit(const std::vector<uint8_t>& rbsp);
    // An end of sequence NAL unit: the next CRA or GDR starts a new CLVS.
    void end_of_sequence() { after_eos_ = true; }
    // The first slice of a picture: with its picture header inside, or after a PH unit.
    H266PictureOrder picture(const std::vector<uint8_t>& slice_rbsp);
    bool header_pending() const { return pending_.has_value(); }

private:
    struct Sps {
        bool valid = false;
        int log2_max_poc_lsb = 4;
        bool poc_msb_cycle = false;
        int poc_msb_cycle_len = 1;
        int num_extra_ph_bits = 0;
    };
    struct Pps {
        bool valid = false;
        int sps_id = 0;
    };
    struct PictureHeader {
        bool gdr_or_irap = false;
        bool gdr = false;
        int lsb = 0;
        std::optional<int> msb_cycle;
        int log2_max_poc_lsb = 4;
    };
    PictureHeader read_picture_header(BitReader& r) const;

    std::array<Sps, 16> sps_{};
    std::array<Pps, 64> pps_{};
    std::optional<PictureHeader> pending_;
    bool first_picture_ = true;
    bool after_eos_ = false;
    bool last_cra_starts_clvs_ = false;
    int prev_tid0_poc_ = 0;
};

}  // namespace filmgrain::bitstream

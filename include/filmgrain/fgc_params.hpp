// The film grain characteristics SEI message (payloadType 19) as signalled,
// named after its syntax elements (H.274 / VSEI 8.5, H.265 D.2.20, H.264 D.1.21).
// Nothing here is inferred or converted: that is src/fgc/params_resolution's job.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace filmgrain {

enum class FgcCodec : int { kAvc = 0, kHevc = 1, kVvc = 2 };

// Which bit-exact behaviour of the frequency-filtering model to reproduce.
//  kRdd5: SMPTE RDD 5 (HM-2020 Dolby implementation): RDD 5 matrix, seed from
//         POC + (idr_pic_id << 5), 8x8 adaptation at every picture size.
//  kFfmpeg: what FFmpeg >= 6.1 (h274.c) outputs: rdd5 except that cut-offs not signalled
//         are 0 (clipped to 2), a block edge whose right block matches no interval is not
//         deblocked (one whose left block matches none is, against zero grain), cut-offs
//         are clipped to 2..14, intervals may overlap (the first wins) and blending_mode_id
//         and a separate colour description are ignored. FFmpeg adds grain to the coded
//         picture before the conformance-window crop, so partial edge blocks average
//         samples of the coded picture: give the decoder's uncropped picture and crop after
//         (filmgrain decode does).
//  kVtm:  HM/VTM master (JVET-X0048): VVC DCT-2 matrix, POC-only seed, 8/16/32 blocks by size.
//  kVfgs: InterDigital VersatileFilmGrain (TR 23002-9 7.5): sample-based adaptation.
//  kTr:   no reference to be bit-exact with: the rdd5 arithmetic extended with what TR 23002-9
//         clause 7 and the SEI semantics allow and the references reject: the auto-regressive
//         model (film_grain_model_id 1), multiplicative blending (blending_mode_id 1) and a
//         film grain bit depth of its own (separate_colour_description_present_flag 1).
//         Parameter sets the rdd5 flavour accepts give the rdd5 output bit for bit.
enum class FgcFlavour : int { kRdd5 = 0, kVtm = 1, kVfgs = 2, kTr = 3, kFfmpeg = 4 };

// "rdd5", "vtm", "vfgs", "tr", "ffmpeg" (the names --flavour takes); "?" for other values.
const char* fgc_flavour_name(FgcFlavour flavour);

// How an FGC SEI's persistence is honoured for pictures that carry no SEI.
//  kReference: as HM does it: a picture without an SEI reuses the last SEI whatever its
//              persistence flag / repetition period (invalid or cancelled -> no grain).
//  kSemantic:  as the SEI semantics say: persistence_flag = 0 (H.264: repetition_period = 0)
//              applies to the current picture only.
enum class FgcPersistence : int { kReference = 0, kSemantic = 1 };

struct FgcIntensityInterval {
    int intensity_interval_lower_bound = 0;  // u(8)
    int intensity_interval_upper_bound = 0;  // u(8)
    // comp_model_value[c][i][0..num_model_values_minus1]; se(v). Only the signalled entries are valid.
    std::array<int, 6> comp_model_value{};
};

struct FgcComponentModel {
    bool comp_model_present_flag = false;
    int num_model_values_minus1 = 0;  // u(3), 0..5
    std::vector<FgcIntensityInterval> intervals;  // num_intensity_intervals_minus1 + 1 entries when present
};

struct FgcParams {
    bool film_grain_characteristics_cancel_flag = false;
    int film_grain_model_id = 0;  // u(2): 0 frequency filtering, 1 auto-regression
    bool separate_colour_description_present_flag = false;
    int film_grain_bit_depth_luma_minus8 = 0;    // u(3)
    int film_grain_bit_depth_chroma_minus8 = 0;  // u(3)
    bool film_grain_full_range_flag = false;
    int film_grain_colour_primaries = 2;
    int film_grain_transfer_characteristics = 2;
    int film_grain_matrix_coeffs = 2;
    int blending_mode_id = 0;   // u(2): 0 additive, 1 multiplicative
    int log2_scale_factor = 0;  // u(4)
    std::array<FgcComponentModel, 3> comp;
    // H.265/H.266: persistence_flag; H.264: repetition_period (ue(v), 0..16384).
    bool film_grain_characteristics_persistence_flag = true;
    int film_grain_characteristics_repetition_period = 1;
};

// The picture identifiers the FGC seed derivation needs. They travel with each
// frame; nothing about them is kept in global state.
struct FgcPictureIds {
    int poc = 0;         // PicOrderCnt of the picture (H.264: TopFieldOrderCnt for frames)
    int idr_pic_id = 0;  // H.264 idr_pic_id of the latest IDR picture; 0 elsewhere
};

}  // namespace filmgrain

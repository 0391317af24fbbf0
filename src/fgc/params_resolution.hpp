// Turns a signalled FGC SEI into the values synthesis uses for one picture format:
// validation as the chosen reference does it, default cut-offs when fewer than three
// model values are sent, and the chroma conversion of the references (TR 23002-9 7.3.1).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::fgc {

struct ResolvedInterval {
    int scale = 0;       // comp_model_value[0] after chroma conversion
    int cutoff_h = 8;    // comp_model_value[1], 2..14 (film_grain_model_id 0)
    int cutoff_v = 8;    // comp_model_value[2], 2..14 (film_grain_model_id 0)
    // film_grain_model_id 1 (tr flavour): comp_model_value[0..5] completed with the
    // defaults, i.e. sigma, p0, p1 (colour correlation), p2, A, p3 in 1/2^log2_scale_factor.
    std::array<int, 6> ar{};
};

struct ResolvedComponent {
    bool present = false;
    std::vector<ResolvedInterval> intervals;
    // interval index for each 8-bit block average, -1 where no interval covers it
    std::array<int16_t, 256> interval_of_intensity{};
};

struct ResolvedFgc {
    bool cancelled = false;  // film_grain_characteristics_cancel_flag: no grain
    int log2_scale_factor = 0;
    int model_id = 0;          // film_grain_model_id: 1 only in the tr flavour
    int blending_mode_id = 0;  // 1 (multiplicative) only in the tr flavour
    // The film grain bit depth of each component: film_grain_bit_depth_luma/chroma_minus8 + 8
    // when separate_colour_description_present_flag = 1 (tr flavour), else the picture's.
    std::array<int, 3> grain_bit_depth{8, 8, 8};
    std::array<ResolvedComponent, 3> comp;
    // distinct (h, v) cut-off pairs, which are the templates this picture needs
    std::vector<std::pair<int, int>> cutoff_pairs;
};

struct PictureFormat {
    ChromaFormat chroma = ChromaFormat::k420;
    int bit_depth = 8;
    int width = 0;
    int height = 0;
};

// Throws Error(kInvalidParams) naming the syntax element, its value and the allowed range,
// or Error(kUnsupported) for valid signalling the flavour does not synthesize (rdd5 and vtm:
// film_grain_model_id 1, blending_mode_id 1, separate_colour_description_present_flag 1,
// which the tr flavour accepts).
ResolvedFgc resolve_fgc_params(const FgcParams& params, FgcFlavour flavour, const PictureFormat& format);

// filmGrainBitDepth[c] of the SEI semantics: film_grain_bit_depth_luma_minus8 + 8 (c = 0) or
// film_grain_bit_depth_chroma_minus8 + 8 when separate_colour_description_present_flag = 1;
// otherwise those elements are inferred from the coded video, i.e. the picture's bit depth.
// picture_bit_depth 0 means "not known here" and gives 16, the deepest picture the library
// (and H.265) takes, so that the ranges below are the widest any picture allows.
int film_grain_bit_depth(const FgcParams& params, int c, int picture_bit_depth);

// The values comp_model_value[c][i][j] can carry, from the FGC SEI semantics (H.274 |
// ISO/IEC 23002-7 8.5 "film_grain_characteristics", H.265 D.3.20, H.264 D.2.21, whose
// range sentence FFmpeg's cbs_h265 / cbs_sei syntax templates transcribe):
//   film_grain_model_id 0: 0 .. 2^filmGrainBitDepth[c] - 1
//   film_grain_model_id 1: -2^(filmGrainBitDepth[c] - 1) .. 2^(filmGrainBitDepth[c] - 1) - 1
// except comp_model_value[c][i][0] of model 1, the standard deviation sigma: the reference
// that synthesizes model 1 (VersatileFilmGrain, TR 23002-9 7.5) takes it as the intensity
// scale factor of model 0, 0 .. 2^filmGrainBitDepth[c] - 1, and the vfgs goldens signal
// sigma up to 255 at 8 bits, so it has model 0's range (a negative deviation means nothing).
// Reserved model ids (2, 3) have no range: se(v) carries any int32.
// "comp_model_value[c][i][j]", as every error about one names it.
std::string comp_model_value_name(int c, int i, int j);

struct ValueRange {
    long long lo = 0;
    long long hi = 0;
};
ValueRange comp_model_value_range(int film_grain_model_id, int j, int film_grain_bit_depth);

// Checks the syntax-level ranges of H.274 (independent of any flavour), as a parser or the
// JSON reader needs them: every element against the range its syntax element can carry,
// comp_model_value[c][i][j] against comp_model_value_range with the picture's bit depth
// (0: not known, the widest, see film_grain_bit_depth). Throws Error(kInvalidParams) naming
// the element, its value and the allowed range. resolve_fgc_params and the vfgs flavour
// call it with the picture's bit depth, so every path to synthesis (SEI payloads, typed
// FgcParams from C++, JSON, the C API) goes through this one check.
void check_fgc_syntax_ranges(const FgcParams& params, int picture_bit_depth = 0);

}  // namespace filmgrain::fgc

// Turns a signalled FGC SEI into the values synthesis uses for one picture format:
// validation as the chosen reference does it, default cut-offs when fewer than three
// model values are sent, and the chroma conversion of the references (TR 23002-9 7.3.1).
#pragma once
#include <array>
#include <cstdint>
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

// Checks the syntax-level ranges of H.274 (independent of any flavour), as a parser or the
// JSON reader needs them. Throws Error(kInvalidParams).
void check_fgc_syntax_ranges(const FgcParams& params);

}  // namespace filmgrain::fgc

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
    int cutoff_h = 8;    // comp_model_value[1], 2..14
    int cutoff_v = 8;    // comp_model_value[2], 2..14
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
// or Error(kUnsupported) for valid signalling the flavour does not synthesize.
ResolvedFgc resolve_fgc_params(const FgcParams& params, FgcFlavour flavour, const PictureFormat& format);

// Checks the syntax-level ranges of H.274 (independent of any flavour), as a parser or the
// JSON reader needs them. Throws Error(kInvalidParams).
void check_fgc_syntax_ranges(const FgcParams& params);

}  // namespace filmgrain::fgc

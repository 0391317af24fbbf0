// Range and consistency checks of film_grain_params() (AV1 spec 5.9.30 syntax
// widths and 6.8.20 conformance requirements) against the frame format.
#pragma once
#include "filmgrain/av1_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::av1 {

// Throws filmgrain::Error(kInvalidParams) naming the field, its value and the
// allowed range. Fields that are not signalled for this format (e.g. chroma
// mult/offset without chroma points) are not checked. When apply_grain == 0
// nothing else is checked (the frame is copied).
void validate_params(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth);

}  // namespace filmgrain::av1

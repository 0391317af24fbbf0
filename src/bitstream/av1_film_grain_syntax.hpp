// AV1 5.9.30 film_grain_params(): the values a frame header signals when it updates the
// grain (apply_grain = 1, update_grain = 1), from num_y_points to clip_to_restricted_range.
// Which of them are present depends on the sequence's colour configuration (mono_chrome,
// subsampling) and on the values read before them.
#pragma once
#include "bitstream/av1_sequence_header.hpp"
#include "filmgrain/av1_params.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {

// Fills `p` from num_y_points on; the fields the syntax leaves out keep their values (the
// defaults of Av1FilmGrainParams for a fresh set). Throws Error(kMalformedPayload) naming the
// element on truncation or a point count above its range.
void read_av1_film_grain_values(BitReader& r, const Av1SequenceHeader& seq, Av1FilmGrainParams& p);

}  // namespace filmgrain::bitstream

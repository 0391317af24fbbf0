// Constant tables of the VFGS flavour (TR 23002-9 clause 7.5 / Annex B.2.2).
// VersatileFilmGrain carries its own copies of the Gaussian table, the seed table and the
// VVC 64-point DCT-2 matrix; they were compared entry by entry with the RDD 5 / HM tables
// of src/fgc/fgc_tables and are identical, so the flavour uses those. What differs is how
// VFGS indexes them (its bit-reversed LFSR, groups stepped outside the cut-offs too).
#pragma once
#include "fgc/fgc_tables.hpp"

namespace filmgrain::vfgs {

using fgc::kGaussianLut;
using fgc::kSeedLut;
// The VVC DCT-2 matrix (fgc::kVvcDct2_64) reaches the flavour through the shared inverse
// transform, fgc::inverse_transform_2d.

}  // namespace filmgrain::vfgs

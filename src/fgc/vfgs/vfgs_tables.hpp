// Constant tables of the VFGS flavour (TR 23002-9 clause 7.5 / Annex B.2.2).
// See vfgs_tables.cpp for where they come from and why VFGS keeps its own copy.
#pragma once
#include <array>
#include <cstdint>

namespace filmgrain::vfgs {

extern const std::array<int8_t, 2048> kGaussianLut;
extern const std::array<uint32_t, 256> kSeedLut;
// kDct2Matrix64[k][n]: k-th basis function (frequency), n-th sample.
extern const std::array<std::array<int8_t, 64>, 64> kDct2Matrix64;

}  // namespace filmgrain::vfgs

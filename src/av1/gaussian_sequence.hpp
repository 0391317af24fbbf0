// Gaussian_Sequence of AV1 spec 7.18.3.3 (the table data lives in gaussian_sequence.cpp).
#pragma once
#include <array>
#include <cstdint>

namespace filmgrain::av1 {

inline constexpr int kGaussianSequenceSize = 2048;  // indexed by an 11-bit random number
extern const std::array<int16_t, kGaussianSequenceSize> kGaussianSequence;

}  // namespace filmgrain::av1

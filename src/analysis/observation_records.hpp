// One analysed picture's observations as bytes: what a distributed analysis task hands
// back to the driver (python/filmgrain/distributed.py), which merges them in picture order
// and fits once. Doubles travel bit for bit, so the fit equals the single-process one.
#pragma once
#include <cstdint>
#include <vector>

#include "analysis/grain_analyzer.hpp"

namespace filmgrain::analysis {

std::vector<uint8_t> serialize_picture_observations(const PictureObservations& picture);
// Throws Error(kMalformedPayload) naming what is wrong (truncated, wrong tag or sizes).
PictureObservations deserialize_picture_observations(const uint8_t* data, std::size_t size);

}  // namespace filmgrain::analysis

// Clean test pictures for the analysis round trips: smooth gradients and flat patches
// (no edges inside the patches), in any format, plus grain added by the library's own
// synthesis with known parameters.
#pragma once
#include <vector>

#include "core/frame_buffer.hpp"

namespace filmgrain::analysis_test {

// A picture of flat rectangles on a slow diagonal ramp covering 8-bit intensities
// lo..hi; chroma planes hold their own slower ramps (so chroma levels vary too).
FrameBuffer make_clean_picture(int width, int height, PixelFormat fmt, int lo = 24, int hi = 232);

// Standard deviation of (grainy - clean) per 8-bit intensity band of the clean picture,
// over samples whose clean value lies in [band_lo, band_hi].
double grain_std_in_band(const FrameBuffer& grainy, const FrameBuffer& clean, int plane, int band_lo, int band_hi);

}  // namespace filmgrain::analysis_test

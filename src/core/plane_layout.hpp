// The memory layout of the frames handed to synthesis, checked before any sample is
// touched. Every model and the session check it (av1::check_frame_view, FgcStreamSynthesis,
// vfgs::Synthesizer).
#pragma once
#include <string>

#include "filmgrain/frame.hpp"

namespace filmgrain {

// Throws Error(kInvalidArgument) naming `name`.strides[p] or `name`.planes[p] with its value:
//  - a plane of more than one row: |stride| from a row of the plane up to what keeps its
//    rows within PTRDIFF_MAX bytes (rows are addressed as data + stride * y in ptrdiff_t);
//  - bit_depth > 8: an even data address and an even stride. Samples are read as uint16_t,
//    which must be 2-byte aligned: misaligned planes are refused, not supported.
// Frames with a non-positive size are left to the callers' size checks.
void check_plane_layout(const FrameView& frame, const std::string& name);

}  // namespace filmgrain

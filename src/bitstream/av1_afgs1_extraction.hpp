// Per-frame AV1 film grain parameters from the AFGS1 metadata of an AV1 stream, as a
// decoder applying AFGS1 would use them: each temporal unit's AFGS1 T.35 payloads update
// the 8 stored parameter sets, and the unit's shown frame takes the set that
// select_film_grain_param_set() (AFGS1 7.3) picks for the picture the sequence header
// describes.
#pragma once
#include <string>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "metadata/av1_params_json.hpp"

namespace filmgrain::bitstream {

// One entry per temporal unit (decode order = output order: one shown frame each), in
// the form `apply --params` reads: the selected set's parameters with update_grain = 1
// and the picture facts of the sequence header (bit depth, subsampling, and the
// matrix_coefficients the synthesis uses). A unit without AFGS1 payload, with a damaged
// one (reported in `warnings`), or whose payload has no set for the picture gets
// apply_grain = 0.
//
// The picture is taken at the sequence header's max_frame_width x max_frame_height (frame
// headers that override the size are not parsed), with its colour description when
// color_description_present_flag = 1.
//
// Throws Error(kUnsupported) for a stream without AFGS1 metadata whose sequence header
// has film_grain_params_present = 1: its grain is in the frame headers, which this
// function does not parse. Throws Error(kMalformedPayload) for a scan that is not AV1 or
// holds no temporal unit.
std::vector<Av1FrameParams> av1_params_from_afgs1(const StreamScan& scan, std::vector<std::string>& warnings);

}  // namespace filmgrain::bitstream

// Per-frame AV1 film grain parameters of an AV1 stream, as a decoder applies them:
//   - from its AFGS1 metadata when it has any: each temporal unit's AFGS1 T.35 payloads
//     update the 8 stored parameter sets, and the unit's shown frame takes the set that
//     select_film_grain_param_set() (AFGS1 7.3) picks for the picture the sequence header
//     describes;
//   - else from the frame headers' film_grain_params() (film_grain_params_present = 1),
//     which the scan reads (av1_frame_header.hpp).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/av1_params_json.hpp"

namespace filmgrain::bitstream {

// One entry per temporal unit (decode order = output order: one shown frame each), in
// the form `apply --params` reads: the frame's parameters with update_grain = 1 (resolved)
// and the picture facts of the sequence header (bit depth, subsampling, and the
// matrix_coefficients the synthesis uses). AFGS1: a unit without payload, with a damaged one
// (reported in `warnings`), or whose payload has no set for the picture gets apply_grain = 0.
// Frame headers: a unit whose header could not be read gets apply_grain = 0 and a warning.
//
// AFGS1 selection takes the picture at the sequence header's max_frame_width x
// max_frame_height (frame headers that override the size are not consulted), with its
// colour description when color_description_present_flag = 1.
//
// Throws Error(kMalformedPayload) for a scan that is not AV1 or holds no temporal unit.
std::vector<Av1FrameParams> av1_params_from_scan(const StreamScan& scan, std::vector<std::string>& warnings);

// AFGS1 in H.264 / H.265 / H.266 streams (T.35 registered user data SEI) and in AV1 metadata
// OBUs: the payloads update the 8 stored sets in decode order, and each applies to the
// picture of its own access unit or temporal unit (AFGS1 text). One entry per output picture
// (units_in_output_order, dropped pictures left out): the payload of its unit with the sets
// resolved, or nothing. Several payloads in one unit: each updates the stored sets, the last
// one chooses. A damaged payload is skipped with a warning. Empty when the stream carries no
// AFGS1 payload.
std::vector<std::optional<Afgs1Payload>> afgs1_payloads_in_output_order(const StreamScan& scan,
                                                                         std::vector<std::string>& warnings);

}  // namespace filmgrain::bitstream

// What `filmgrain inspect` prints and `params extract` writes, from a StreamScan.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bitstream/stream_scan.hpp"
#include "metadata/params_file.hpp"

namespace filmgrain::bitstream {

nlohmann::json stream_scan_to_json(const StreamScan& scan);
std::string stream_scan_to_text(const StreamScan& scan);

// The per-frame parameter file in output order: each output picture with its POC
// (and idr_pic_id for H.264) and the FGC SEI that arrived in its access unit. An access
// unit with several FGC SEI messages contributes the first that parses; the others and
// the damaged ones are reported in `warnings`. Throws Error(kUnsupported) for AV1, whose
// parameters are AV1 film grain sets, not FGC SEIs: av1_grain_extraction.hpp turns its
// AFGS1 metadata into per-frame AV1 parameters.
ParamsFile params_file_from_scan(const StreamScan& scan, std::vector<std::string>& warnings);

}  // namespace filmgrain::bitstream

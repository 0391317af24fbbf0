// The AFGS1 payloads of a scanned stream, read as a decoder reads them: in decode order, each
// updating the 8 stored parameter sets (AFGS1 7.2), so that a set with update_grain_flag = 0
// carries the parameters it reuses. One reading for every consumer of a scan (the C API's
// stream scan, `inspect`, `params extract`, `decode`), which then hand the payloads on in
// whatever order they apply them.
#pragma once
#include <string>
#include <variant>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "metadata/afgs1.hpp"

namespace filmgrain::bitstream {

// Per T.35 payload: nothing (not AFGS1), the payload as read, or why it could not be read
// (the stored sets are then unchanged, as Afgs1Reader leaves them).
using Afgs1Read = std::variant<std::monostate, Afgs1Payload, std::string>;

// reads[unit][j] for scan.units[unit].t35[j], units in decode order.
std::vector<std::vector<Afgs1Read>> read_afgs1_in_decode_order(const StreamScan& scan);

}  // namespace filmgrain::bitstream

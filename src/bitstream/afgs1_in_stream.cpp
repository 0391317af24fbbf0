#include "bitstream/afgs1_in_stream.hpp"

#include "bitstream/sei_messages.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::bitstream {

std::vector<std::vector<Afgs1Read>> read_afgs1_in_decode_order(const StreamScan& scan) {
    Afgs1Reader stored_sets;
    std::vector<std::vector<Afgs1Read>> reads;
    reads.reserve(scan.units.size());
    for (const AccessUnit& u : scan.units) {
        std::vector<Afgs1Read>& unit = reads.emplace_back();
        for (const FoundT35& t : u.t35) {
            if (!is_afgs1_t35(t.t35)) {
                unit.emplace_back();
                continue;
            }
            try {
                unit.emplace_back(stored_sets.receive(t35_bytes(t.t35), true));
            } catch (const Error& e) {
                unit.emplace_back(std::string(e.what()));
            }
        }
    }
    return reads;
}

}  // namespace filmgrain::bitstream

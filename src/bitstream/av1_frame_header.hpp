// AV1 uncompressed_header() (AV1 5.9) read as far as film_grain_params() (5.9.30), for the
// film grain of frame-header streams (aomenc --film-grain-test). Everything before the
// grain is parsed only to reach it; the state that parsing needs across frames is kept
// per reference slot (7.20 reference frame update process): frame type, order hint,
// frame size, segmentation feature data and the resolved film grain parameters.
//
// Not followed: frame_refs_short_signaling = 1 (set_frame_refs, 7.8) throws
// Error(kUnsupported); scalable streams are read as if every OBU belonged to the chosen
// operating point (temporal/spatial ids only select buffer_removal_time fields).
#pragma once
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "bitstream/av1_obu.hpp"
#include "bitstream/av1_sequence_header.hpp"
#include "filmgrain/av1_params.hpp"

namespace filmgrain::bitstream {

struct Av1ShownFrame {
    // The parameters the shown frame is synthesized with: update_grain = 0 already resolved
    // from its reference slot (load_grain_params), apply_grain = 0 when it has none.
    Av1FilmGrainParams grain;
    bool show_existing_frame = false;
    // update_grain = 0: the sets the frame's other references (ref_frame_idx) hold, with the
    // header's grain_seed, as (slot, set), where they differ from the set loaded: what a
    // decoder loading the wrong slot applies (`filmgrain verify` tries them).
    std::vector<std::pair<int, Av1FilmGrainParams>> other_slot_grain;
};

class Av1FrameHeaderReader {
public:
    // One OBU_FRAME_HEADER or OBU_FRAME payload. Returns the shown frame when this header
    // shows one (show_frame = 1 or show_existing_frame = 1). Throws Error(kMalformedPayload)
    // naming the syntax element on truncation or invalid references; the reader's slots are
    // then left as they were.
    std::optional<Av1ShownFrame> read(const Av1SequenceHeader& seq, const Av1Obu& obu);
    void reset() { slots_ = {}; }

    struct Slot {
        bool valid = false;
        int frame_type = 0;
        int order_hint = 0;
        int upscaled_width = 0, frame_width = 0, frame_height = 0, render_width = 0, render_height = 0;
        std::array<std::array<int, 8>, 8> feature_enabled{}, feature_data{};
        Av1FilmGrainParams grain;
    };

private:
    std::array<Slot, 8> slots_{};
};

}  // namespace filmgrain::bitstream

// The film grain parameters an AV1 decoder keeps with its eight reference frames
// (AV1 7.20 reference frame update process, 7.21 load_grain_params), so that a frame
// header with update_grain = 0, or a show_existing_frame, finds the parameters it refers to.
#pragma once
#include <array>
#include <optional>

#include "filmgrain/av1_params.hpp"

namespace filmgrain::session {

class Av1ReferenceSlots {
public:
    static constexpr int kNumSlots = 8;  // NUM_REF_FRAMES

    // The effective parameters of a frame header: with update_grain = 0 those of slot
    // film_grain_params_ref_idx, keeping the header's own grain_seed. Throws
    // Error(kInvalidParams) naming film_grain_params_ref_idx when that slot holds nothing.
    Av1FilmGrainParams resolve(const Av1FilmGrainParams& header) const;
    // Stores `p` in every slot whose bit is set in refresh_frame_flags.
    void store(const Av1FilmGrainParams& p, unsigned refresh_frame_flags);
    // Throws Error naming frame_to_show_map_idx when out of range or empty.
    const Av1FilmGrainParams& at(int slot) const;
    void clear() { slots_ = {}; }

private:
    std::array<std::optional<Av1FilmGrainParams>, kNumSlots> slots_;
};

}  // namespace filmgrain::session

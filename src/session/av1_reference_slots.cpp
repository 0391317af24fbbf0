#include "session/av1_reference_slots.hpp"

#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::session {

Av1FilmGrainParams Av1ReferenceSlots::resolve(const Av1FilmGrainParams& header) const {
    if (!header.apply_grain || header.update_grain) return header;
    const int idx = header.film_grain_params_ref_idx;
    if (idx < 0 || idx >= kNumSlots)
        throw Error(ErrorCode::kInvalidParams, out_of_range_message("film_grain_params_ref_idx", idx, 0, kNumSlots - 1));
    if (!slots_[std::size_t(idx)])
        throw Error(ErrorCode::kInvalidParams,
                    "film_grain_params_ref_idx = " + std::to_string(idx) +
                        " with update_grain = 0 names a reference slot that holds no film grain parameters");
    // load_grain_params() copies everything but the seed, which this header signals anew.
    Av1FilmGrainParams p = *slots_[std::size_t(idx)];
    p.grain_seed = header.grain_seed;
    p.update_grain = 0;
    p.film_grain_params_ref_idx = idx;
    return p;
}

void Av1ReferenceSlots::store(const Av1FilmGrainParams& p, unsigned refresh_frame_flags) {
    for (int i = 0; i < kNumSlots; i++)
        if (refresh_frame_flags & (1u << i)) slots_[std::size_t(i)] = p;
}

const Av1FilmGrainParams& Av1ReferenceSlots::at(int slot) const {
    if (slot < 0 || slot >= kNumSlots)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("frame_to_show_map_idx", slot, 0, kNumSlots - 1));
    if (!slots_[std::size_t(slot)])
        throw Error(ErrorCode::kInvalidParams, "frame_to_show_map_idx = " + std::to_string(slot) +
                                                   " names a reference slot that holds no film grain parameters");
    return *slots_[std::size_t(slot)];
}

}  // namespace filmgrain::session

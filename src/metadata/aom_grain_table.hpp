// libaom film grain table files ("filmgrn1" text format, aom_dsp/grain_table.c),
// as written by aomenc --film-grain-denoise / read by --film-grain-table.
//
//   filmgrn1
//   E <start> <end> <apply_grain> <random_seed> <update_parameters>
//   	p <ar_coeff_lag> <ar_coeff_shift> <grain_scale_shift> <scaling_shift>
//   	  <chroma_scaling_from_luma> <overlap_flag> <cb_mult> <cb_luma_mult> <cb_offset>
//   	  <cr_mult> <cr_luma_mult> <cr_offset>
//   	sY <n> <value scaling>...     (sCb, sCr alike)
//   	cY <2*lag*(lag+1) signed coefficients>
//   	cCb / cCr <2*lag*(lag+1)+1 signed coefficients>
//
// The p/s/c lines are present only when update_parameters is 1. Times are in
// the encoder's timestamp units (10 MHz ticks for aomenc). Shifts are stored as
// the actual shift (ar_coeff_shift 6..9, scaling_shift 8..11), coefficients
// without the +128 bias, and the chroma mult/offset fields as raw values. The
// format has no clip_to_restricted_range; it reads as 0.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "filmgrain/av1_params.hpp"

namespace filmgrain {

struct AomGrainTableEntry {
    int64_t start_time = 0;
    int64_t end_time = 0;
    // apply_grain, grain_seed (random_seed) and update_grain (update_parameters)
    // come from the E line; the rest only when update_grain is 1.
    Av1FilmGrainParams params;
    bool operator==(const AomGrainTableEntry&) const = default;
};

struct AomGrainTable {
    std::vector<AomGrainTableEntry> entries;

    // Index of the first entry with start_time <= t < end_time (libaom's lookup rule).
    std::optional<std::size_t> find_index(int64_t t) const;
    const AomGrainTableEntry* find(int64_t t) const;

    // The entry's parameters with update_grain == 0 resolved: parameters (but
    // not apply_grain / grain_seed) are carried over from the nearest earlier
    // entry that had update_grain == 1. Throws Error(kInvalidParams) if none.
    Av1FilmGrainParams resolved_params(std::size_t index) const;
};

// Parses table text. Throws Error(kMalformedPayload) naming the line and field.
AomGrainTable parse_aom_grain_table(std::string_view text);
// Reads and parses a file (Error(kIo) when it cannot be read).
AomGrainTable read_aom_grain_table(const std::string& path);
// Writes text in exactly libaom's layout (so libaom tables round-trip byte for byte).
std::string format_aom_grain_table(const AomGrainTable& table);
void write_aom_grain_table(const AomGrainTable& table, const std::string& path);

}  // namespace filmgrain

// AOMedia Film Grain Synthesis 1 (AFGS1) metadata: the ITU-T T.35 payload
// metadata_aom_itu_t_t35() carrying av1_film_grain_param_sets() (AFGS1 v1.0.0,
// sections 6.2-6.4 syntax, 7.x semantics), read and write.
//
// A payload holds 1..8 parameter sets, each addressed by film_grain_param_set_idx.
// The receiver keeps 8 stored sets across pictures (update_grain_flag = 0 reuses
// one with a new seed), and picks, for each picture, the signalled set that fits
// its size, subsampling, bit depth and colour description.
//
// Where the AFGS1 text cannot be implemented literally, this reader follows what
// the existing writer (AOM's AFGS1 reference writer) produces and what FFmpeg's
// reader (libavcodec/aom_film_grain.c) understands:
//   - AR coefficients: the text derives "ArCoeffsYPlus128 = ar_coeffs_y - (1 << (BitsArY - 1))",
//     which taken literally would remove the +128 bias twice. Writers code the
//     signed coefficient plus 2^(bits-1); we read coefficient = ar_coeffs_y - 2^(bits-1)
//     (ar_coeffs_*_plus_128 = that + 128), as FFmpeg does.
//   - point_*_value_increment equal to 0 after the first point would give equal
//     point values, which the AV1 scaling interpolation cannot use (it divides by
//     the run): rejected, naming the element.
//   - point values (running sums of increments) above 255, and chroma scalings
//     (point_c*_scaling + c*_scaling_offset) above 255: rejected (FFmpeg rejects the
//     former and silently wraps the latter into 8 bits).
//   - bits_per_*_scaling_res = 0: the text's residual term is undefined (a shift by -1)
//     and FFmpeg then leaves the set's previous points in place. We read it as
//     "no residual": the prediction from the reference set with a zero residual.
//     Our writer never emits it, so FFmpeg and this reader agree on our payloads.
//   - matrix_coefficients is absent unless cicp_info_present_flag = 1, but the
//     synthesis needs it (identity-matrix chroma clip); selection returns the
//     set's value when present and the picture's otherwise.
//   - FFmpeg does not skip a set's padding after apply_grain_flag = 0 or
//     update_grain_flag = 0; we follow the text (padding up to payload_size).
//     Payloads in which such a short set is followed by another set are read
//     differently by FFmpeg; the writer keeps the caller's order (the first set is
//     the prediction reference), so put short sets last for FFmpeg.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "filmgrain/av1_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {

inline constexpr int kAfgs1CountryCode = 0xB5;
inline constexpr int kAfgs1ProviderCode = 0x5890;
inline constexpr int kAfgs1ProviderOrientedCode = 0x01;
inline constexpr int kAfgs1MaxSets = 8;

// The picture a set is meant for (signalled with update_grain_flag = 1).
struct Afgs1SetTarget {
    int apply_units_resolution_log2 = 0;  // 0..15
    int apply_horz_resolution = 0;        // 12 bits, units of 1 << log2 luma samples
    int apply_vert_resolution = 0;
    int luma_only_flag = 0;
    int subsampling_x = 1, subsampling_y = 1;  // 0 when luma_only_flag
    int video_signal_characteristics_flag = 0;
    int bit_depth_minus8 = 0;  // 0..4
    int cicp_info_present_flag = 0;
    int color_primaries = 2, transfer_characteristics = 2, matrix_coefficients = 2, video_full_range_flag = 0;
    bool operator==(const Afgs1SetTarget&) const = default;

    int width() const { return apply_horz_resolution << apply_units_resolution_log2; }
    int height() const { return apply_vert_resolution << apply_units_resolution_log2; }
};

// One av1_film_grain_params(). `params` holds the effective AV1 values
// (Av1FilmGrainParams conventions: raw values with the +128/+256 biases):
// for update_grain_flag = 0 those of the stored set, with this set's seed.
// params.apply_grain / grain_seed / update_grain are the set's flags.
struct Afgs1ParamSet {
    int film_grain_param_set_idx = 0;
    Afgs1SetTarget target;
    Av1FilmGrainParams params;
    bool operator==(const Afgs1ParamSet&) const = default;
};

// One av1_film_grain_param_sets().
struct Afgs1Payload {
    int afgs1_enable_flag = 1;
    std::vector<Afgs1ParamSet> sets;  // in signalled order
    bool operator==(const Afgs1Payload&) const = default;
};

struct Afgs1WriteOptions {
    bool t35_header = true;  // country/provider codes before av1_film_grain_param_sets()
    // Code a set's scaling functions by prediction from the first set when that is
    // shorter (same point count and point values, same chroma mult/offset).
    bool predict_scaling = true;
};

// Writes sets with update_grain = 0 or apply_grain = 0 in their short forms.
// Chooses the narrowest bit widths. Throws Error(kInvalidParams) naming the field
// when a value cannot be coded (e.g. more than 8 sets, duplicate indices,
// decreasing point values, a resolution not representable in 12 bits).
std::vector<uint8_t> write_afgs1(const Afgs1Payload& payload, const Afgs1WriteOptions& options = {});

// A payload as Afgs1Reader::receive resolved it, written with every applied set's parameters
// present (update_grain_flag = 1). H.26x stores the sets in decode order (AFGS1 7.2), while a
// player hands pictures over in output order: these bytes mean the same to a receiver that
// has not seen the payloads before them (a session, fg_context_push_afgs1_t35), whatever the
// order it gets them in.
std::vector<uint8_t> write_afgs1_resolved(Afgs1Payload resolved, const Afgs1WriteOptions& options = {});

// The receiver: 8 stored parameter sets that persist across payloads.
class Afgs1Reader {
public:
    // Parses one payload (with the T.35 header when `t35_header`), updates the
    // stored sets and returns the sets as signalled, resolved. Throws
    // Error(kMalformedPayload) naming the syntax element on truncation, bad codes,
    // reserved or out-of-range values; stored sets are left untouched then.
    Afgs1Payload receive(const uint8_t* data, std::size_t size, bool t35_header = true);
    Afgs1Payload receive(const std::vector<uint8_t>& v, bool t35_header = true) {
        return receive(v.data(), v.size(), t35_header);
    }
    // The stored set (nullopt: never signalled).
    const std::optional<Afgs1ParamSet>& stored(int idx) const { return slots_.at(std::size_t(idx)); }

private:
    std::array<std::optional<Afgs1ParamSet>, kAfgs1MaxSets> slots_;
    std::array<bool, kAfgs1MaxSets> has_params_{};  // set once signalled with update_grain_flag = 1
};

// True when the bytes start with the AFGS1 T.35 header (a bare
// av1_film_grain_param_sets() never starts with 0xB5: its reserved_4bits are 0).
bool afgs1_has_t35_header(const uint8_t* data, std::size_t size);

// The decoded picture a set is chosen for. Unknown colour facts (-1) match anything.
struct Afgs1Picture {
    int width = 0, height = 0;
    ChromaFormat format = ChromaFormat::k420;
    int bit_depth = 8;
    int color_primaries = -1, transfer_characteristics = -1, matrix_coefficients = -1, video_full_range_flag = -1;
};

struct Afgs1Selection {
    std::size_t set_index = 0;    // into Afgs1Payload::sets
    // The chosen set as the picture's own parameters (afgs1_set_as_frame_params); apply_grain
    // = 0 when the set disables grain.
    Av1FilmGrainParams params;
    int matrix_coefficients = 2;  // the set's when signalled, else the picture's (2 if unknown)
};

// A set's parameters as a picture's own AV1 film grain parameters (update_grain 1; chroma
// point counts marked signalled where AV1 would infer them 0): what every consumer of a
// selected or converted set applies.
Av1FilmGrainParams afgs1_set_as_frame_params(const Afgs1ParamSet& set);

// select_film_grain_param_set(): among the sets of this payload whose
// subsampling (luma_only sets fit any picture: they carry no chroma grain), bit
// depth and colour description (when signalled) fit the picture, the one whose
// resolution equals the picture's (width >> log2 == apply_horz_resolution, same
// vertically) — else, as the text recommends and FFmpeg does, the largest one
// not exceeding the picture. A 0x0 resolution fits any picture size (FFmpeg's
// convention for writers that do not know it). nullopt when none fits or
// afgs1_enable_flag = 0: no grain for that picture.
std::optional<Afgs1Selection> select_afgs1_set(const Afgs1Payload& payload, const Afgs1Picture& picture);

}  // namespace filmgrain

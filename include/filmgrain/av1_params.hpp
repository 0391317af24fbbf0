// AV1 film grain parameters (AV1 spec 5.9.30 film_grain_params(), semantics 6.8.20).
//
// Every field holds the raw bitstream value of the syntax element of the same name,
// including the +128 / +256 biases of the AR coefficients and of the chroma
// mult/offset fields. The values are the *effective* ones for the displayed frame:
// resolving update_grain = 0 / film_grain_params_ref_idx (load_grain_params) is the
// caller's job; synthesis never looks at those two fields.
#pragma once
#include <array>

namespace filmgrain {

struct Av1FilmGrainParams {
    int apply_grain = 0;
    int grain_seed = 0;                 // 16 bits
    int update_grain = 1;
    int film_grain_params_ref_idx = 0;  // 3 bits, informative only

    int num_y_points = 0;  // 0..14
    std::array<int, 14> point_y_value{};
    std::array<int, 14> point_y_scaling{};

    int chroma_scaling_from_luma = 0;

    int num_cb_points = 0;  // 0..10
    std::array<int, 10> point_cb_value{};
    std::array<int, 10> point_cb_scaling{};
    int num_cr_points = 0;  // 0..10
    std::array<int, 10> point_cr_value{};
    std::array<int, 10> point_cr_scaling{};

    int grain_scaling_minus_8 = 0;  // 0..3
    int ar_coeff_lag = 0;           // 0..3
    // Only the first numPosLuma = 2*lag*(lag+1) luma entries and numPosChroma
    // (= numPosLuma, +1 when num_y_points > 0) chroma entries are meaningful.
    // 128 means a zero coefficient.
    std::array<int, 24> ar_coeffs_y_plus_128{};
    std::array<int, 25> ar_coeffs_cb_plus_128{};
    std::array<int, 25> ar_coeffs_cr_plus_128{};
    int ar_coeff_shift_minus_6 = 0;  // 0..3
    int grain_scale_shift = 0;       // 0..3

    // Signalled only when the component has scaling points (num_cb_points /
    // num_cr_points > 0); unused otherwise.
    int cb_mult = 128, cb_luma_mult = 192, cb_offset = 256;
    int cr_mult = 128, cr_luma_mult = 192, cr_offset = 256;

    int overlap_flag = 0;
    int clip_to_restricted_range = 0;

    // AV1 film_grain_params() does not signal num_cb_points / num_cr_points for 4:2:0 without
    // luma points (they are inferred 0); AFGS1 av1_film_grain_params() signals them, and such
    // a set may carry chroma points (AFGS1 text, FFmpeg 7.1). true: the counts were signalled.
    bool chroma_point_counts_signalled = false;

    Av1FilmGrainParams() {
        ar_coeffs_y_plus_128.fill(128);
        ar_coeffs_cb_plus_128.fill(128);
        ar_coeffs_cr_plus_128.fill(128);
    }
    bool operator==(const Av1FilmGrainParams&) const = default;

    // 2*lag*(lag+1): number of causal luma neighbours in the AR filter.
    int num_pos_luma() const { return 2 * ar_coeff_lag * (ar_coeff_lag + 1); }
    // Chroma filters also carry one coefficient for the co-located luma grain,
    // but only when there is luma grain to take it from.
    int num_pos_chroma() const { return num_pos_luma() + (num_y_points > 0 ? 1 : 0); }
};

// Sequence/frame-level facts that synthesis needs besides film_grain_params().
// When applying grain to a FrameView, bit depth and subsampling come from the view;
// this struct carries them for metadata (JSON) round trips.
struct Av1ColorInfo {
    int bit_depth = 8;
    int mono_chrome = 0;
    int subsampling_x = 1;
    int subsampling_y = 1;
    int matrix_coefficients = 2;  // 0 = MC_IDENTITY (changes the restricted chroma clip)
    bool operator==(const Av1ColorInfo&) const = default;
};

inline constexpr int kAv1MatrixCoefficientsIdentity = 0;

}  // namespace filmgrain

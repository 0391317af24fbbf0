// select_film_grain_param_set(): which signalled AFGS1 set applies to a picture
// (AFGS1 7.3 conformance requirements and the recommendation that follows them).
#include "metadata/afgs1.hpp"

namespace filmgrain {
namespace {

bool fits_format(const Afgs1SetTarget& t, const Afgs1Picture& pic) {
    // A luma-only set carries no chroma grain, so it fits any chroma format.
    if (t.luma_only_flag) return true;
    if (pic.format == ChromaFormat::k400) return false;
    return t.subsampling_x == chroma_shift_x(pic.format) && t.subsampling_y == chroma_shift_y(pic.format);
}

bool same_or_unknown(int signalled, int picture) { return picture < 0 || signalled == picture; }

bool fits_signal(const Afgs1SetTarget& t, const Afgs1Picture& pic) {
    if (!t.video_signal_characteristics_flag) return true;
    if (t.bit_depth_minus8 + 8 != pic.bit_depth) return false;
    if (!t.cicp_info_present_flag) return true;
    return same_or_unknown(t.color_primaries, pic.color_primaries) &&
           same_or_unknown(t.transfer_characteristics, pic.transfer_characteristics) &&
           same_or_unknown(t.matrix_coefficients, pic.matrix_coefficients) &&
           same_or_unknown(t.video_full_range_flag, pic.video_full_range_flag);
}

bool any_size(const Afgs1SetTarget& t) { return t.apply_horz_resolution == 0 && t.apply_vert_resolution == 0; }

bool exact_size(const Afgs1SetTarget& t, const Afgs1Picture& pic) {
    return (pic.width >> t.apply_units_resolution_log2) == t.apply_horz_resolution &&
           (pic.height >> t.apply_units_resolution_log2) == t.apply_vert_resolution;
}

}  // namespace

Av1FilmGrainParams afgs1_set_as_frame_params(const Afgs1ParamSet& set) {
    // Complete already: a stored set reused with update_grain_flag 0 was resolved when the
    // payload was read. AFGS1 signals the chroma point counts even for 4:2:0 without luma
    // points, where AV1's own syntax infers them 0: marked where that is the case, so a set
    // AV1's syntax can carry stays equal to its AV1 form.
    Av1FilmGrainParams p = set.params;
    p.update_grain = 1;
    p.film_grain_params_ref_idx = 0;
    p.chroma_point_counts_signalled = p.num_y_points == 0 && (p.num_cb_points > 0 || p.num_cr_points > 0);
    return p;
}

std::optional<Afgs1Selection> select_afgs1_set(const Afgs1Payload& payload, const Afgs1Picture& pic) {
    if (!payload.afgs1_enable_flag) return std::nullopt;
    std::optional<std::size_t> exact, largest;
    long long largest_area = -1;
    for (std::size_t i = 0; i < payload.sets.size(); ++i) {
        const Afgs1SetTarget& t = payload.sets[i].target;
        if (!fits_format(t, pic) || !fits_signal(t, pic)) continue;
        if (exact_size(t, pic)) {
            if (!exact) exact = i;
            continue;
        }
        const long long w = t.width(), h = t.height();
        if (!any_size(t) && (w > pic.width || h > pic.height)) continue;
        if (w * h > largest_area) {
            largest_area = w * h;
            largest = i;
        }
    }
    const std::optional<std::size_t> chosen = exact ? exact : largest;
    if (!chosen) return std::nullopt;
    const Afgs1ParamSet& s = payload.sets[*chosen];
    Afgs1Selection sel;
    sel.set_index = *chosen;
    sel.params = afgs1_set_as_frame_params(s);
    sel.matrix_coefficients = s.target.cicp_info_present_flag ? s.target.matrix_coefficients
                              : pic.matrix_coefficients >= 0 ? pic.matrix_coefficients
                                                             : 2;
    return sel;
}

}  // namespace filmgrain

// AFGS1 writer: av1_film_grain_param_sets() with the narrowest bit widths the
// syntax offers, and scaling prediction from the first set when it is shorter.
#include <algorithm>
#include <optional>
#include <set>
#include <string>

#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/afgs1_fields.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain {
namespace {

using afgs1_fields::ar_coeffs_of;
using afgs1_fields::mults_of;
using afgs1_fields::scaling_of;
const char* const* const kComp = afgs1_fields::kComponentName;

void check(const std::string& field, long long v, long long lo, long long hi, int set_number) {
    if (v < lo || v > hi)
        throw Error(ErrorCode::kInvalidParams, "AFGS1: parameter set " + std::to_string(set_number) + ": " +
                                                   out_of_range_message(field, v, lo, hi));
}

int bit_length(int v) {
    int n = 0;
    while (v >> n) ++n;
    return n;
}

// Scaling prediction coded as: factor 1 (mult 256 + 16), no intercept (add 256),
// residual = scaling - reference scaling with granularity 1.
struct Prediction {
    int bits = 0;  // bits_per_*_scaling_res, 1..7
    int cost = 0;  // in bits
};

std::optional<Prediction> plan_prediction(Av1FilmGrainParams& p, Av1FilmGrainParams& ref, int c) {
    const auto s = scaling_of(p, c);
    const auto r = scaling_of(ref, c);
    if (*s.count == 0 || *s.count != *r.count) return std::nullopt;
    if (c > 0)
        for (int k = 0; k < 3; ++k)
            if (*mults_of(p, c)[k] != *mults_of(ref, c)[k]) return std::nullopt;
    int lo = 0, hi = 0;
    for (int i = 0; i < *s.count; ++i) {
        if (s.values[i] != r.values[i]) return std::nullopt;
        const int d = s.scalings[i] - r.scalings[i];
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    for (int bits = 1; bits <= 7; ++bits)
        if (-lo <= (1 << (bits - 1)) && hi <= (1 << (bits - 1)) - 1)
            return Prediction{bits, 9 + 9 + 3 + *s.count * bits + 3};
    return std::nullopt;
}

struct DirectCoding {
    int bits_incr = 1, bits_scal = 5, offset = 0;
    int cost = 4;
};

DirectCoding plan_direct(Av1FilmGrainParams& p, int c, int n) {
    const auto s = scaling_of(p, c);
    const std::string comp = kComp[c];
    check("num_" + comp + "_points", *s.count, 0, s.max_points, n);
    DirectCoding d;
    if (*s.count == 0) return d;
    int max_inc = 0, min_scal = 255, max_scal = 0;
    for (int i = 0; i < *s.count; ++i) {
        const int lo = i ? s.values[i - 1] + 1 : 0;
        check("point_" + comp + "_value[" + std::to_string(i) + "] (values must increase)", s.values[i], lo, 255, n);
        check("point_" + comp + "_scaling[" + std::to_string(i) + "]", s.scalings[i], 0, 255, n);
        max_inc = std::max(max_inc, s.values[i] - (i ? s.values[i - 1] : 0));
        min_scal = std::min(min_scal, s.scalings[i]);
        max_scal = std::max(max_scal, s.scalings[i]);
    }
    d.bits_incr = std::max(1, bit_length(max_inc));
    d.offset = c ? min_scal : 0;  // luma has no offset field
    d.bits_scal = std::max(5, bit_length(max_scal - d.offset));
    d.cost = 4 + 3 + 2 + (c ? 8 : 0) + *s.count * (d.bits_incr + d.bits_scal);
    return d;
}

void write_direct(BitWriter& w, Av1FilmGrainParams& p, int c, const DirectCoding& d) {
    const auto s = scaling_of(p, c);
    w.u(4, uint32_t(*s.count));
    if (!*s.count) return;
    w.u(3, uint32_t(d.bits_incr - 1));
    w.u(2, uint32_t(d.bits_scal - 5));
    if (c) w.u(8, uint32_t(d.offset));
    for (int i = 0; i < *s.count; ++i) {
        w.u(d.bits_incr, uint32_t(s.values[i] - (i ? s.values[i - 1] : 0)));
        w.u(d.bits_scal, uint32_t(s.scalings[i] - d.offset));
    }
}

void write_predicted(BitWriter& w, Av1FilmGrainParams& p, Av1FilmGrainParams& ref, int c, const Prediction& pr) {
    const auto s = scaling_of(p, c);
    const auto r = scaling_of(ref, c);
    w.u(9, 256 + 16);  // multiplier 1.0 in 1/16 units
    w.u(9, 256);       // intercept 0
    w.u(3, uint32_t(pr.bits));
    for (int i = 0; i < *s.count; ++i) w.u(pr.bits, uint32_t(s.scalings[i] - r.scalings[i] + (1 << (pr.bits - 1))));
    w.u(3, 1);  // granularity
}

void write_ar_coeffs(BitWriter& w, Av1FilmGrainParams& p, int c, int count, int n) {
    const int* a = ar_coeffs_of(p, c);
    int lo = 0, hi = 0;
    for (int i = 0; i < count; ++i) {
        check(std::string("ar_coeffs_") + kComp[c] + "_plus_128[" + std::to_string(i) + "]", a[i], 0, 255, n);
        lo = std::min(lo, a[i] - 128);
        hi = std::max(hi, a[i] - 128);
    }
    int bits = 5;
    while (bits < 8 && (-lo > (1 << (bits - 1)) || hi > (1 << (bits - 1)) - 1)) ++bits;
    w.u(2, uint32_t(bits - 5));
    for (int i = 0; i < count; ++i) w.u(bits, uint32_t(a[i] - 128 + (1 << (bits - 1))));
}

void write_params(BitWriter& w, const Afgs1ParamSet& set, Av1FilmGrainParams* ref, int n) {
    Av1FilmGrainParams p = set.params;
    const Afgs1SetTarget& t = set.target;
    check("film_grain_param_set_idx", set.film_grain_param_set_idx, 0, 7, n);
    w.u(3, uint32_t(set.film_grain_param_set_idx));
    check("apply_grain", p.apply_grain, 0, 1, n);
    w.u(1, uint32_t(p.apply_grain));
    if (!p.apply_grain) return;
    check("grain_seed", p.grain_seed, 0, 65535, n);
    w.u(16, uint32_t(p.grain_seed));
    check("update_grain", p.update_grain, 0, 1, n);
    w.u(1, uint32_t(p.update_grain));
    if (!p.update_grain) return;

    check("apply_units_resolution_log2", t.apply_units_resolution_log2, 0, 15, n);
    check("apply_horz_resolution", t.apply_horz_resolution, 0, 4095, n);
    check("apply_vert_resolution", t.apply_vert_resolution, 0, 4095, n);
    w.u(4, uint32_t(t.apply_units_resolution_log2));
    w.u(12, uint32_t(t.apply_horz_resolution));
    w.u(12, uint32_t(t.apply_vert_resolution));
    check("luma_only_flag", t.luma_only_flag, 0, 1, n);
    w.u(1, uint32_t(t.luma_only_flag));
    if (!t.luma_only_flag) {
        check("subsampling_x", t.subsampling_x, 0, 1, n);
        check("subsampling_y", t.subsampling_y, 0, t.subsampling_x, n);
        w.u(1, uint32_t(t.subsampling_x));
        w.u(1, uint32_t(t.subsampling_y));
    } else {
        check("chroma_scaling_from_luma (luma_only_flag = 1)", p.chroma_scaling_from_luma, 0, 0, n);
        check("num_cb_points (luma_only_flag = 1)", p.num_cb_points, 0, 0, n);
        check("num_cr_points (luma_only_flag = 1)", p.num_cr_points, 0, 0, n);
    }
    check("video_signal_characteristics_flag", t.video_signal_characteristics_flag, 0, 1, n);
    w.u(1, uint32_t(t.video_signal_characteristics_flag));
    if (t.video_signal_characteristics_flag) {
        check("bit_depth_minus8", t.bit_depth_minus8, 0, 4, n);
        w.u(3, uint32_t(t.bit_depth_minus8));
        check("cicp_info_present_flag", t.cicp_info_present_flag, 0, 1, n);
        w.u(1, uint32_t(t.cicp_info_present_flag));
        if (t.cicp_info_present_flag) {
            check("color_primaries", t.color_primaries, 0, 255, n);
            check("transfer_characteristics", t.transfer_characteristics, 0, 255, n);
            check("matrix_coefficients", t.matrix_coefficients, 0, 255, n);
            check("video_full_range_flag", t.video_full_range_flag, 0, 1, n);
            const int cp = t.color_primaries, tc = t.transfer_characteristics, mc = t.matrix_coefficients;
            if (cp == 0 || cp == 3 || (cp > 12 && cp != 22))
                check("color_primaries (reserved values excluded)", cp, 1, 2, n);
            if (tc == 0 || tc == 3 || tc > 18) check("transfer_characteristics (reserved values excluded)", tc, 1, 2, n);
            if (mc == 3 || mc > 14) check("matrix_coefficients (reserved values excluded)", mc, 0, 2, n);
            w.u(8, uint32_t(t.color_primaries));
            w.u(8, uint32_t(t.transfer_characteristics));
            w.u(8, uint32_t(t.matrix_coefficients));
            w.u(1, uint32_t(t.video_full_range_flag));
        }
    }
    check("chroma_scaling_from_luma", p.chroma_scaling_from_luma, 0, 1, n);
    if (p.chroma_scaling_from_luma) {
        check("num_cb_points (chroma_scaling_from_luma = 1)", p.num_cb_points, 0, 0, n);
        check("num_cr_points (chroma_scaling_from_luma = 1)", p.num_cr_points, 0, 0, n);
    }
    for (int c = 1; c <= 2; ++c)
        if (*scaling_of(p, c).count) {
            const std::string comp = kComp[c];
            check(comp + "_mult", *mults_of(p, c)[0], 0, 255, n);
            check(comp + "_luma_mult", *mults_of(p, c)[1], 0, 255, n);
            check(comp + "_offset", *mults_of(p, c)[2], 0, 511, n);
        }

    // Which scaling functions to predict: those that code shorter that way.
    const bool chroma_signalled = !t.luma_only_flag && !p.chroma_scaling_from_luma;
    DirectCoding direct[3];
    std::optional<Prediction> pred[3];
    bool use_pred[3] = {false, false, false};
    for (int c = 0; c < 3; ++c) {
        direct[c] = plan_direct(p, c, n);
        if (ref && (c == 0 || chroma_signalled)) pred[c] = plan_prediction(p, *ref, c);
        use_pred[c] = pred[c] && pred[c]->cost + 1 < direct[c].cost;
    }
    const bool predict = use_pred[0] || use_pred[1] || use_pred[2];
    w.u(1, predict);
    if (predict) w.u(1, use_pred[0]);
    if (use_pred[0]) write_predicted(w, p, *ref, 0, *pred[0]);
    else write_direct(w, p, 0, direct[0]);
    if (!t.luma_only_flag) w.u(1, uint32_t(p.chroma_scaling_from_luma));
    if (chroma_signalled) {
        for (int c = 1; c <= 2; ++c) {
            if (predict) w.u(1, use_pred[c]);
            if (use_pred[c]) write_predicted(w, p, *ref, c, *pred[c]);
            else write_direct(w, p, c, direct[c]);
        }
    }
    check("grain_scaling_minus_8", p.grain_scaling_minus_8, 0, 3, n);
    check("ar_coeff_lag", p.ar_coeff_lag, 0, 3, n);
    w.u(2, uint32_t(p.grain_scaling_minus_8));
    w.u(2, uint32_t(p.ar_coeff_lag));
    const int num_pos_luma = p.num_pos_luma();
    const int num_pos_chroma = p.num_pos_chroma();
    if (p.num_y_points) write_ar_coeffs(w, p, 0, num_pos_luma, n);
    if (p.chroma_scaling_from_luma || p.num_cb_points) write_ar_coeffs(w, p, 1, num_pos_chroma, n);
    if (p.chroma_scaling_from_luma || p.num_cr_points) write_ar_coeffs(w, p, 2, num_pos_chroma, n);
    check("ar_coeff_shift_minus_6", p.ar_coeff_shift_minus_6, 0, 3, n);
    check("grain_scale_shift", p.grain_scale_shift, 0, 3, n);
    w.u(2, uint32_t(p.ar_coeff_shift_minus_6));
    w.u(2, uint32_t(p.grain_scale_shift));
    for (int c = 1; c <= 2; ++c)
        if (*scaling_of(p, c).count && !use_pred[c]) {
            w.u(8, uint32_t(*mults_of(p, c)[0]));
            w.u(8, uint32_t(*mults_of(p, c)[1]));
            w.u(9, uint32_t(*mults_of(p, c)[2]));
        }
    check("overlap_flag", p.overlap_flag, 0, 1, n);
    check("clip_to_restricted_range", p.clip_to_restricted_range, 0, 1, n);
    w.u(1, uint32_t(p.overlap_flag));
    w.u(1, uint32_t(p.clip_to_restricted_range));
}

}  // namespace

std::vector<uint8_t> write_afgs1(const Afgs1Payload& payload, const Afgs1WriteOptions& options) {
    BitWriter w;
    if (options.t35_header) {
        w.u(8, kAfgs1CountryCode);
        w.u(16, kAfgs1ProviderCode);
        w.u(8, kAfgs1ProviderOrientedCode);
    }
    if (payload.afgs1_enable_flag != 0 && payload.afgs1_enable_flag != 1)
        throw Error(ErrorCode::kInvalidParams,
                    "AFGS1: " + out_of_range_message("afgs1_enable_flag", payload.afgs1_enable_flag, 0, 1));
    w.u(1, uint32_t(payload.afgs1_enable_flag));
    if (!payload.afgs1_enable_flag) {
        w.byte_align_zero();
        return w.bytes();
    }
    const long long count = static_cast<long long>(payload.sets.size());
    if (count < 1 || count > kAfgs1MaxSets)
        throw Error(ErrorCode::kInvalidParams,
                    "AFGS1: " + out_of_range_message("number of parameter sets", count, 1, kAfgs1MaxSets));
    std::set<int> seen;
    for (const auto& s : payload.sets)
        if (!seen.insert(s.film_grain_param_set_idx).second)
            throw Error(ErrorCode::kInvalidParams, "AFGS1: film_grain_param_set_idx = " +
                                                       std::to_string(s.film_grain_param_set_idx) +
                                                       " is used by two sets of one payload");
    w.u(4, 0);  // reserved_4bits
    w.u(3, uint32_t(count - 1));

    // The prediction reference is the first set, when this payload carries its parameters.
    std::optional<Av1FilmGrainParams> ref;
    const Afgs1ParamSet& first = payload.sets.front();
    if (options.predict_scaling && first.params.apply_grain && first.params.update_grain) ref = first.params;

    for (std::size_t n = 0; n < payload.sets.size(); ++n) {
        const Afgs1ParamSet& s = payload.sets[n];
        BitWriter body;
        Av1FilmGrainParams* r =
            (n > 0 && ref && s.film_grain_param_set_idx != first.film_grain_param_set_idx) ? &*ref : nullptr;
        write_params(body, s, r, int(n));
        // payload_size counts its own flag and field as well as the padding.
        const std::size_t bits = body.bit_count();
        const bool short_size = (bits + 3 + 7) / 8 < 4;
        const std::size_t size = short_size ? (bits + 3 + 7) / 8 : (bits + 9 + 7) / 8;
        if (size > 255)
            throw Error(ErrorCode::kInvalidParams, "AFGS1: parameter set " + std::to_string(n) + " needs " +
                                                       std::to_string(size) +
                                                       " bytes, more than payload_size can express (255)");
        w.u(1, short_size);
        w.u(short_size ? 2 : 8, uint32_t(size));
        const auto& bytes = body.bytes();
        for (std::size_t b = 0; b < bits; ++b) w.u(1, (bytes[b >> 3] >> (7 - (b & 7))) & 1u);
        const std::size_t used = bits + (short_size ? 3 : 9);
        for (std::size_t b = used; b < size * 8; ++b) w.u(1, 0);
    }
    return w.bytes();
}

std::vector<uint8_t> write_afgs1_resolved(Afgs1Payload resolved, const Afgs1WriteOptions& options) {
    for (Afgs1ParamSet& s : resolved.sets) s.params.update_grain = 1;
    return write_afgs1(resolved, options);
}

}  // namespace filmgrain

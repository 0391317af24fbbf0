#include "metadata/afgs1.hpp"

#include <algorithm>
#include <set>
#include <string>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"
#include "metadata/afgs1_fields.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain {
namespace {

[[noreturn]] void malformed(const std::string& msg) { throw Error(ErrorCode::kMalformedPayload, "AFGS1: " + msg); }

using afgs1_fields::ar_coeffs_of;
using afgs1_fields::mults_of;
using afgs1_fields::scaling_of;
const char* const* const kComp = afgs1_fields::kComponentName;

// ---------------------------------------------------------------- reading

class SetParser {
public:
    SetParser(BitReader& br, int set_number) : br_(br), n_(set_number) {}

    uint32_t u(int bits, const std::string& field) {
        name_ = "parameter set " + std::to_string(n_) + ": " + field;
        return br_.u(bits, name_.c_str());
    }
    [[noreturn]] void fail(const std::string& msg) const {
        malformed("parameter set " + std::to_string(n_) + ": " + msg);
    }

    // Prediction from the reference set (AFGS1 semantics of predict_*_scaling_flag).
    void predicted_points(int c, const Av1FilmGrainParams& ref, Av1FilmGrainParams& p) {
        const std::string comp = kComp[c];
        const int mult = int(u(9, comp + "_scaling_mult")) - 256;
        const int add = int(u(9, comp + "_scaling_add")) - 256;
        const int bits = int(u(3, "bits_per_" + comp + "_scaling_res"));
        Av1FilmGrainParams& r = const_cast<Av1FilmGrainParams&>(ref);
        const afgs1_fields::Scaling src = scaling_of(r, c);
        const afgs1_fields::Scaling dst = scaling_of(p, c);
        int res[14] = {};
        for (int i = 0; i < *src.count; ++i) res[i] = int(u(bits, indexed("point_" + comp + "_scaling_res", i)));
        // bits_per_*_scaling_res = 0: no residual (see the header).
        const int granularity = bits ? int(u(3, comp + "_scaling_res_granularity")) : 0;
        *dst.count = *src.count;
        for (int i = 0; i < *src.count; ++i) {
            const int residual = bits ? (res[i] - (1 << (bits - 1))) * granularity : 0;
            dst.values[i] = src.values[i];
            dst.scalings[i] = std::clamp(((src.scalings[i] * mult + 8) >> 4) + add + residual, 0, 255);
        }
    }

    void direct_points(int c, Av1FilmGrainParams& p) {
        const std::string comp = kComp[c];
        const afgs1_fields::Scaling dst = scaling_of(p, c);
        const int count = int(u(4, "num_" + comp + "_points"));
        if (count > dst.max_points) fail(out_of_range_message("num_" + comp + "_points", count, 0, dst.max_points));
        *dst.count = count;
        if (!count) return;
        const int bits_incr = int(u(3, "point_" + comp + "_value_increment_bits_minus1")) + 1;
        const int bits_scal = int(u(2, "point_" + comp + "_scaling_bits_minus5")) + 5;
        const int offset = c ? int(u(8, comp + "_scaling_offset")) : 0;
        int value = 0;
        for (int i = 0; i < count; ++i) {
            const std::string inc_name = indexed("point_" + comp + "_value_increment", i);
            const int inc = int(u(bits_incr, inc_name));
            if (i > 0 && inc == 0)
                fail(inc_name + " = 0: point values must be strictly increasing (the scaling interpolation "
                                "divides by the distance between points)");
            value += inc;
            if (value > 255)
                fail("point_" + comp + "_value[" + std::to_string(i) + "] = " + std::to_string(value) +
                     " (sum of the increments) is out of range [0, 255]");
            const int scaling = int(u(bits_scal, indexed("point_" + comp + "_scaling", i))) + offset;
            if (scaling > 255)
                fail(indexed("point_" + comp + "_scaling", i) + (c ? " + " + comp + "_scaling_offset" : std::string()) +
                     " = " + std::to_string(scaling) + " is out of range [0, 255]");
            dst.values[i] = value;
            dst.scalings[i] = scaling;
        }
    }

    void ar_coeffs(int c, int count, Av1FilmGrainParams& p) {
        const std::string comp = kComp[c];
        const int bits = int(u(2, "bits_per_ar_coeff_" + comp + "_minus5")) + 5;
        int* dst = ar_coeffs_of(p, c);
        // Writers code coefficient + 2^(bits-1); the bias is removed once (see header).
        for (int i = 0; i < count; ++i)
            dst[i] = int(u(bits, indexed("ar_coeffs_" + comp, i))) - (1 << (bits - 1)) + 128;
    }

private:
    BitReader& br_;
    int n_;
    std::string name_;
};

void check_cicp(SetParser& sp, const char* field, int v, bool reserved) {
    if (reserved) sp.fail(std::string(field) + " = " + std::to_string(v) + " is a reserved value (ITU-T H.273)");
}

}  // namespace

bool afgs1_has_t35_header(const uint8_t* data, std::size_t size) {
    return size >= 1 && data[0] == kAfgs1CountryCode;
}

Afgs1Payload Afgs1Reader::receive(const uint8_t* data, std::size_t size, bool t35_header) {
    BitReader br(data, size);
    if (t35_header) {
        const int country = int(br.u(8, "itu_t_t35_country_code"));
        if (country != kAfgs1CountryCode)
            malformed("itu_t_t35_country_code = " + std::to_string(country) + " is not the AOM code 0xB5 (181)");
        const int provider = int(br.u(16, "itu_t_t35_terminal_provider_code"));
        if (provider != kAfgs1ProviderCode)
            malformed("itu_t_t35_terminal_provider_code = " + std::to_string(provider) +
                      " is not the AOM code 0x5890 (22672)");
        const int oriented = int(br.u(8, "itu_t_t35_terminal_provider_oriented_code"));
        if (oriented != kAfgs1ProviderOrientedCode)
            malformed("itu_t_t35_terminal_provider_oriented_code = " + std::to_string(oriented) +
                      " is not AFGS1 (0x01)");
    }
    Afgs1Payload out;
    out.afgs1_enable_flag = int(br.u(1, "afgs1_enable_flag"));
    if (!out.afgs1_enable_flag) return out;
    br.u(4, "reserved_4bits");  // "ignored by a decoder"
    const int num_sets = int(br.u(3, "num_film_grain_sets_minus1")) + 1;

    // Work on a copy so that a malformed payload leaves the stored sets as they were.
    auto slots = slots_;
    auto has_params = has_params_;
    std::set<int> seen;
    int ref_idx = -1;
    for (int n = 0; n < num_sets; ++n) {
        SetParser sp(br, n);
        const std::size_t start = br.bit_position();
        const bool short_size = sp.u(1, "payload_less_than_4byte_flag") != 0;
        const int payload_size = int(sp.u(short_size ? 2 : 8, "payload_size"));

        const int idx = int(sp.u(3, "film_grain_param_set_idx"));
        if (!seen.insert(idx).second)
            sp.fail("film_grain_param_set_idx = " + std::to_string(idx) +
                    " is signalled twice in one payload (each set of a picture needs its own index)");
        if (n == 0) ref_idx = idx;
        auto& slot = slots[std::size_t(idx)];
        Afgs1ParamSet set;
        set.film_grain_param_set_idx = idx;
        const bool apply = sp.u(1, "apply_grain_flag") != 0;
        if (!apply) {
            // load_grain_params(idx); apply_grain_flag = 0; save_grain_params(idx)
            if (slot) set = *slot;
            set.params.apply_grain = 0;
            set.params.update_grain = 0;
            slot = set;
        } else {
            const int seed = int(sp.u(16, "grain_seed"));
            const bool update = sp.u(1, "update_grain_flag") != 0;
            if (!update) {
                if (!has_params[std::size_t(idx)])
                    sp.fail("update_grain_flag = 0 but film_grain_param_set_idx = " + std::to_string(idx) +
                            " holds no parameters (the first use of an index must have update_grain_flag = 1)");
                set = *slot;
                set.params.apply_grain = 1;
                set.params.grain_seed = seed;
                set.params.update_grain = 0;
                slot = set;
            } else {
                Av1FilmGrainParams& p = set.params;
                p.apply_grain = 1;
                p.grain_seed = seed;
                p.update_grain = 1;
                Afgs1SetTarget& t = set.target;
                t.apply_units_resolution_log2 = int(sp.u(4, "apply_units_resolution_log2"));
                t.apply_horz_resolution = int(sp.u(12, "apply_horz_resolution"));
                t.apply_vert_resolution = int(sp.u(12, "apply_vert_resolution"));
                t.luma_only_flag = int(sp.u(1, "luma_only_flag"));
                t.subsampling_x = t.subsampling_y = 0;
                if (!t.luma_only_flag) {
                    t.subsampling_x = int(sp.u(1, "subsampling_x"));
                    t.subsampling_y = int(sp.u(1, "subsampling_y"));
                    if (!t.subsampling_x && t.subsampling_y)
                        sp.fail("subsampling_x = 0 with subsampling_y = 1 (4:4:0) is not a format AV1 grain "
                                "synthesis defines");
                }
                t.video_signal_characteristics_flag = int(sp.u(1, "video_signal_characteristics_flag"));
                if (t.video_signal_characteristics_flag) {
                    t.bit_depth_minus8 = int(sp.u(3, "bit_depth_minus8"));
                    if (t.bit_depth_minus8 > 4) sp.fail(out_of_range_message("bit_depth_minus8", t.bit_depth_minus8, 0, 4));
                    t.cicp_info_present_flag = int(sp.u(1, "cicp_info_present_flag"));
                    if (t.cicp_info_present_flag) {
                        t.color_primaries = int(sp.u(8, "color_primaries"));
                        check_cicp(sp, "color_primaries", t.color_primaries,
                                   t.color_primaries == 0 || t.color_primaries == 3 ||
                                       (t.color_primaries > 12 && t.color_primaries < 22) || t.color_primaries > 22);
                        t.transfer_characteristics = int(sp.u(8, "transfer_characteristics"));
                        check_cicp(sp, "transfer_characteristics", t.transfer_characteristics,
                                   t.transfer_characteristics == 0 || t.transfer_characteristics == 3 ||
                                       t.transfer_characteristics > 18);
                        t.matrix_coefficients = int(sp.u(8, "matrix_coefficients"));
                        check_cicp(sp, "matrix_coefficients", t.matrix_coefficients,
                                   t.matrix_coefficients == 3 || t.matrix_coefficients > 14);
                        t.video_full_range_flag = int(sp.u(1, "video_full_range_flag"));
                    }
                }

                const bool predict = sp.u(1, "predict_scaling_flag") != 0;
                const Av1FilmGrainParams* ref = nullptr;
                if (predict) {
                    if (n == 0)
                        sp.fail("predict_scaling_flag = 1 in the first parameter set, which is itself the "
                                "prediction reference");
                    if (ref_idx == idx)
                        sp.fail("predict_scaling_flag = 1 but film_grain_param_set_idx = " + std::to_string(idx) +
                                " is the reference set's own index");
                    const auto& rs = slots[std::size_t(ref_idx)];
                    if (!rs || !has_params[std::size_t(ref_idx)])
                        sp.fail("predict_scaling_flag = 1 but the reference set " + std::to_string(ref_idx) +
                                " holds no scaling functions");
                    ref = &rs->params;
                }
                bool predicted[3] = {false, false, false};
                predicted[0] = predict && sp.u(1, "predict_y_scaling_flag");
                if (predicted[0]) sp.predicted_points(0, *ref, p);
                else sp.direct_points(0, p);

                p.chroma_scaling_from_luma = t.luma_only_flag ? 0 : int(sp.u(1, "chroma_scaling_from_luma_flag"));
                if (!t.luma_only_flag && !p.chroma_scaling_from_luma) {
                    for (int c = 1; c <= 2; ++c) {
                        predicted[c] = predict && sp.u(1, std::string("predict_") + kComp[c] + "_scaling_flag");
                        if (predicted[c]) {
                            sp.predicted_points(c, *ref, p);
                            Av1FilmGrainParams& r = const_cast<Av1FilmGrainParams&>(*ref);
                            if (*scaling_of(p, c).count)
                                for (int k = 0; k < 3; ++k) *mults_of(p, c)[k] = *mults_of(r, c)[k];
                        } else {
                            sp.direct_points(c, p);
                        }
                    }
                }
                p.grain_scaling_minus_8 = int(sp.u(2, "grain_scaling_minus8"));
                p.ar_coeff_lag = int(sp.u(2, "ar_coeff_lag"));
                const int num_pos_luma = p.num_pos_luma();
                int num_pos_chroma = num_pos_luma;
                if (p.num_y_points || predicted[0]) {
                    num_pos_chroma = num_pos_luma + 1;
                    sp.ar_coeffs(0, num_pos_luma, p);
                }
                if (p.chroma_scaling_from_luma || p.num_cb_points || predicted[1]) sp.ar_coeffs(1, num_pos_chroma, p);
                if (p.chroma_scaling_from_luma || p.num_cr_points || predicted[2]) sp.ar_coeffs(2, num_pos_chroma, p);
                p.ar_coeff_shift_minus_6 = int(sp.u(2, "ar_coeff_shift_minus6"));
                p.grain_scale_shift = int(sp.u(2, "grain_scale_shift"));
                for (int c = 1; c <= 2; ++c) {
                    if (*scaling_of(p, c).count && !predicted[c]) {
                        const auto m = mults_of(p, c);
                        const std::string comp = kComp[c];
                        *m[0] = int(sp.u(8, comp + "_mult"));
                        *m[1] = int(sp.u(8, comp + "_luma_mult"));
                        *m[2] = int(sp.u(9, comp + "_offset"));
                    }
                }
                p.overlap_flag = int(sp.u(1, "overlap_flag"));
                p.clip_to_restricted_range = int(sp.u(1, "clip_to_restricted_range_flag"));
                // Coefficients read for a plane that ends up without grain (prediction from
                // a reference without points) play no part in synthesis: keep the canonical
                // form (128) so that equal sets compare equal.
                Av1FilmGrainParams canonical;
                if (!p.num_y_points) p.ar_coeffs_y_plus_128 = canonical.ar_coeffs_y_plus_128;
                for (int c = 1; c <= 2; ++c) {
                    int* a = ar_coeffs_of(p, c);
                    const bool used = p.chroma_scaling_from_luma || *scaling_of(p, c).count;
                    for (int i = used ? p.num_pos_chroma() : 0; i < 25; ++i) a[i] = 128;
                }
                slot = set;
                has_params[std::size_t(idx)] = true;
            }
        }
        const std::size_t used = br.bit_position() - start;
        if (used > std::size_t(payload_size) * 8)
            sp.fail("payload_size = " + std::to_string(payload_size) + " bytes, but the set uses " +
                    std::to_string(used) + " bits");
        for (std::size_t b = used; b < std::size_t(payload_size) * 8; ++b)
            if (sp.u(1, "padding_zero_bit"))
                sp.fail("padding_zero_bit = 1 (padding bits must be 0; a writer and this reader disagree on the "
                        "set's length)");
        out.sets.push_back(set);
    }
    if (!br.only_trailing_bits_left())
        malformed("data after the last parameter set (" + std::to_string(br.bits_left()) +
                  " bits that are not zero padding)");
    slots_ = slots;
    has_params_ = has_params;
    return out;
}

}  // namespace filmgrain

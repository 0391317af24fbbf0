#include "bitstream/av1_frame_header.hpp"

#include <algorithm>
#include <string>

#include "bitstream/av1_film_grain_syntax.hpp"
#include "filmgrain/error.hpp"
#include "metadata/bit_reader.hpp"

namespace filmgrain::bitstream {
namespace {

constexpr int kKeyFrame = 0, kInterFrame = 1, kIntraOnlyFrame = 2, kSwitchFrame = 3;
constexpr int kPrimaryRefNone = 7;
constexpr int kAllFrames = 0xFF;
constexpr int kRefsPerFrame = 7;

// AV1 5.9.14 segmentation feature syntax (Segmentation_Feature_Bits / _Signed / _Max).
constexpr int kFeatureBits[8] = {8, 6, 6, 6, 6, 3, 0, 0};
constexpr int kFeatureSigned[8] = {1, 1, 1, 1, 1, 0, 0, 0};
constexpr int kFeatureMax[8] = {255, 63, 63, 63, 63, 7, 0, 0};

[[noreturn]] void malformed(const std::string& what) {
    throw Error(ErrorCode::kMalformedPayload, "AV1 frame header: " + what);
}

// AV1 4.10.6 su(n)
int su(BitReader& r, int n, const char* field) {
    int value = int(r.u(n, field));
    const int sign_mask = 1 << (n - 1);
    if (value & sign_mask) value -= 2 * sign_mask;
    return value;
}

// AV1 4.10.7 ns(n)
int ns(BitReader& r, int n, const char* field) {
    int w = 0;
    for (int x = n; x != 0; x >>= 1) w++;
    const int m = (1 << w) - n;
    const int v = int(r.u(w - 1, field));
    if (v < m) return v;
    return (v << 1) - m + int(r.u(1, field));
}

// AV1 5.9.26 decode_subexp(): the bits read depend on numSyms and the data only, so the
// reference value of decode_signed_subexp_with_ref is not needed to get past it.
void skip_subexp(BitReader& r, int num_syms) {
    int i = 0, mk = 0;
    const int k = 3;
    while (true) {
        const int b2 = i ? k + i - 1 : k;
        const int a = 1 << b2;
        if (num_syms <= mk + 3 * a) {
            ns(r, num_syms - mk, "subexp_final_bits");
            return;
        }
        if (r.flag("subexp_more_bits")) {
            i++;
            mk += a;
        } else {
            r.u(b2, "subexp_bits");
            return;
        }
    }
}

int tile_log2(int blk_size, int target) {
    int k = 0;
    while ((blk_size << k) < target) k++;
    return k;
}

struct FrameState {
    int frame_type = kKeyFrame;
    bool show_frame = true, showable_frame = false, error_resilient_mode = false;
    bool frame_is_intra = true;
    bool allow_screen_content_tools = false, force_integer_mv = false;
    bool frame_size_override_flag = false;
    bool disable_cdf_update = false;
    int order_hint = 0;
    int primary_ref_frame = kPrimaryRefNone;
    int refresh_frame_flags = 0;
    bool allow_intrabc = false, allow_high_precision_mv = false;
    std::array<int, kRefsPerFrame> ref_frame_idx{};
    int upscaled_width = 0, frame_width = 0, frame_height = 0, render_width = 0, render_height = 0;
    int mi_cols = 0, mi_rows = 0;
    std::array<std::array<int, 8>, 8> feature_enabled{}, feature_data{};
};

class HeaderParser {
public:
    HeaderParser(const Av1SequenceHeader& seq, const Av1Obu& obu, std::array<Av1FrameHeaderReader::Slot, 8>& slots)
        : s_(seq), obu_(obu), slots_(slots), r_(obu.payload) {}

    std::optional<Av1ShownFrame> run() {
        FrameState& f = f_;
        if (s_.reduced_still_picture_header) {
            f.frame_type = kKeyFrame;
            f.frame_is_intra = true;
            f.show_frame = true;
            f.showable_frame = false;
        } else {
            if (r_.flag("show_existing_frame")) return show_existing();
            f.frame_type = int(r_.u(2, "frame_type"));
            f.frame_is_intra = f.frame_type == kIntraOnlyFrame || f.frame_type == kKeyFrame;
            f.show_frame = r_.flag("show_frame");
            if (f.show_frame && s_.decoder_model_info_present_flag && !s_.equal_picture_interval)
                r_.u(s_.frame_presentation_time_length, "frame_presentation_time");
            f.showable_frame = f.show_frame ? f.frame_type != kKeyFrame : r_.flag("showable_frame");
            if (f.frame_type == kSwitchFrame || (f.frame_type == kKeyFrame && f.show_frame))
                f.error_resilient_mode = true;
            else
                f.error_resilient_mode = r_.flag("error_resilient_mode");
        }
        if (f.frame_type == kKeyFrame && f.show_frame)
            for (auto& slot : slots_) {
                slot.valid = false;
                slot.order_hint = 0;
            }
        f.disable_cdf_update = r_.flag("disable_cdf_update");
        f.allow_screen_content_tools = s_.seq_force_screen_content_tools == 2
                                           ? r_.flag("allow_screen_content_tools")
                                           : s_.seq_force_screen_content_tools != 0;
        if (f.allow_screen_content_tools)
            f.force_integer_mv = s_.seq_force_integer_mv == 2 ? r_.flag("force_integer_mv") : s_.seq_force_integer_mv != 0;
        if (f.frame_is_intra) f.force_integer_mv = true;
        if (s_.frame_id_numbers_present_flag) r_.u(s_.frame_id_length, "current_frame_id");
        if (f.frame_type == kSwitchFrame)
            f.frame_size_override_flag = true;
        else if (!s_.reduced_still_picture_header)
            f.frame_size_override_flag = r_.flag("frame_size_override_flag");
        f.order_hint = int(r_.u(s_.order_hint_bits, "order_hint"));
        f.primary_ref_frame =
            f.frame_is_intra || f.error_resilient_mode ? kPrimaryRefNone : int(r_.u(3, "primary_ref_frame"));
        if (s_.decoder_model_info_present_flag && r_.flag("buffer_removal_time_present_flag"))
            for (int op = 0; op < s_.operating_points; op++)
                if (s_.decoder_model_present_for_this_op[std::size_t(op)]) {
                    const int idc = s_.operating_point_idc[std::size_t(op)];
                    const bool in_temporal = (idc >> obu_.temporal_id) & 1, in_spatial = (idc >> (obu_.spatial_id + 8)) & 1;
                    if (idc == 0 || (in_temporal && in_spatial))
                        r_.u(s_.buffer_removal_time_length, "buffer_removal_time");
                }
        if (f.frame_type == kSwitchFrame || (f.frame_type == kKeyFrame && f.show_frame))
            f.refresh_frame_flags = kAllFrames;
        else
            f.refresh_frame_flags = int(r_.u(8, "refresh_frame_flags"));
        if ((!f.frame_is_intra || f.refresh_frame_flags != kAllFrames) && f.error_resilient_mode && s_.enable_order_hint)
            for (auto& slot : slots_) {
                const int hint = int(r_.u(s_.order_hint_bits, "ref_order_hint[i]"));
                if (hint != slot.order_hint) {
                    slot.valid = false;
                    slot.order_hint = hint;
                }
            }
        if (f.frame_is_intra) {
            frame_size();
            render_size();
            if (f.allow_screen_content_tools && f.upscaled_width == f.frame_width)
                f.allow_intrabc = r_.flag("allow_intrabc");
        } else {
            inter_frame_refs_and_size();
        }
        if (!s_.reduced_still_picture_header && !f.disable_cdf_update) r_.u(1, "disable_frame_end_update_cdf");
        // load_previous(): segmentation feature data of the primary reference frame
        if (f.primary_ref_frame != kPrimaryRefNone) {
            const auto& ref = slots_[std::size_t(f.ref_frame_idx[std::size_t(f.primary_ref_frame)])];
            f.feature_enabled = ref.feature_enabled;
            f.feature_data = ref.feature_data;
        }
        return after_refs();
    }

private:
    std::optional<Av1ShownFrame> show_existing() {
        const int idx = int(r_.u(3, "frame_to_show_map_idx"));
        if (s_.decoder_model_info_present_flag && !s_.equal_picture_interval)
            r_.u(s_.frame_presentation_time_length, "frame_presentation_time");
        if (s_.frame_id_numbers_present_flag) r_.u(s_.frame_id_length, "display_frame_id");
        const Av1FrameHeaderReader::Slot shown = slots_[std::size_t(idx)];
        if (!shown.valid)
            malformed("show_existing_frame of frame_to_show_map_idx = " + std::to_string(idx) +
                      ", a reference slot that holds no frame");
        // 7.21: showing an existing key frame refreshes every slot with it
        if (shown.frame_type == kKeyFrame)
            for (auto& slot : slots_) slot = shown;
        Av1ShownFrame out;
        out.show_existing_frame = true;
        if (s_.film_grain_params_present) out.grain = shown.grain;
        return out;
    }

    void superres_params() {
        FrameState& f = f_;
        int denom = 8;
        if (s_.enable_superres && r_.flag("use_superres")) denom = int(r_.u(3, "coded_denom")) + 9;
        f.upscaled_width = f.frame_width;
        f.frame_width = (f.upscaled_width * 8 + denom / 2) / denom;
    }

    void compute_image_size() {
        f_.mi_cols = 2 * ((f_.frame_width + 7) >> 3);
        f_.mi_rows = 2 * ((f_.frame_height + 7) >> 3);
    }

    void frame_size() {
        FrameState& f = f_;
        if (f.frame_size_override_flag) {
            f.frame_width = int(r_.u(s_.frame_width_bits, "frame_width_minus_1")) + 1;
            f.frame_height = int(r_.u(s_.frame_height_bits, "frame_height_minus_1")) + 1;
        } else {
            f.frame_width = s_.max_frame_width;
            f.frame_height = s_.max_frame_height;
        }
        superres_params();
        compute_image_size();
    }

    void render_size() {
        FrameState& f = f_;
        if (r_.flag("render_and_frame_size_different")) {
            f.render_width = int(r_.u(16, "render_width_minus_1")) + 1;
            f.render_height = int(r_.u(16, "render_height_minus_1")) + 1;
        } else {
            f.render_width = f.upscaled_width;
            f.render_height = f.frame_height;
        }
    }

    void inter_frame_refs_and_size() {
        FrameState& f = f_;
        if (s_.enable_order_hint && r_.flag("frame_refs_short_signaling"))
            throw Error(ErrorCode::kUnsupported,
                        "AV1 frame header: frame_refs_short_signaling = 1 (set_frame_refs, AV1 7.8) is not followed");
        for (int i = 0; i < kRefsPerFrame; i++) {
            f.ref_frame_idx[std::size_t(i)] = int(r_.u(3, "ref_frame_idx[i]"));
            if (!slots_[std::size_t(f.ref_frame_idx[std::size_t(i)])].valid)
                malformed("ref_frame_idx[" + std::to_string(i) + "] = " + std::to_string(f.ref_frame_idx[std::size_t(i)]) +
                          " names a reference slot that holds no frame");
            if (s_.frame_id_numbers_present_flag) r_.u(s_.delta_frame_id_length, "delta_frame_id_minus_1");
        }
        if (f.frame_size_override_flag && !f.error_resilient_mode) {
            bool found = false;
            for (int i = 0; i < kRefsPerFrame && !found; i++) {
                if (!r_.flag("found_ref")) continue;
                found = true;
                const auto& ref = slots_[std::size_t(f.ref_frame_idx[std::size_t(i)])];
                f.upscaled_width = ref.upscaled_width;
                f.frame_width = f.upscaled_width;
                f.frame_height = ref.frame_height;
                f.render_width = ref.render_width;
                f.render_height = ref.render_height;
            }
            if (!found) {
                frame_size();
                render_size();
            } else {
                superres_params();
                compute_image_size();
            }
        } else {
            frame_size();
            render_size();
        }
        f.allow_high_precision_mv = f.force_integer_mv ? false : r_.flag("allow_high_precision_mv");
        if (!r_.flag("is_filter_switchable")) r_.u(2, "interpolation_filter");
        r_.u(1, "is_motion_mode_switchable");
        if (!f.error_resilient_mode && s_.enable_ref_frame_mvs) r_.u(1, "use_ref_frame_mvs");
    }

    void tile_info() {
        const FrameState& f = f_;
        const bool sb128 = s_.use_128x128_superblock;
        const int sb_cols = sb128 ? (f.mi_cols + 31) >> 5 : (f.mi_cols + 15) >> 4;
        const int sb_rows = sb128 ? (f.mi_rows + 31) >> 5 : (f.mi_rows + 15) >> 4;
        const int sb_size = (sb128 ? 5 : 4) + 2;
        const int max_tile_width_sb = 4096 >> sb_size;
        int max_tile_area_sb = (4096 * 2304) >> (2 * sb_size);
        const int min_log2_tile_cols = tile_log2(max_tile_width_sb, sb_cols);
        const int max_log2_tile_cols = tile_log2(1, std::min(sb_cols, 64));
        const int max_log2_tile_rows = tile_log2(1, std::min(sb_rows, 64));
        const int min_log2_tiles = std::max(min_log2_tile_cols, tile_log2(max_tile_area_sb, sb_rows * sb_cols));
        int tile_cols_log2 = 0, tile_rows_log2 = 0;
        if (r_.flag("uniform_tile_spacing_flag")) {
            tile_cols_log2 = min_log2_tile_cols;
            while (tile_cols_log2 < max_log2_tile_cols && r_.flag("increment_tile_cols_log2")) tile_cols_log2++;
            tile_rows_log2 = std::max(min_log2_tiles - tile_cols_log2, 0);
            while (tile_rows_log2 < max_log2_tile_rows && r_.flag("increment_tile_rows_log2")) tile_rows_log2++;
        } else {
            int widest = 0, start = 0, cols = 0;
            for (; start < sb_cols; cols++) {
                const int size = ns(r_, std::min(sb_cols - start, max_tile_width_sb), "width_in_sbs_minus_1") + 1;
                widest = std::max(widest, size);
                start += size;
            }
            tile_cols_log2 = tile_log2(1, cols);
            max_tile_area_sb = min_log2_tiles > 0 ? (sb_rows * sb_cols) >> (min_log2_tiles + 1) : sb_rows * sb_cols;
            const int max_tile_height_sb = std::max(max_tile_area_sb / widest, 1);
            int rows = 0;
            for (start = 0; start < sb_rows; rows++)
                start += ns(r_, std::min(sb_rows - start, max_tile_height_sb), "height_in_sbs_minus_1") + 1;
            tile_rows_log2 = tile_log2(1, rows);
        }
        if (tile_cols_log2 > 0 || tile_rows_log2 > 0) {
            r_.u(tile_rows_log2 + tile_cols_log2, "context_update_tile_id");
            r_.u(2, "tile_size_bytes_minus_1");
        }
    }

    int read_delta_q(const char* field) { return r_.flag("delta_coded") ? su(r_, 7, field) : 0; }

    void segmentation_params() {
        FrameState& f = f_;
        const bool enabled = r_.flag("segmentation_enabled");
        if (!enabled) {
            f.feature_enabled = {};
            f.feature_data = {};
            return;
        }
        bool update_data = true;
        if (f.primary_ref_frame != kPrimaryRefNone) {
            if (r_.flag("segmentation_update_map")) r_.u(1, "segmentation_temporal_update");
            update_data = r_.flag("segmentation_update_data");
        }
        if (!update_data) return;  // the primary reference frame's, loaded by load_previous()
        for (int i = 0; i < 8; i++)
            for (int j = 0; j < 8; j++) {
                int value = 0;
                const bool on = r_.flag("feature_enabled");
                if (on) {
                    const int bits = kFeatureBits[j], limit = kFeatureMax[j];
                    if (kFeatureSigned[j])
                        value = std::clamp(su(r_, 1 + bits, "feature_value"), -limit, limit);
                    else
                        value = std::clamp(int(r_.u(bits, "feature_value")), 0, limit);
                }
                f.feature_enabled[std::size_t(i)][std::size_t(j)] = on;
                f.feature_data[std::size_t(i)][std::size_t(j)] = value;
            }
    }

    std::optional<Av1ShownFrame> after_refs() {
        FrameState& f = f_;
        const int num_planes = s_.mono_chrome ? 1 : 3;
        tile_info();
        // quantization_params()
        const int base_q_idx = int(r_.u(8, "base_q_idx"));
        int dq[5] = {read_delta_q("DeltaQYDc"), 0, 0, 0, 0};
        if (num_planes > 1) {
            const bool diff_uv_delta = s_.separate_uv_delta_q ? r_.flag("diff_uv_delta") : false;
            dq[1] = read_delta_q("DeltaQUDc");
            dq[2] = read_delta_q("DeltaQUAc");
            if (diff_uv_delta) {
                dq[3] = read_delta_q("DeltaQVDc");
                dq[4] = read_delta_q("DeltaQVAc");
            } else {
                dq[3] = dq[1];
                dq[4] = dq[2];
            }
        }
        if (r_.flag("using_qmatrix")) {
            r_.u(4, "qm_y");
            r_.u(4, "qm_u");
            if (s_.separate_uv_delta_q) r_.u(4, "qm_v");
        }
        segmentation_params();
        // delta_q_params(), delta_lf_params()
        bool delta_q_present = false;
        if (base_q_idx > 0) delta_q_present = r_.flag("delta_q_present");
        if (delta_q_present) {
            r_.u(2, "delta_q_res");
            if (!f.allow_intrabc && r_.flag("delta_lf_present")) {
                r_.u(2, "delta_lf_res");
                r_.u(1, "delta_lf_multi");
            }
        }
        // CodedLossless: every segment's qindex (get_qindex(1, segmentId)) and every delta 0
        bool coded_lossless = true;
        for (int seg = 0; seg < 8; seg++) {
            int qindex = base_q_idx;
            if (f.feature_enabled[std::size_t(seg)][0])
                qindex = std::clamp(base_q_idx + f.feature_data[std::size_t(seg)][0], 0, 255);
            coded_lossless = coded_lossless && qindex == 0 && !dq[0] && !dq[1] && !dq[2] && !dq[3] && !dq[4];
        }
        const bool all_lossless = coded_lossless && f.frame_width == f.upscaled_width;
        // loop_filter_params()
        if (!coded_lossless && !f.allow_intrabc) {
            const int l0 = int(r_.u(6, "loop_filter_level[0]"));
            const int l1 = int(r_.u(6, "loop_filter_level[1]"));
            if (num_planes > 1 && (l0 || l1)) {
                r_.u(6, "loop_filter_level[2]");
                r_.u(6, "loop_filter_level[3]");
            }
            r_.u(3, "loop_filter_sharpness");
            if (r_.flag("loop_filter_delta_enabled") && r_.flag("loop_filter_delta_update")) {
                for (int i = 0; i < 8; i++)
                    if (r_.flag("update_ref_delta")) su(r_, 7, "loop_filter_ref_deltas");
                for (int i = 0; i < 2; i++)
                    if (r_.flag("update_mode_delta")) su(r_, 7, "loop_filter_mode_deltas");
            }
        }
        // cdef_params()
        if (!coded_lossless && !f.allow_intrabc && s_.enable_cdef) {
            r_.u(2, "cdef_damping_minus_3");
            const int cdef_bits = int(r_.u(2, "cdef_bits"));
            for (int i = 0; i < (1 << cdef_bits); i++) {
                r_.u(4, "cdef_y_pri_strength");
                r_.u(2, "cdef_y_sec_strength");
                if (num_planes > 1) {
                    r_.u(4, "cdef_uv_pri_strength");
                    r_.u(2, "cdef_uv_sec_strength");
                }
            }
        }
        // lr_params()
        if (!all_lossless && !f.allow_intrabc && s_.enable_restoration) {
            bool uses_lr = false, uses_chroma_lr = false;
            for (int i = 0; i < num_planes; i++)
                if (r_.u(2, "lr_type") != 0) {  // Remap_Lr_Type maps only 0 to RESTORE_NONE
                    uses_lr = true;
                    uses_chroma_lr = uses_chroma_lr || i > 0;
                }
            if (uses_lr) {
                if (s_.use_128x128_superblock) {
                    r_.u(1, "lr_unit_shift");
                } else if (r_.flag("lr_unit_shift")) {
                    r_.u(1, "lr_unit_extra_shift");
                }
                if (s_.subsampling_x && s_.subsampling_y && uses_chroma_lr) r_.u(1, "lr_uv_shift");
            }
        }
        // read_tx_mode()
        if (!coded_lossless) r_.u(1, "tx_mode_select");
        // frame_reference_mode()
        const bool reference_select = f.frame_is_intra ? false : r_.flag("reference_select");
        // skip_mode_params()
        if (skip_mode_allowed(reference_select)) r_.u(1, "skip_mode_present");
        if (!f.frame_is_intra && !f.error_resilient_mode && s_.enable_warped_motion) r_.u(1, "allow_warped_motion");
        r_.u(1, "reduced_tx_set");
        global_motion_params();
        Av1FilmGrainParams grain = film_grain_params();

        // 7.20 reference frame update
        for (int i = 0; i < 8; i++)
            if ((f.refresh_frame_flags >> i) & 1) {
                auto& slot = slots_[std::size_t(i)];
                slot.valid = true;
                slot.frame_type = f.frame_type;
                slot.order_hint = f.order_hint;
                slot.upscaled_width = f.upscaled_width;
                slot.frame_width = f.frame_width;
                slot.frame_height = f.frame_height;
                slot.render_width = f.render_width;
                slot.render_height = f.render_height;
                slot.feature_enabled = f.feature_enabled;
                slot.feature_data = f.feature_data;
                slot.grain = grain;
            }
        if (!f.show_frame) return std::nullopt;
        Av1ShownFrame out;
        out.grain = grain;
        out.other_slot_grain = std::move(other_slot_grain_);
        return out;
    }

    int relative_dist(int a, int b) const {
        if (!s_.enable_order_hint) return 0;
        const int diff = a - b, m = 1 << (s_.order_hint_bits - 1);
        return (diff & (m - 1)) - (diff & m);
    }

    bool skip_mode_allowed(bool reference_select) const {
        const FrameState& f = f_;
        if (f.frame_is_intra || !reference_select || !s_.enable_order_hint) return false;
        int forward = -1, backward = -1, forward_hint = 0, backward_hint = 0;
        for (int i = 0; i < kRefsPerFrame; i++) {
            const int hint = slots_[std::size_t(f.ref_frame_idx[std::size_t(i)])].order_hint;
            if (relative_dist(hint, f.order_hint) < 0) {
                if (forward < 0 || relative_dist(hint, forward_hint) > 0) {
                    forward = i;
                    forward_hint = hint;
                }
            } else if (relative_dist(hint, f.order_hint) > 0) {
                if (backward < 0 || relative_dist(hint, backward_hint) < 0) {
                    backward = i;
                    backward_hint = hint;
                }
            }
        }
        if (forward < 0) return false;
        if (backward >= 0) return true;
        int second = -1, second_hint = 0;
        for (int i = 0; i < kRefsPerFrame; i++) {
            const int hint = slots_[std::size_t(f.ref_frame_idx[std::size_t(i)])].order_hint;
            if (relative_dist(hint, forward_hint) < 0 && (second < 0 || relative_dist(hint, second_hint) > 0)) {
                second = i;
                second_hint = hint;
            }
        }
        return second >= 0;
    }

    // AV1 5.9.24 / 5.9.25: only the bits; the parameters themselves do not matter here.
    void global_motion_params() {
        if (f_.frame_is_intra) return;
        constexpr int kIdentity = 0, kTranslation = 1, kRotZoom = 2, kAffine = 3;
        for (int ref = 0; ref < 7; ref++) {
            int type = kIdentity;
            if (r_.flag("is_global")) {
                if (r_.flag("is_rot_zoom"))
                    type = kRotZoom;
                else
                    type = r_.flag("is_translation") ? kTranslation : kAffine;
            }
            auto param = [&](int idx) {
                int abs_bits = 12;  // GM_ABS_ALPHA_BITS
                if (idx < 2) abs_bits = type == kTranslation ? 9 - !f_.allow_high_precision_mv : 12;
                const int mx = 1 << abs_bits;
                skip_subexp(r_, 2 * mx + 1);  // decode_signed_subexp_with_ref(-mx, mx + 1, r)
            };
            if (type >= kRotZoom) {
                param(2);
                param(3);
                if (type == kAffine) {
                    param(4);
                    param(5);
                }
            }
            if (type >= kTranslation) {
                param(0);
                param(1);
            }
        }
    }

    // AV1 5.9.30 film_grain_params(), with load_grain_params for update_grain = 0.
    Av1FilmGrainParams film_grain_params() {
        const FrameState& f = f_;
        Av1FilmGrainParams p;  // reset_grain_params(): apply_grain = 0
        if (!s_.film_grain_params_present || (!f.show_frame && !f.showable_frame)) return p;
        if (!r_.flag("apply_grain")) return p;
        const int seed = int(r_.u(16, "grain_seed"));
        const bool update = f.frame_type == kInterFrame ? r_.flag("update_grain") : true;
        if (!update) {
            const int ref = int(r_.u(3, "film_grain_params_ref_idx"));
            bool named = false;
            for (int i = 0; i < kRefsPerFrame; i++) named = named || f.ref_frame_idx[std::size_t(i)] == ref;
            if (!named)
                malformed("film_grain_params_ref_idx = " + std::to_string(ref) +
                          " is none of the frame's ref_frame_idx (AV1 6.8.20)");
            p = slots_[std::size_t(ref)].grain;
            p.grain_seed = seed;
            p.update_grain = 1;  // resolved
            p.film_grain_params_ref_idx = 0;
            for (int i = 0; i < kRefsPerFrame; i++) {
                const int other = f.ref_frame_idx[std::size_t(i)];
                Av1FilmGrainParams q = slots_[std::size_t(other)].grain;
                q.grain_seed = seed;
                q.update_grain = 1;
                q.film_grain_params_ref_idx = 0;
                const bool listed = std::any_of(other_slot_grain_.begin(), other_slot_grain_.end(),
                                                [&](const auto& e) { return e.first == other || e.second == q; });
                if (other != ref && !listed && !(q == p)) other_slot_grain_.emplace_back(other, q);
            }
            return p;
        }
        p.apply_grain = 1;
        p.grain_seed = seed;
        p.update_grain = 1;
        read_av1_film_grain_values(r_, s_, p);
        return p;
    }

    const Av1SequenceHeader& s_;
    const Av1Obu& obu_;
    std::array<Av1FrameHeaderReader::Slot, 8>& slots_;
    BitReader r_;
    FrameState f_;
    std::vector<std::pair<int, Av1FilmGrainParams>> other_slot_grain_;
};

}  // namespace

std::optional<Av1ShownFrame> Av1FrameHeaderReader::read(const Av1SequenceHeader& seq, const Av1Obu& obu) {
    // Parsed against a copy: a header that fails leaves the slots as they were.
    std::array<Slot, 8> slots = slots_;
    HeaderParser parser(seq, obu, slots);
    std::optional<Av1ShownFrame> shown = parser.run();
    slots_ = slots;
    return shown;
}

}  // namespace filmgrain::bitstream

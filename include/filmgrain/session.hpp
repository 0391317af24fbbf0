// filmgrain::Session: one stream's film grain, whatever the model. Metadata goes in as it
// arrives (FGC SEI bytes or typed sets, AV1 frame-header grain, AFGS1 T.35 payloads) and
// every output picture goes through apply(). The session owns what a decoder would otherwise
// re-implement: SEIs waiting for their picture, persistence and cancel, the AV1 reference
// slots and show_existing_frame, the AFGS1 stored sets and their selection, the
// invalid-parameter policy and the stripe threads. It is the one stream engine under every
// entry point: the C API (filmgrain.h) is a thin shell over it, and the `filmgrain` tool's
// apply, decode, demo, tradeoff and analysis round trip drive it too.
//
// Errors are thrown as filmgrain::Error (error.hpp) naming the field, its value and the
// allowed range. Sessions are independent of each other; one session is used from one thread
// at a time.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "filmgrain/av1_params.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/export.h"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {

struct SessionOptions {
    // FGC SEI synthesis: rdd5, vtm, vfgs or tr (TR 23002-9 beyond the references).
    FgcFlavour flavour = FgcFlavour::kRdd5;
    FgcPersistence persistence = FgcPersistence::kReference;
    // true: an invalid parameter set leaves pictures untouched and apply() reports why in
    // ApplyResult::message; false: apply() throws.
    bool passthrough_invalid = false;
    // Stripe workers per session, including the calling thread: 0..256, 0 = every hardware
    // thread. rdd5/vtm/tr and AV1/AFGS1 split each picture into stripes; the output is the
    // same for every count. So does vfgs: its reference's random state runs through the
    // picture in order, and each stripe starts from that state jumped ahead at set-up.
    int threads = 0;
    // vtm: the SPS coded luma size (HM's block size choice); 0 = picture size rounded up to 16.
    int coded_width = 0;
    int coded_height = 0;
    // FGC block size: 0 = the flavour's own; 8, 16 or 32 to force one (vfgs: 16 only).
    int block_size = 0;
    // vtm, tr: TR 23002-9 7.3.2.3 single-line blocks of 8, 16 or 32 samples (0: square).
    int single_line_blocks = 0;
    // vfgs: TR 23002-9 7.2.4.2 / 7.5.4 pattern interpolation (off = the reference).
    bool pattern_interpolation = false;
    // vfgs: the reference's -r seed, --gain (percent) and --outdepth (0: the input's depth;
    // dst then has this bit depth).
    std::optional<uint32_t> vfgs_seed;
    int vfgs_gain_percent = 100;
    int vfgs_output_bit_depth = 0;
    // AV1 / AFGS1: -1 keeps each set's clip_to_restricted_range; 0 or 1 replaces it (libaom
    // grain tables cannot carry the flag).
    int clip_to_restricted_range = -1;
    // true: the scalar reference stages instead of the vector ones (verification and
    // benchmarks; the output is identical).
    bool reference_kernels = false;
    // true: apply() reports the parameters it synthesized each picture from
    // (ApplyResult::applied), for tools that check a decoder against the session
    // (`filmgrain verify`). Off by default: it copies the parameter set per picture.
    bool report_applied_parameters = false;
};

// What apply() synthesized a picture from, as the stream state resolved it.
struct AppliedGrain {
    enum class Model { kNone, kFgc, kAv1 };
    Model model = Model::kNone;
    // FGC: the SEI in force, its syntax, the picture ids the seed came from (after
    // FrameInfo::seed), and whether this picture brought its own SEI (else it persisted).
    FgcParams fgc;
    FgcCodec fgc_codec = FgcCodec::kHevc;
    FgcPictureIds fgc_ids;
    bool fgc_own_sei = false;
    // AV1 and AFGS1: the set applied (update_grain resolved, seed and clipping as
    // synthesized) and the matrix_coefficients used.
    Av1FilmGrainParams av1;
    int matrix_coefficients = 2;
};

struct FrameInfo {
    FgcPictureIds ids;
    // rdd5/vtm/tr: the picture offset the seed derives from; AV1: grain_seed; vfgs: refused.
    std::optional<uint32_t> seed;
    // The picture's matrix_coefficients (CICP) when the caller knows it: AV1 synthesis uses
    // it instead of the parameter set's, and AFGS1 selection matches sets against it.
    std::optional<int> matrix_coefficients;
};

struct ApplyResult {
    bool grain_applied = false;
    std::string message;  // why no grain was added, when notable (passthrough, cancel)
    // The parameter set in force is invalid and the picture passed unchanged
    // (passthrough_invalid); `message` names the field. Not set for pictures that simply
    // have no grain (cancel, no AFGS1 payload or set for them, apply_grain = 0).
    bool parameters_refused = false;
    // SessionOptions::report_applied_parameters: what the picture was synthesized from
    // (absent when nothing governed it: no metadata, vfgs).
    std::optional<AppliedGrain> applied;
};

class FG_API Session {
public:
    // Throws Error(kInvalidArgument) naming the option at fault.
    explicit Session(const SessionOptions& options = {});
    ~Session();
    Session(Session&&) noexcept;
    Session& operator=(Session&&) noexcept;
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    // An FGC SEI arriving with `picture` (nullopt: the next picture applied).
    void receive_fgc_sei_payload(const uint8_t* payload, std::size_t size, FgcCodec codec,
                                 std::optional<FgcPictureIds> picture = std::nullopt);
    void receive_fgc_params(const FgcParams& params, FgcCodec codec,
                            std::optional<FgcPictureIds> picture = std::nullopt);
    // A frame header's film_grain_params(); resolves update_grain = 0 from the slots and
    // stores the result in the slots of refresh_frame_flags.
    void receive_av1_params(const Av1FilmGrainParams& params, unsigned refresh_frame_flags = 0,
                            int matrix_coefficients = 2);
    void show_existing_av1_frame(int frame_to_show_map_idx);
    // An AFGS1 ITU-T T.35 payload for the next picture applied, as fg_context_push_afgs1_t35
    // (filmgrain.h) describes. Throws Error(kMalformedPayload) naming the syntax element;
    // the session's stored sets are then unchanged.
    void receive_afgs1_t35(const uint8_t* payload, std::size_t size);
    void reset();

    // dst may be src. info nullptr: POC counts pictures from 0, idr_pic_id 0.
    ApplyResult apply(const FrameView& src, const FrameView& dst, const FrameInfo* info = nullptr);

    // Follows the stream over one picture without synthesizing it: the metadata state moves
    // on exactly as apply() would move it (pending SEIs, persistence and cancel, AFGS1
    // payloads, the picture count), so that work on a range of a stream can start mid-way
    // from the metadata alone. vfgs needs the picture's luma size (its random state steps
    // once per 16x16 block, and a skip jumps it as far): the first form throws
    // Error(kUnsupported) for it.
    void skip_picture(const FrameInfo* info = nullptr);
    void skip_picture(int luma_width, int luma_height, const FrameInfo* info = nullptr);

    const SessionOptions& options() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace filmgrain

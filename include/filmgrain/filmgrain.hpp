// filmgrain C++ API: the same per-stream context as the C API (filmgrain.h), for C++
// callers. Errors are thrown as filmgrain::Error (error.hpp) carrying an ErrorCode and a
// message that names the field, its value and the allowed range. Frames are FrameViews
// (frame.hpp); parameters are FgcParams (fgc_params.hpp) and Av1FilmGrainParams
// (av1_params.hpp).
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

struct ContextOptions {
    FgcFlavour flavour = FgcFlavour::kRdd5;
    FgcPersistence persistence = FgcPersistence::kReference;
    // true: an invalid parameter set leaves pictures untouched and apply() reports why in
    // ApplyResult::message; false: apply() throws.
    bool passthrough_invalid = false;
    // Stripe workers per context, including the calling thread: 0..256, 0 = every hardware
    // thread. rdd5/vtm and AV1/AFGS1 split each picture into stripes; the output is the same
    // for every count. vfgs runs on the calling thread (its reference's random state runs
    // through the picture in order).
    int threads = 0;
    // vtm: the SPS coded luma size (HM's block size choice); 0 = picture size rounded up to 16.
    int coded_width = 0;
    int coded_height = 0;
    std::optional<uint32_t> vfgs_seed;  // vfgs: the reference's -r
    int vfgs_gain_percent = 100;
};

struct FrameInfo {
    FgcPictureIds ids;
    // rdd5/vtm: the picture offset the seed derives from; AV1: grain_seed; vfgs: refused.
    std::optional<uint32_t> seed;
};

struct ApplyResult {
    bool grain_applied = false;
    std::string message;  // why no grain was added, when notable (passthrough, cancel)
};

// One stream's film grain state: SEIs waiting for their pictures, the parameter set in
// force with its persistence, AV1 reference slots, template caches. Not copyable;
// independent of every other instance.
class FG_API GrainContext {
public:
    // Throws Error(kInvalidArgument) naming the option at fault.
    explicit GrainContext(const ContextOptions& options = {});
    ~GrainContext();
    GrainContext(GrainContext&&) noexcept;
    GrainContext& operator=(GrainContext&&) noexcept;
    GrainContext(const GrainContext&) = delete;
    GrainContext& operator=(const GrainContext&) = delete;

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
    // the context's stored sets are then unchanged.
    void receive_afgs1_t35(const uint8_t* payload, std::size_t size);
    // One FGC or AV1 parameter set in the project's JSON form.
    void receive_json(std::string_view json, FgcCodec codec = FgcCodec::kHevc,
                      std::optional<FgcPictureIds> picture = std::nullopt);
    void reset();

    // dst may be src. info nullptr: POC counts pictures from 0, idr_pic_id 0.
    ApplyResult apply(const FrameView& src, const FrameView& dst, const FrameInfo* info = nullptr);

    const ContextOptions& options() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace filmgrain

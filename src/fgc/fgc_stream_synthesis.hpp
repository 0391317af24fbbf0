// The per-context FGC state a decoder keeps across pictures: the SEI in force, its
// persistence and cancellation, the validated parameters for the current picture format,
// and the template cache. One instance per stream; instances share nothing.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/params_resolution.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {

struct FgcOptions {
    FgcFlavour flavour = FgcFlavour::kRdd5;
    FgcPersistence persistence = FgcPersistence::kReference;
    int block_size = 0;  // 0: the flavour's own choice; 8, 16 or 32 to force one
    // Single-line blocks (TR 23002-9 7.3.2.3), vtm and tr flavours: 8, 16 or 32 averages the
    // intensity over Nx1 segments of a row and uses one template per component and picture
    // (the first intensity interval's); N is then the block size. 0: square blocks.
    int single_line_blocks = 0;
    // vtm: HM picks the block size from the *coded* picture size (SPS
    // pic_width/height_in_luma_samples), which a decoded picture does not carry. 0 means
    // the picture size rounded up to a multiple of 16, as encoders with a 16x16 minimum
    // coding block (x265's fast presets, which made the goldens) code it: a 1920x1080
    // picture coded as 1920x1088 takes the 16x16 mode. Decoders should pass the SPS size.
    int coded_width = 0;
    int coded_height = 0;
    // Invalid parameter sets: false -> apply() throws; true -> the picture passes through
    // untouched, as the reference decoders output it, and the result carries the reason.
    bool passthrough_invalid = false;
    // Stripe workers including the calling thread; 0 = every hardware thread. The output is
    // identical for every count.
    int threads = 0;
    // true: run the scalar reference stages instead of the optimized (vector) ones; for
    // verification and benchmarks, the output is identical.
    bool reference_kernels = false;
};

struct FgcFrameResult {
    bool grain_applied = false;
    bool sei_in_force = false;  // some SEI (valid or not) governs this picture
    std::string message;         // why no grain was added, when that is notable
    bool parameters_refused = false;  // the set in force is invalid (passthrough_invalid)
};

class FgcStreamSynthesis {
public:
    explicit FgcStreamSynthesis(const FgcOptions& options);
    ~FgcStreamSynthesis();
    FgcStreamSynthesis(const FgcStreamSynthesis&) = delete;
    FgcStreamSynthesis& operator=(const FgcStreamSynthesis&) = delete;

    // An FGC SEI that arrived with the next picture to be applied.
    void receive_sei(const FgcParams& params, FgcCodec codec = FgcCodec::kHevc);
    // Follows the stream over one picture without synthesizing it (the SEI in force and
    // persistence move on as apply() moves them).
    void skip_picture();
    // A new coded layer-wise video sequence: nothing persists across it.
    void reset();

    // Synthesizes one picture in output order. dst may alias src.
    FgcFrameResult apply(const FrameView& src, const FrameView& dst, const FgcPictureIds& ids);

    const FgcOptions& options() const { return options_; }
    // The SEI in force for the picture apply() last synthesized (null: none), and its codec.
    const FgcParams* params_in_force(FgcCodec* codec) const;
    int templates_built() const;
    // Working memory besides the templates (stripe buffers, block states), in bytes.
    std::size_t scratch_bytes() const;
    // Everything the context keeps between pictures: the 64x64 templates built, their
    // scaled per-interval tables and the scratch above (docs/performance-notes.md).
    std::size_t working_bytes() const;

private:
    void advance_to_next_picture();
    struct Active;
    FgcOptions options_;
    FgcParams pending_;  // valid when has_pending_; kept to reuse its storage
    bool has_pending_ = false;
    FgcCodec pending_codec_ = FgcCodec::kHevc;
    std::unique_ptr<Active> active_;
    std::unique_ptr<fgc::FgcPictureSynthesis> synthesis_;
};

}  // namespace filmgrain

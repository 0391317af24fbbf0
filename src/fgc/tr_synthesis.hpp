// Synthesis of one picture for what TR 23002-9 clause 7 and the FGC SEI semantics allow
// beyond the bit-exact references: the tr flavour, and single-line blocks in the vtm
// flavour. It runs the frequency-filtering pipeline's stages (template_generation,
// block_randomization, local_adaptation, deblocking, blending) with:
//
//  - film_grain_model_id 1: per-interval auto-regressive templates (ar_template_generation)
//    in place of the frequency-filtered ones, scaled by comp_model_value[0] with a shift one
//    smaller (the templates carry one more bit), and the colour correlation p1 added per
//    sample from the previous component's finished grain (see add_colour_correlation);
//  - blending_mode_id 1: multiplicative blending (multiplicative_blending.hpp);
//  - single-line blocks (TR 7.3.2.3): intensity averaged over N x 1 segments of one row
//    (N = 8, 16 or 32, which is then the block size) and one template per component and
//    picture, that of the component's first intensity interval; only the scale factor
//    follows the segments;
//  - a film grain bit depth of its own (separate_colour_description_present_flag). The SEI
//    describes grain for a picture of Bg bits, where the references' arithmetic makes it
//    g8 << (Bg - 8) from the 8-bit scale grain g8; carried to the picture's B bits it is
//    multiplied by 2^(B - Bg). For B, Bg >= 8 the product is g8 << (B - 8) exactly, the
//    grain the picture's own bit depth gives: the grain keeps its level relative to full
//    scale whatever Bg, and the decoded samples are taken to Bg and the intensity to 8
//    bits by shifts, which compose the same way. So Bg changes the allowed range of
//    comp_model_value[0] (255 << (Bg - 8), params_resolution) and nothing else. The colour
//    description (primaries, transfer, matrix, range) is not converted: a FrameView does
//    not carry the picture's own, and the grain is added in the picture's colour space.
//
// With model 0, additive blending, square blocks and no separate colour description the
// output is the rdd5 flavour's (base kTr) or the vtm flavour's (base kVtm), bit for bit.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "fgc/params_resolution.hpp"
#include "fgc/template_generation.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::fgc {

class TrFrameSynthesis {
public:
    // base: kTr (the rdd5 arithmetic: RDD 5 matrix, averages of the samples inside the
    // picture) or kVtm (VVC DCT-2 templates, edge-replicated averages, whole blocks).
    // block_size: 8, 16 or 32; single_line_blocks: 0 or the block size.
    TrFrameSynthesis(FgcFlavour base, int block_size, int single_line_blocks);
    // Builds the templates `params` needs. Not thread-safe; call before apply().
    void prepare(const ResolvedFgc& params);
    // pic_offset as for FgcFrameSynthesis::apply. dst may alias src.
    void apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst, int32_t pic_offset);
    int block_size() const { return block_size_; }
    int single_line_blocks() const { return single_line_; }
    FgcFlavour base() const { return base_; }
    // Templates built so far: frequency-filtered and auto-regressive.
    int templates_built() const { return cache_.built_count() + int(ar_cache_.size()); }

private:
    template <typename Pixel>
    void apply_component(const ResolvedFgc& params, int c, const FrameView& src, const FrameView& dst, uint32_t seed,
                         bool keep_grain);
    void add_colour_correlation(const ResolvedFgc& params, int c, const FrameView& frame, int y0, int rows, int stride);

    FgcFlavour base_;
    int block_size_;
    int single_line_;
    TemplateCache cache_;
    // Auto-regressive templates by (component, log2_scale_factor, p0, p2, A, p3).
    std::map<std::array<int, 6>, std::unique_ptr<GrainTemplate>> ar_cache_;
    // For the picture being synthesized: each interval's template, per component.
    std::array<std::vector<const GrainTemplate*>, 3> interval_template_;
    std::vector<uint32_t> states_;
    std::vector<int32_t> stripe_;
    std::vector<int16_t> rho_;  // p1 of each stripe sample's interval (colour correlation)
    std::array<std::vector<int32_t>, 3> plane_grain_;  // finished grain, kept for the next component
};

}  // namespace filmgrain::fgc

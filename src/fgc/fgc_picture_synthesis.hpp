// The frequency-filtering synthesis of one picture from resolved parameters, for every
// flavour but vfgs (rdd5, ffmpeg, vtm, tr): per component, 16-row (32-row) stripes of grain
// are built block by block from the templates, deblocked at vertical block edges and
// blended. Stripes are independent, so they can run in any order or in parallel with
// identical output.
//
// Two implementations of a stripe, chosen per picture:
//  - the scalar reference (reference_stripe.cpp), stage by stage as TR 23002-9 clause 7
//    reads: block randomization, local adaptation (square blocks or single-line segments),
//    the interval's template (frequency-filtered or auto-regressive) scaled by
//    comp_model_value[0] >> (log2_scale_factor + 6 - film_grain_model_id), deblocking,
//    the colour term of model 1, additive or multiplicative blending. It covers everything
//    the tr flavour allows; with model 0, additive blending and square blocks it is the
//    rdd5 (HM-2020), ffmpeg or vtm (HM/VTM) reference, depending on the flavour's
//    local-adaptation and deblocking rules;
//  - the optimized twin (optimized_stripe.cpp): pre-scaled tables and fused vector
//    deblocking + blending, for model 0 with additive blending, square blocks and the
//    rdd5, vtm or tr flavour. Tests prove it equal to the reference.
//
// film_grain_model_id 1 (tr): the colour correlation p1 of a chroma component reads the
// previous component's finished grain, so such a component's stripes run after all of the
// previous component's (colour_correlation.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "fgc/params_resolution.hpp"
#include "fgc/scaled_templates.hpp"
#include "fgc/simd/fgc_kernels.hpp"
#include "fgc/template_generation.hpp"
#include "core/kernels.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {
class ThreadPool;
}

namespace filmgrain::fgc {

using ::filmgrain::Kernels;

// The block size used for local adaptation and deblocking: RDD 5 always 8; HM/VTM 8 up to
// 1920x1080 luma samples of the coded picture, 16 up to 3840x2160, 32 above (deriveFGSBlkSize).
int default_block_size(FgcFlavour flavour, int luma_width, int luma_height);

// Departures from the flavour's reference that decoder implementations are known to make,
// re-synthesized by `filmgrain verify` (src/verify/fgc_mistakes) to name the one a decoder
// made. They run on the scalar reference stripe only; all false is the flavour itself.
struct FgcDeviations {
    bool no_deblocking = false;  // neither the template rows nor the vertical block edges
    // rdd5 / vtm / tr deblock every edge; FFmpeg only edges whose right block got grain
    // (deblocking.hpp). Toggled: each takes the other's rule.
    bool blank_block_deblocking_toggled = false;
    // Partial blocks at the right and bottom: averaged over (and given grain in) the samples
    // inside the picture (rdd5, ffmpeg, tr) or whole over edge-replicated padding (vtm).
    // Toggled: each takes the other's.
    bool partial_blocks_toggled = false;
    // Chroma blocks take their intensity interval from the co-sited luma block's average
    // (a 4:2:0 decoder that reuses luma's block averages) instead of their own.
    bool chroma_interval_from_luma = false;
    bool any() const {
        return no_deblocking || blank_block_deblocking_toggled || partial_blocks_toggled || chroma_interval_from_luma;
    }
};

class FgcPictureSynthesis {
public:
    // flavour: rdd5, ffmpeg, vtm or tr (vtm: VVC DCT-2 templates and edge-replicated
    // averages over whole blocks; the others: the RDD 5 matrix and averages of the samples
    // inside the picture). block_size: 8, 16 or 32. threads: stripe workers including the
    // caller (0 = every hardware thread); the output is the same for any count.
    // single_line_blocks (vtm, tr): 0 or the block size, TR 23002-9 7.3.2.3's N x 1 segments.
    FgcPictureSynthesis(FgcFlavour flavour, int block_size, int threads = 1, Kernels kernels = Kernels::kOptimized,
                      int single_line_blocks = 0);
    ~FgcPictureSynthesis();

    // Builds whatever templates `params` needs (the only allocation after the first frame
    // of a parameter set). Not thread-safe; do it before synthesizing stripes.
    void prepare(const ResolvedFgc& params);

    // Adds grain to every component; pic_offset is RDD 5's POC + (idr_pic_id << 5) or the
    // POC alone for vtm. dst may alias src. Planes without grain are copied when dst != src.
    void apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst, int32_t pic_offset);

    // Verification only (FgcDeviations); set before prepare().
    void set_deviations(const FgcDeviations& deviations);

    int block_size() const { return block_size_; }
    int single_line_blocks() const { return single_line_; }
    const TemplateCache& templates() const { return cache_; }
    // Templates built so far: frequency-filtered and auto-regressive.
    int templates_built() const { return cache_.built_count() + int(ar_cache_.size()); }
    // Bytes of the scaled template tables of the optimized path (ScaledTemplates).
    std::size_t scaled_template_bytes() const;

    int threads() const;
    // Bytes of working memory held besides the templates and their scaled copies (stripe
    // buffers, block states).
    std::size_t scratch_bytes() const;

private:
    // Grain rows the optimized stripe gathers before blending them (at most a block's rows)
    static constexpr int kBandRows = 8;
    // One thread's stripe buffers, grown on the calling thread in apply() and reused.
    struct Scratch {
        std::vector<int32_t> stripe;          // reference path
        std::vector<uint8_t> has_grain;       // ... ffmpeg flavour: the blocks that got grain
        std::vector<int16_t> rho;             // ... model 1: p1 of each sample's interval
        std::vector<uint32_t> sums;           // block sums of the stripe's block rows
        std::vector<uint32_t> last_row_sums;  // ... vtm: of the picture's last row, below which it replicates
        std::vector<const int16_t*> blocks;   // optimized path: row 0 of each block's scaled grain
        std::vector<const int8_t*> narrow_blocks;  // ... when the tables are int8
        std::vector<int32_t> places;          // ... each block column's place in the tables
        std::vector<int16_t> band;            // optimized path: the grain of one block row
        std::vector<int8_t> narrow_band;      // ... when the tables are int8
        std::vector<int16_t> scaled;          // components without scaled tables: blocks scaled here
        std::vector<simd::BlockCopy> copies;  // ... by these copies
    };
    // Whether the optimized stripes give this picture's output (see the top of this file).
    bool optimized_for(const ResolvedFgc& params, const FrameView& src) const;
    // Writes plane_grain_[c] when the next component's colour term reads it.
    template <typename Pixel>
    void reference_stripe(const ResolvedFgc& params, int c, const FrameView& src, const FrameView& dst, int by,
                          Scratch& scratch);
    // prefetch_next: the same thread takes the stripe below next (its rows are prefetched)
    template <typename Pixel>
    void optimized_stripe_of(const ResolvedFgc& params, int c, const PlaneView& src, const PlaneView& dst,
                             int bit_depth, int by, bool prefetch_next, Scratch& scratch) const;
    // Table: the element type of the component's scaled templates (int8_t when narrow)
    template <typename Pixel, int kBlock, typename Table>
    void optimized_stripe(const ResolvedFgc& params, int c, const PlaneView& src, const PlaneView& dst, int bit_depth,
                          int by, bool prefetch_next, Scratch& scratch) const;

    FgcFlavour flavour_;
    int block_size_;
    FgcDeviations deviations_;
    int single_line_;
    Kernels kernels_;
    TemplateCache cache_;
    // Auto-regressive templates (model 1) by (component, log2_scale_factor, p0, p2, A, p3).
    std::map<std::array<int, 6>, std::unique_ptr<GrainTemplate>> ar_cache_;
    // For the picture being synthesized: each interval's template, per component (reference path).
    std::array<std::vector<const GrainTemplate*>, 3> interval_template_;
    // Model 1: which components add the colour term, and which keep their finished grain for it.
    std::array<bool, 3> correlate_{};
    std::array<bool, 3> keep_grain_{};
    std::array<std::vector<int32_t>, 3> plane_grain_;
    std::unique_ptr<ThreadPool> pool_;
    std::vector<uint32_t> states_[3];
    ScaledTemplates scaled_[3];
    bool have_scaled_[3] = {false, false, false};
    // Per component and block average: the offset of its interval's tables from interval 0
    // (of the zero table when it has no interval), for the components with tables.
    std::array<int32_t, 256> table_offsets_[3] = {};
    std::vector<Scratch> scratch_;
};

void copy_plane(const PlaneView& src, const PlaneView& dst, int bytes_per_sample);

}  // namespace filmgrain::fgc

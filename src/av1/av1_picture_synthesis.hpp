// AV1 film grain synthesis (AV1 spec 7.18.3), bit-exact with libaom and dav1d.
//
// Work is split into 32-luma-row stripes. Everything shared by the stripes (the
// grain templates and the scaling functions) is built once per frame into an
// Av1SynthesisContext, which is immutable afterwards; apply_stripes() on disjoint
// stripe ranges may therefore run concurrently and gives the same output in any
// order or partition.
#pragma once
#include <memory>
#include <vector>

#include "av1/grain_blending.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/scaling_lookup.hpp"
#include "filmgrain/av1_params.hpp"
#include "core/kernels.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain {
class ThreadPool;
}

namespace filmgrain::av1 {

// The optimized stripes also keep allocation-free stripe buffers (Av1StripeScratch).
using ::filmgrain::Kernels;

// A stripe worker's memory, reused across stripes and frames: the two noise rows a stripe
// shares with the one above (and at 12 bits the two rows they fade from), per block its
// template origin and template row in this stripe and in the one above, and its overlap seam.
struct StripeScratch {
    std::vector<int16_t> noise;
    std::vector<int16_t> previous;
    std::vector<int32_t> origins, previous_origins;
    std::vector<const int16_t*> block_rows, previous_block_rows;
    std::vector<const int8_t*> byte_block_rows;  // block_rows in the int8 luma template (8 bits)
    // Each block's first sample in the rows shared with the stripe above (made in `noise`).
    std::vector<const int16_t*> shared_rows;
    std::vector<uint32_t> seams;
    // The stripe's co-sited luma averages (co_sited_luma_row) of horizontally subsampled
    // chroma above 8 bits, shared by both chroma planes: a stripe's chroma rows of samples.
    std::vector<uint16_t> co_sited_luma;

    // Sizes everything for pictures `luma_width` wide, with `co_sited_bytes` of shared
    // co-sited luma (Av1SynthesisContext::co_sited_bytes; no-op once large enough). Everything
    // a stripe may need is sized here: the synthesizer calls it for every worker before a
    // frame, so that a worker that got no stripe (or only some kinds) in the first frames
    // cannot allocate in a later one.
    void reserve(int luma_width, std::size_t co_sited_bytes);
    std::size_t bytes() const;

    // The random byte of every block of `stripe` (stripe_block_offsets). Every plane of a
    // stripe uses them, and with overlap the next stripe again, so the last two stripes'
    // are kept (keyed by seed and stripe: the scratch outlives frames).
    const uint8_t* block_offsets(int grain_seed, int stripe, int blocks);

private:
    struct DrawnOffsets {
        int grain_seed = -1, stripe = -1, blocks = 0;
        std::vector<uint8_t> bytes;
    };
    DrawnOffsets drawn_[2];
};

class Av1SynthesisContext {
public:
    // Validates `p` against the format (throws filmgrain::Error) and builds the
    // per-frame state. matrix_coefficients only matters for restricted clipping.
    // `templates` picks the grain template generator (both give the same templates).
    Av1SynthesisContext(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width, int height,
                        int matrix_coefficients, Kernels templates = Kernels::kReference);

    // Rebuilds the context for another frame, reusing its storage (no allocation once it
    // has held a frame of the same bit depth).
    void reset(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width, int height,
               int matrix_coefficients, Kernels templates = Kernels::kReference);

    int stripe_count() const;
    // Bytes of a stripe's shared co-sited luma rows (StripeScratch::co_sited_luma): above 8
    // bits with horizontally subsampled chroma, else 0 (nothing shared).
    std::size_t co_sited_bytes() const;
    // Bytes held by templates and scaling tables.
    std::size_t table_bytes() const;

    // Processes luma rows [32*s0, 32*s1) and the chroma rows co-sited with them.
    // dst may be src (in place). Planes that get no grain are copied when dst is
    // not src. The views must match the context's format, bit depth and size.
    void apply_stripes(const FrameView& src, const FrameView& dst, int s0, int s1) const;
    // The same with a chosen implementation and caller-owned scratch (no allocation once the
    // scratch has grown to the frame width). Concurrent calls need one scratch each.
    void apply_stripes(const FrameView& src, const FrameView& dst, int s0, int s1, Kernels kernels,
                       StripeScratch& scratch) const;

    const Av1FilmGrainParams& params() const { return p_; }
    const GrainTemplate& grain_template(int plane) const { return templates_[plane]; }
    const ScalingLookup& scaling(int plane) const { return scaling_[plane]; }
    bool plane_has_grain(int plane) const { return has_grain_[plane]; }

private:
    template <typename Pixel>
    void apply_stripe(const FrameView& src, const FrameView& dst, int stripe) const;
    template <typename Pixel>
    void apply_stripe_optimized(const FrameView& src, const FrameView& dst, int stripe, StripeScratch& scratch) const;
    // The planes of a stripe in the order both paths process them, with the rows of each the
    // stripe covers; planes without grain are copied here, the others handed to
    // blend(plane, first_row, rows, plane_width, plane_height).
    template <typename Pixel, typename Blend>
    void for_each_stripe_plane(const FrameView& src, const FrameView& dst, int stripe, Blend&& blend,
                               bool luma_first = false) const;

    Av1FilmGrainParams p_;
    ChromaFormat format_ = ChromaFormat::k420;
    int bit_depth_ = 8, width_ = 0, height_ = 0;
    int subx_ = 0, suby_ = 0;
    ClipLimits clip_;
    GrainTemplate templates_[3];
    // At 8 bits, the luma template as int8 (8-bit grain is -128..127) with
    // simd::kByteNoiseReadBytes spare bytes, for the kernels that read noise as bytes
    // (simd::BlockNoiseRow::byte_blocks); empty otherwise.
    std::vector<int8_t> luma_template_bytes_;
    ScalingLookup scaling_[3];  // [1], [2] alias luma's function with chroma_scaling_from_luma
    bool has_grain_[3] = {false, false, false};
    ChromaScalingIndex chroma_index_[3];
};

// Checks that a view is usable for the given format/bit depth/size (throws
// filmgrain::Error kInvalidArgument).
void check_frame_view(const FrameView& v, const char* name);

// Adds grain to `src`, writing `dst` (which may be `src` itself). With
// apply_grain == 0 the frame is copied unchanged. Throws filmgrain::Error on
// invalid parameters or views.
void apply_film_grain(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                      int matrix_coefficients);

// A stream-level synthesizer: owns a thread pool (`threads` workers including the caller;
// 0 = every hardware thread) and per-thread stripe scratch, so that frames after the first
// are synthesized without growing memory. The output does not depend on the thread count
// or on `kernels`. One instance per stream; instances share nothing.
class Av1PictureSynthesis {
public:
    explicit Av1PictureSynthesis(int threads = 0, Kernels kernels = Kernels::kOptimized);
    ~Av1PictureSynthesis();
    Av1PictureSynthesis(const Av1PictureSynthesis&) = delete;
    Av1PictureSynthesis& operator=(const Av1PictureSynthesis&) = delete;

    void apply(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst, int matrix_coefficients);
    int threads() const;
    // Working memory held: templates, scaling tables and every thread's stripe scratch.
    std::size_t working_bytes() const;

private:
    Kernels kernels_;
    std::unique_ptr<Av1SynthesisContext> context_;
    std::unique_ptr<ThreadPool> pool_;
    std::vector<StripeScratch> scratch_;
};

// apply_film_grain with `threads` stripe workers (0 = every hardware thread).
void apply_film_grain(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                      int matrix_coefficients, int threads);

}  // namespace filmgrain::av1

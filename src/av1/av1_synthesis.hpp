// AV1 film grain synthesis (AV1 spec 7.18.3), bit-exact with libaom and dav1d.
//
// Work is split into 32-luma-row stripes. Everything shared by the stripes (the
// grain templates and the scaling functions) is built once per frame into an
// Av1SynthesisContext, which is immutable afterwards; apply_stripes() on disjoint
// stripe ranges may therefore run concurrently and gives the same output in any
// order or partition.
#pragma once
#include "av1/grain_blending.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/scaling_lookup.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::av1 {

class Av1SynthesisContext {
public:
    // Validates `p` against the format (throws filmgrain::Error) and builds the
    // per-frame state. matrix_coefficients only matters for restricted clipping.
    Av1SynthesisContext(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width, int height,
                        int matrix_coefficients);

    int stripe_count() const;

    // Processes luma rows [32*s0, 32*s1) and the chroma rows co-sited with them.
    // dst may be src (in place). Planes that get no grain are copied when dst is
    // not src. The views must match the context's format, bit depth and size.
    void apply_stripes(const FrameView& src, const FrameView& dst, int s0, int s1) const;

    const Av1FilmGrainParams& params() const { return p_; }
    const GrainTemplate& grain_template(int plane) const { return templates_[plane]; }
    const ScalingLookup& scaling(int plane) const { return scaling_[plane]; }
    bool plane_has_grain(int plane) const { return has_grain_[plane]; }

private:
    template <typename Pixel>
    void apply_stripe(const FrameView& src, const FrameView& dst, int stripe) const;

    Av1FilmGrainParams p_;
    ChromaFormat format_;
    int bit_depth_, width_, height_;
    int subx_ = 0, suby_ = 0;
    ClipLimits clip_;
    GrainTemplate templates_[3];
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

}  // namespace filmgrain::av1

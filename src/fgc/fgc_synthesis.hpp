// The frequency-filtering synthesis of one picture from resolved parameters: per component,
// 16-row (32-row) stripes of grain are built block by block from the templates, deblocked
// at vertical block edges and blended. Stripes are independent, so they can run in any
// order or in parallel with identical output.
#pragma once
#include <cstdint>
#include <vector>

#include "fgc/params_resolution.hpp"
#include "fgc/template_generation.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::fgc {

// The block size used for local adaptation and deblocking: RDD 5 always 8; HM/VTM 8 up to
// 1920x1080 luma samples of the coded picture, 16 up to 3840x2160, 32 above (deriveFGSBlkSize).
int default_block_size(FgcFlavour flavour, int luma_width, int luma_height);

class FgcFrameSynthesis {
public:
    // block_size: 8, 16 or 32.
    FgcFrameSynthesis(FgcFlavour flavour, int block_size);

    // Builds whatever templates `params` needs (the only allocation after the first frame
    // of a parameter set). Not thread-safe; do it before synthesizing stripes.
    void prepare(const ResolvedFgc& params);

    // Adds grain to every component; pic_offset is RDD 5's POC + (idr_pic_id << 5) or the
    // POC alone for vtm. dst may alias src. Planes without grain are copied when dst != src.
    void apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst, int32_t pic_offset);

    int block_size() const { return block_size_; }
    const TemplateCache& templates() const { return cache_; }

private:
    template <typename Pixel>
    void apply_component(const ResolvedFgc& params, int c, const PlaneView& src, const PlaneView& dst, int bit_depth,
                         uint32_t seed);

    FgcFlavour flavour_;
    int block_size_;
    TemplateCache cache_;
    std::vector<uint32_t> states_;
    std::vector<int32_t> stripe_;
};

void copy_plane(const PlaneView& src, const PlaneView& dst, int bytes_per_sample);

}  // namespace filmgrain::fgc

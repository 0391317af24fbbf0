// The per-row work of the VFGS synthesis, split in two kernels, each with a scalar
// reference (namespace vfgs::scalar, vfgs_row_kernels_scalar.cpp, written from the
// per-sample helpers of vfgs_picture_synthesis.hpp) and a Highway twin (vfgs::simd,
// simd/vfgs_kernels_hwy.cpp) that tests/fgc/vfgs/vfgs_simd_equivalence_test.cpp
// proves equal on random input for every compiled target:
//
//  1. grain_row: per block, every sample's signed template sample picked by the sample's
//     intensity, with the vertical overlap on the first rows of a stripe, then the
//     horizontal deblocking of the edges between the row's blocks; also the sample's
//     scale. Unscaled, one int16 per sample (|g| <= 199: kMaxBlendGrain below).
//  2. blend_row: the scaling and the additive blend with VFGS's clip, optionally
//     rounded to 8 bits.
//
// At 8 and 10 bits the Highway side also has both in one pass (grain_blend_row_*), whose
// reference is the two scalar kernels run one after the other.
#pragma once
#include <cstdint>

#include "fgc/vfgs/vfgs_intensity_runs.hpp"

namespace filmgrain::vfgs {

inline constexpr int kTemplatePitch = 64;                              // template row length
inline constexpr int kTemplateBytes = kTemplatePitch * kTemplatePitch;  // one GrainTemplate

// One block of a block stripe: where its part of the template starts (oy * 64 + ox, the
// same in every template of the pool) and its sign; the same for the block above, which
// the overlap rows blend in. The row inside the block is the job's (pool, pool_up).
struct GrainBlock {
    int32_t offset = 0;
    int32_t offset_up = 0;
    int32_t sign = 1;
    int32_t sign_up = 1;
};

struct GrainRowJob {
    // template 0 of the component's pool advanced to this row's template row; template t is
    // kTemplateBytes further per index. pool_up: the same for the block above.
    const int8_t* pool = nullptr;
    const int8_t* pool_up = nullptr;
    const ComponentLuts* luts = nullptr;   // the component's tables (scalar kernels)
    const IntensityRuns* runs = nullptr;   // the same tables as runs (vector kernels)
    const GrainBlock* blocks = nullptr;
    int block_count = 0;
    int block_width = 16;                  // 16 (luma, 4:4:4 chroma) or 8 (subsampled chroma)
    int overlap_c1 = 0, overlap_c2 = 0;    // overlap_weights(); (0, 0) = no overlap
    int intensity_shift = 0;               // bit depth - 8
    bool pattern_interpolation = false;    // scalar kernels only
};

// The largest |grain| the blend kernels take above 8 bits (their 8-bit forms take any int16
// grain). grain_row writes at most 199: the int8 templates are clipped to +-127, the
// overlap's weights sum to 40 / 32 (+-159) and the deblocking's to 5 / 4.
inline constexpr int kMaxBlendGrain = 255;

// Per-row arguments of blend_row.
struct BlendRowJob {
    int width = 0;      // samples
    int shift = 0;      // scale_shift()
    int bit_depth = 8;  // of the input (the clip is 255 << (bit_depth - 8))
};

namespace scalar {
// `in` holds block_count * block_width samples (the caller pads a last block that sticks
// out of the row). The edges deblocked are those between the job's blocks; the caller
// deblocks the one between two calls (deblock_edge()).
void grain_row_u8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale);
void grain_row_u16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale);
// `out` may be `in`. blend_row_u16 and blend_row_u16_to_u8: |grain| <= kMaxBlendGrain.
void blend_row_u8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out);
void blend_row_u16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                   uint16_t* out);
// --outdepth 8 from 10 bits
void blend_row_u16_to_u8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                         uint8_t* out);
}  // namespace scalar

namespace simd {
// Same contracts; job.runs->count <= kMaxVectorRuns, no pattern interpolation.
void grain_row_u8(const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale);
void grain_row_u16(const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale);
void blend_row_u8(const BlendRowJob& job, const uint8_t* in, const int16_t* grain, const int16_t* scale, uint8_t* out);
void blend_row_u16(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                   uint16_t* out);
void blend_row_u16_to_u8(const BlendRowJob& job, const uint16_t* in, const int16_t* grain, const int16_t* scale,
                         uint8_t* out);
// grain_row then blend_row over the same row, in one pass with no grain in memory, where
// the target and the row allow (256-bit vectors; a row of whole blocks, 16 samples a
// multiple; 8 bits with a shift of 8..15, 10 bits with one of 6..15). Returns false,
// having written nothing, where they do not: then the caller runs the two kernels.
bool grain_blend_row_u8(const GrainRowJob& job, const BlendRowJob& blend, const uint8_t* in, uint8_t* out);
bool grain_blend_row_u16(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint16_t* out);
bool grain_blend_row_u16_to_u8(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint8_t* out);
}  // namespace simd

}  // namespace filmgrain::vfgs

// 64x64 grain templates of the frequency-filtering model (TR 23002-9 7.3.1, RDD 5 4.2):
// a band-limited block of Gaussian coefficients, inverse-transformed, clipped to +-127,
// with the vertical pre-deblocking of each block's first and last row baked in.
#pragma once
#include <array>
#include <cstdint>
#include <memory>

#include "fgc/grain_template.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::fgc {


// Which inverse transform and rounding the template uses.
enum class TemplateTransform { kRdd5Matrix, kVvcDct2 };

// Coefficients for cut-offs (h, v) in 2..14: the first 4(h+1) horizontal and 4(v+1)
// vertical frequencies, filled four at a time from the Gaussian table with the LFSR seeded
// from Seed_LUT[h-2 + 13(v-2)]; DC is zeroed.
void fill_template_coefficients(int cutoff_h, int cutoff_v, int32_t coeff[kTemplateSize][kTemplateSize]);

// The 2-D inverse transform every frequency-filtered template goes through (the flavours
// differ only in its parameters): pass 1 sums over the first index of the n x n row-major
// block `coeff` and rounds by >> first_shift, pass 2 sums over the second index and rounds
// by >> second_shift; the result is clipped to +-127. rows_follow_first_index: template row
// r holds the positions along the first index (VFGS, whose coefficient rows are vertical
// frequencies), else along the second (RDD 5 / HM, whose first index is horizontal).
// matrix_step 2 takes the even rows of the 64-point matrix: the 32-point basis times
// sqrt 2 (VFGS's 4:2:0 chroma, n = 32).
void inverse_transform_2d(const int32_t* coeff, int n, TemplateTransform transform, int matrix_step, int first_shift,
                          int second_shift, bool rows_follow_first_index, GrainTemplate& out);

// Scalar reference: inverse transform of the coefficients, clipped to +-127.
// RDD 5: two passes with the RDD 5 matrix, each (x + 128) >> 8.
// VTM:   two passes with the VVC DCT-2 matrix, each (x + 256) >> 9.
void inverse_transform_template(const int32_t coeff[kTemplateSize][kTemplateSize], TemplateTransform transform,
                                GrainTemplate& out);

GrainTemplate make_grain_template(int cutoff_h, int cutoff_v, TemplateTransform transform, int block_size);

// Lazily built templates of one context: only the cut-off pairs pictures use are made.
class TemplateCache {
public:
    TemplateCache(TemplateTransform transform, int block_size) : transform_(transform), block_size_(block_size) {}
    // Builds (h, v) if it is not there yet. Not thread-safe; call before parallel stages.
    const GrainTemplate& ensure(int cutoff_h, int cutoff_v);
    // The template for (h, v); it must have been ensured.
    const GrainTemplate& get(int cutoff_h, int cutoff_v) const { return *slots_[index(cutoff_h, cutoff_v)]; }
    int built_count() const;
    // Changing block size changes the baked-in pre-deblocking, so the cache starts over.
    void reconfigure(TemplateTransform transform, int block_size);
    int block_size() const { return block_size_; }

private:
    static int index(int h, int v) { return (h - 2) * 13 + (v - 2); }
    TemplateTransform transform_;
    int block_size_;
    std::array<std::unique_ptr<GrainTemplate>, 169> slots_;
};

}  // namespace filmgrain::fgc

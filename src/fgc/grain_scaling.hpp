// Scaling (TR 23002-9 7.3.2, RDD 5 4.3): a block's grain is its template samples times the
// block's sign and its intensity interval's scale factor (comp_model_value[0], after the
// chroma conversion), shifted right by log2_scale_factor + 6 (one less for the
// auto-regressive templates, which carry one more bit). The optimized stripes scale whole
// blocks or tables with simd::scale_template_blocks, tested equal to this.
#pragma once
#include <cstdint>

namespace filmgrain::fgc {

inline void scale_template_row(const int8_t* tmpl, int32_t signed_scale, int shift, int32_t* grain, int count) {
    for (int k = 0; k < count; k++) grain[k] = (signed_scale * tmpl[k]) >> shift;
}

}  // namespace filmgrain::fgc

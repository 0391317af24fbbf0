// AV1 spec 7.18.3.5: clipping limits of the noise application.
#include "av1/grain_blending.hpp"

#include "filmgrain/av1_params.hpp"

namespace filmgrain::av1 {

ClipLimits clip_limits(bool clip_to_restricted_range, int bit_depth, int matrix_coefficients) {
    const int up = bit_depth - 8;
    if (!clip_to_restricted_range) {
        const int max = (256 << up) - 1;
        return {0, max, max};
    }
    const bool identity = matrix_coefficients == kAv1MatrixCoefficientsIdentity;
    return {16 << up, 235 << up, (identity ? 235 : 240) << up};
}

}  // namespace filmgrain::av1

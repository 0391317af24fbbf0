// The colour term of the auto-regressive model (film_grain_model_id 1, tr flavour):
// p1 * G[c-1][x][y], the previous component's finished grain at the co-located position
// (the rounded mean of the 2x2 or 2x1 luma samples under a subsampled chroma sample), in
// units of 2^-log2_scale_factor. It is added to the grain after the component's own
// filtering rather than fed through its recursion: the templates are made before any
// picture, and the recursion would need the previous component's grain of the whole
// picture at every sample.
#pragma once
#include <cstdint>

#include "fgc/params_resolution.hpp"

namespace filmgrain::fgc {

// Component c (1 or 2) adds the term: model 1, c and c - 1 have grain, some p1 is not 0.
bool has_colour_correlation(const ResolvedFgc& params, int c);

// The previous component's grain of the whole plane, row-major.
struct PreviousGrain {
    const int32_t* grain = nullptr;
    int width = 0;
    int height = 0;
    int shift_x = 0;  // log2 of its samples per sample of this component, horizontally
    int shift_y = 0;  // ... and vertically
};

// Adds the term to `rows` rows of grain (`stride` apart) starting at picture row y0, for
// the `width` samples of each row; rho holds each sample's p1 (0: none) at the same layout.
// The reference form reads every co-located sample through the edge clamp; the other is the
// same per subsampling, with the clamp only where the co-located samples cross the previous
// plane's last column or row (tested equal on random grain, colour_correlation_test).
void add_colour_correlation(const PreviousGrain& previous, int log2_scale_factor, int y0, int rows, int width,
                            int32_t* grain, const int16_t* rho, int stride);
void add_colour_correlation_reference(const PreviousGrain& previous, int log2_scale_factor, int y0, int rows, int width,
                                      int32_t* grain, const int16_t* rho, int stride);

}  // namespace filmgrain::fgc

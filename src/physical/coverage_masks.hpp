// Per-bin coverage masks for the unit-zoom pixel-wise estimator.
//
// At zoom 1 sample k of pixel (x, y) lies in bin (k_c x + sx_k, k_c y + sy_k) at a bin-local
// point L_k that does not depend on the pixel (sample_points.hpp; k_c = cells per pixel). So
// a bin b can only ever be visited by the samples whose steps (sx_k, sy_k) are congruent to
// b modulo k_c, at their fixed points L_k. The samples fall into k_c^2 such classes; for each
// bin, the mask of its class's samples covered by the bin's grains is computed once, and a
// pixel's estimate becomes N bit look-ups instead of N point-in-grains searches. The result
// is the same test on the same float coordinates as every other estimator (inside_grain),
// so the output is bit-identical to theirs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "physical/bin_grid.hpp"
#include "physical/grain_field.hpp"
#include "physical/sample_points.hpp"

namespace filmgrain::physical {

// The optimized kernel reads whole vectors: class point lists are padded to this many floats
// (with NaN, which no grain covers), and every mask holds at least that many bits.
constexpr int kClassPointPad = 16;

// A bin's mask is made of 16-bit words: at the smallest radii a class holds about eight
// points (800 samples over 10x10 bins per pixel), and the estimator reads one word per sample
// from some fifty bin rows, so a word no wider than the class keeps those rows in L1/L2
// cache (64-bit words made them four times larger). A vector of at most 16 lanes never
// straddles two words.
using MaskWord = uint16_t;
constexpr int kMaskWordBits = 16;

struct SampleClasses {
    int cells_per_pixel = 1;
    int words = 1;  // MaskWords per bin mask
    // Class c = (sy mod k_c) * k_c + (sx mod k_c): its points are lx/ly[begin[c], begin[c] + size[c]).
    std::vector<uint32_t> begin, size;
    std::vector<float> lx, ly;
    // Per sample: its class, and the word and bit of its place in the class mask.
    std::vector<uint32_t> sample_class, sample_word;
    std::vector<uint8_t> sample_bit;
};

// Unit zoom only.
SampleClasses group_samples_by_class(const SamplePoints& points);

// The class of each bin of a grid: class = row_class[by] + col_class[bx] (grid-relative).
struct MaskLayout {
    BinGrid grid;
    int words = 1;
    std::vector<uint32_t> row_class, col_class;
};
MaskLayout mask_layout(const BinGrid& grid, const SampleClasses& classes);

// ORs into `masks` (the layout's bins, row-major, `words` per bin) the class samples each
// grain covers, in every bin bins_met_by() gives the grain: bit j of a bin's mask is set when
// its class point j is inside one of those grains. Painting grain by grain gives each bin the
// OR over the grains its list would hold (GrainField), with no list to build. The scalar
// reference, and the vector kernel that must equal it.
void paint_coverage_masks_reference(const Grain* grains, std::size_t n, const MaskLayout& layout,
                                    const SampleClasses& classes, MaskWord* masks);
void paint_coverage_masks_optimized(const Grain* grains, std::size_t n, const MaskLayout& layout,
                                    const SampleClasses& classes, MaskWord* masks);

// Generates the grains that reach [x0, x1] x [y0, y1] (GrainField::generate_by_cell_rows)
// and paints the masks of every bin of the grid over that rectangle (row-major, `words` per
// bin) from them. Returns the grain count.
std::size_t paint_tile_masks(GrainField& field, const CellIntensity& intensity, const GrainRadiusLaw& radius,
                             uint64_t seed, double x0, double y0, double x1, double y1, const SampleClasses& classes,
                             bool reference, std::vector<MaskWord>& masks);

}  // namespace filmgrain::physical

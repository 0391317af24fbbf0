// AV1 film grain (AV1 7.18.3) re-synthesized with one mistake that decoder and hardware
// implementations are known to make, so that `filmgrain verify` can name the mistake that
// reproduces a decoder's picture. Each mistake is a small departure from the reference
// stages (av1/), reusing them wherever the mistake leaves a stage alone; kNone gives the
// reference output exactly (tests/verify/av1_mistakes_test.cpp proves it on random sets).
// Slow on purpose: a scalar whole-picture path, run only on pictures that mismatch.
#pragma once
#include <vector>

#include "filmgrain/av1_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::verify {

enum class Av1Mistake {
    kNone,
    kNoOverlap,                     // overlap_flag ignored: blocks butt without the cross-fade
    kChromaSeedsNotPerPlane,        // Cb/Cr templates seeded with grain_seed itself (no XOR)
    kChromaSeedsSwapped,            // Cb seeded with Cr's constant and Cr with Cb's
    kBlockOffsetsSwapped,           // horizontal offset from the low nibble, vertical from the high
    kClipToRestrictedRangeToggled,  // clip_to_restricted_range ignored (or applied when 0)
    kChromaScalingFromLumaToggled,  // chroma_scaling_from_luma taken the other way
    kArCoeffShiftPlusOne,           // ar_coeff_shift_minus_6 read one too high
    kArCoeffShiftMinusOne,          // ... one too low
    kScalingShiftTruncated,         // (scale * grain) >> shift without Round2's rounding
    kTemplateNotCentred,            // block windows from the template's corner (no 9 / 6 margin)
    kLumaAverageTruncated,          // 4:2:0 / 4:2:2 co-sited luma average (a + b) >> 1
    kHighBitDepthAs8Bit,            // > 8 bits: grain made at 8 bits on src >> (bd - 8), shifted up
};

struct Av1MistakeInfo {
    Av1Mistake mistake;
    const char* id;
    const char* description;
};

// Every mistake above but kNone, in a fixed order (ties in the diagnosis keep it).
const std::vector<Av1MistakeInfo>& av1_picture_mistakes();

// false when the mistake cannot change this picture (overlap_flag = 0 for kNoOverlap, no
// chroma grain for the chroma mistakes, 8 bits for kHighBitDepthAs8Bit...): not worth trying.
bool av1_mistake_applies(Av1Mistake mistake, const Av1FilmGrainParams& p, const FrameView& picture);

// The reference synthesis of `p` on `src` into `dst` (same format; dst may not be src) with
// `mistake` made. Parameters are not validated beyond what the stages need: a mistaken
// reading may leave the ranges the syntax allows (the caller checked the real set).
void synthesize_av1_with_mistake(const Av1FilmGrainParams& p, Av1Mistake mistake, const FrameView& src,
                                 const FrameView& dst, int matrix_coefficients);

}  // namespace filmgrain::verify

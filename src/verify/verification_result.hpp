// What `filmgrain verify` found, frame by frame: the plain values the report writers
// (verification_report.hpp) turn into text, JSON and HTML, and the exit status a CI reads.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "io/video_file.hpp"
#include "verify/picture_comparison.hpp"

namespace filmgrain::verify {

// One known implementation mistake re-synthesized on a picture (mistake_hypotheses.hpp).
struct HypothesisOutcome {
    std::string id;           // e.g. "av1.no_overlap"
    std::string description;  // what the decoder would have done wrong
    bool exact = false;       // reproduces the decoder's picture sample for sample
    int64_t differing = 0;    // samples still differing under the hypothesis
    double squared_error = 0;
};

struct FrameVerification {
    int index = 0;            // output picture number in the stream / clean input
    bool missing = false;     // the decoder output no picture for it (frame alignment)
    int decoded_index = -1;   // which decoded picture was compared with it
    bool grain_expected = false;  // the reference adds grain to this picture
    bool exact = false;
    // Picture comparisons (absent with a .md5 list: then only exact is known).
    std::optional<PictureComparison> comparison;
    std::string expected_md5, decoded_md5;  // .md5 lists
    // Mismatching decoded pictures of 9 to 15 bits: their samples above the bit depth (a
    // decoder that does not clip, or data not in the format named), the first and the count.
    std::optional<SampleAboveBitDepth> above_bit_depth;
    // The heat map written for this picture (HeatMapWriter), relative to the report; empty: none.
    std::string heat_map;
    // Mismatching pictures: every hypothesis that applies to this picture, best first.
    std::vector<HypothesisOutcome> hypotheses;
};

// A hypothesis judged over every mismatching picture.
struct StreamDiagnosis {
    std::string id, description;
    int frames_tried = 0;
    int frames_exact = 0;     // mismatching pictures it reproduces exactly
    // bit-exact pictures it would have changed for certain (certain_hypotheses): evidence against
    int frames_contradicted = 0;
    int64_t differing = 0;    // samples still differing, summed over the pictures tried
    double squared_error = 0;
};

struct VerificationResult {
    std::string model;        // "av1", "fgc" (flavour named in `reference`), "none"
    std::string reference;    // what the expected pictures are: "av1 (AV1 7.18.3)", "fgc rdd5"...
    std::string decoded_name, source_name;
    int width = 0, height = 0;
    std::string pix_fmt;
    int luma_block = 32;      // the block side of the per-block counts
    std::vector<FrameVerification> frames;
    int extra_decoded = 0;    // decoded pictures no stream picture matched (output past the end)
    // Best first: hypotheses that explain the most mismatching pictures exactly, then the
    // fewest differing samples.
    std::vector<StreamDiagnosis> diagnosis;

    int mismatching() const;
    int missing() const;
    bool all_exact() const { return mismatching() == 0 && missing() == 0 && extra_decoded == 0; }
};

}  // namespace filmgrain::verify

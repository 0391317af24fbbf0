// The reports of `filmgrain verify`: a summary line for CI logs, a text report, JSON for
// tools, and an HTML page with a heat map per mismatching picture, so that a decoder team sees
// which pictures depart from the reference, where in the picture, and which known mistake
// (if any) reproduces their output.
#pragma once
#include <cstdio>
#include <string>

#include "filmgrain/frame.hpp"
#include "verify/picture_comparison.hpp"
#include "verify/verification_result.hpp"

namespace filmgrain::verify {

// Heat maps of where a decoded picture departs from the reference, as PNG files in one
// directory: the decoded luma in grey (at most kMaxWidth pixels wide), every block with
// differing samples tinted red, the more opaque the larger the share of its samples that
// differ, and outlined.
class HeatMapWriter {
public:
    static constexpr int kMaxWidth = 960;

    // Creates `directory` when missing (throws Error(kIo) naming it when it cannot).
    explicit HeatMapWriter(std::string directory);

    const std::string& directory() const { return directory_; }

    // Writes frame_NNNNNN.png for `frame_index` and returns that name (relative to
    // directory()). `luma`: the comparison of the decoded picture's luma plane, whose block
    // grid must cover `decoded` (throws Error(kInvalidArgument) otherwise, Error(kIo) naming
    // the file when it cannot be written).
    std::string write(int frame_index, const FrameView& decoded, const PlaneComparison& luma) const;

private:
    std::string directory_;
};

// One line for a CI log: "verify: 48 frames, 45 bit-exact, 3 mismatching, 0 missing; most
// likely: av1.no_overlap (overlap_flag ignored) reproduces 3/3 exactly", or
// "verify: 48 frames, all bit-exact".
std::string verification_summary_line(const VerificationResult& result);

// The readable report: what was compared, the bit-exact pictures as ranges, per mismatching
// picture and plane where it departs (counts, largest difference, first differing sample,
// blocks), the missing pictures and the diagnosis table. At most `max_frames_listed`
// mismatching or missing pictures are detailed (negative: all); the rest are counted. The
// summary line is not part of it: a caller prints verification_summary_line() last, where a CI
// log's tail shows it.
void print_verification_text(std::FILE* out, const VerificationResult& result, int max_frames_listed);

// Every field of the result as JSON, without a final newline (keys in snake_case; top level:
// model, reference, source, decoded, width, height, pix_fmt, luma_block, frames,
// extra_decoded, diagnosis, summary). Per plane the differing samples per block are rows of
// the block grid (differing_per_block[by][bx]); a plane without differences gives an empty
// array, as its blocks are all zero and a long run would otherwise fill the file with them.
std::string verification_json(const VerificationResult& result);

// A self-contained HTML page (inline CSS) at `html_path`: summary, diagnosis, the pictures
// (mismatching and missing first) and each picture's heat map (FrameVerification::heat_map,
// relative to the page). Written through OutputFile; throws Error(kIo) naming the file.
void write_verification_html(const std::string& html_path, const VerificationResult& result);

}  // namespace filmgrain::verify

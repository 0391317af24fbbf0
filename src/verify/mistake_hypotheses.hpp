// The mistakes `filmgrain verify` re-synthesizes on a mismatching picture: the AV1 and FGC
// picture mistakes (av1_mistakes.hpp, fgc_mistakes.hpp), the stream-state mistakes (AV1
// show_existing_frame and update_grain = 0 slots), and "grain not applied" / "applied twice".
// Each is judged by how close its picture lands to the decoder's; over the stream, the
// diagnosis ranks them by the pictures they reproduce exactly.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "filmgrain/av1_params.hpp"
#include "verify/fgc_mistakes.hpp"
#include "verify/verification_result.hpp"

namespace filmgrain::verify {

// What a picture's grain derives from.
struct PictureFacts {
    enum class Model { kNone, kAv1, kFgc };
    Model model = Model::kNone;
    // AV1 and AFGS1: the set applied, resolved (update_grain = 1), and the picture's CICP matrix.
    Av1FilmGrainParams av1;
    int matrix_coefficients = 2;
    bool av1_show_existing_frame = false;
    std::optional<Av1FilmGrainParams> av1_previous;  // the previous output picture's set
    std::vector<std::pair<int, Av1FilmGrainParams>> av1_other_slots;  // update_grain = 0 (Av1ShownFrame)
    FgcPictureFacts fgc;

    // The reference adds grain (which may still leave the picture unchanged, e.g. under
    // zero scaling).
    bool grain_expected() const;
};

struct Hypothesis {
    std::string id, description;
    // Makes the picture the mistaken decoder outputs from the clean picture (and the
    // reference's output, for "applied twice").
    std::function<void(const FrameView& clean, const FrameView& expected, const FrameView& dst)> synthesize;
};

// The id of every hypothesis there is (either model's, the stream-state ones, the generic two).
std::vector<std::string> hypothesis_ids();

// Every hypothesis that can change this picture, in a fixed order.
std::vector<Hypothesis> picture_hypotheses(const PictureFacts& facts, const FrameView& clean, int threads);

// Hypotheses whose effect on a picture is certain wherever they apply (grain dropped or
// doubled, a picture left without its persisted SEI, another seed or parameter set): a
// bit-exact picture where one of them applies contradicts it. Empty when none applies.
std::vector<std::string> certain_hypotheses(const PictureFacts& facts, const FrameView& clean);

// Judges every hypothesis on one mismatching picture, best first (one whose synthesis refuses
// the picture, e.g. vtm outside HM's size limits, is left out) (exact, then fewest
// differing samples, then smallest squared error). With `decoded_md5` set and `decoded`
// null, only exactness is known (MD5 lists): differing is -1 for the others.
std::vector<HypothesisOutcome> judge_hypotheses(const PictureFacts& facts, const FrameView& clean,
                                                const FrameView& expected, const FrameView* decoded,
                                                const std::string& decoded_md5, int threads);

// Ranks the hypotheses over the stream: most mismatching pictures reproduced exactly, then
// fewest bit-exact pictures contradicting them (FrameVerification + certain_hypotheses, given
// per frame in `contradictions`), then fewest differing samples. A hypothesis not tried on a
// mismatching picture (it cannot change it) counts as not reproducing it.
std::vector<StreamDiagnosis> diagnose_stream(const std::vector<FrameVerification>& frames,
                                             const std::vector<std::vector<std::string>>& contradictions);

}  // namespace filmgrain::verify

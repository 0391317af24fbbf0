#include "verify/mistake_hypotheses.hpp"

#include <algorithm>
#include <map>

#include "av1/av1_picture_synthesis.hpp"
#include "core/frame_buffer.hpp"
#include "filmgrain/error.hpp"
#include "verify/av1_mistakes.hpp"

namespace filmgrain::verify {
namespace {

constexpr const char* kNotApplied = "grain_not_applied";
constexpr const char* kAppliedTwice = "grain_applied_twice";
constexpr const char* kShowExistingReuse = "av1.show_existing_frame_reuses_previous";
constexpr const char* kWrongSlot = "av1.update_grain_wrong_slot";

bool av1_has_grain(const Av1FilmGrainParams& p, int planes) {
    return p.apply_grain && (p.num_y_points > 0 || (planes > 1 && (p.num_cb_points > 0 || p.num_cr_points > 0 ||
                                                                   p.chroma_scaling_from_luma)));
}

void reference_av1(const Av1FilmGrainParams& p, int mc, const FrameView& src, const FrameView& dst, int threads) {
    av1::apply_film_grain(p, src, dst, mc, threads);
}

}  // namespace

std::vector<std::string> hypothesis_ids() {
    std::vector<std::string> ids;
    for (const Av1MistakeInfo& m : av1_picture_mistakes()) ids.emplace_back(m.id);
    ids.emplace_back(kShowExistingReuse);
    ids.emplace_back(kWrongSlot);
    for (const FgcMistakeInfo& m : fgc_picture_mistakes()) ids.emplace_back(m.id);
    ids.emplace_back(kNotApplied);
    ids.emplace_back(kAppliedTwice);
    return ids;
}

bool PictureFacts::grain_expected() const {
    switch (model) {
    case Model::kAv1: return av1.apply_grain != 0;
    case Model::kFgc: return !fgc.params.film_grain_characteristics_cancel_flag;
    default: return false;
    }
}

std::vector<Hypothesis> picture_hypotheses(const PictureFacts& f, const FrameView& clean, int threads) {
    std::vector<Hypothesis> out;
    if (f.model == PictureFacts::Model::kAv1) {
        for (const Av1MistakeInfo& m : av1_picture_mistakes()) {
            if (!av1_mistake_applies(m.mistake, f.av1, clean)) continue;
            out.push_back({m.id, m.description, [p = f.av1, mistake = m.mistake, mc = f.matrix_coefficients](
                                                    const FrameView& c, const FrameView&, const FrameView& d) {
                               synthesize_av1_with_mistake(p, mistake, c, d, mc);
                           }});
        }
        if (f.av1_show_existing_frame && f.av1_previous && !(*f.av1_previous == f.av1))
            out.push_back({kShowExistingReuse,
                           "show_existing_frame shown with the previous picture's grain parameters and seed, not "
                           "those its reference slot holds",
                           [p = *f.av1_previous, mc = f.matrix_coefficients, threads](
                               const FrameView& c, const FrameView&, const FrameView& d) {
                               reference_av1(p, mc, c, d, threads);
                           }});
        for (const auto& [slot, set] : f.av1_other_slots)
            out.push_back({kWrongSlot,
                           "update_grain = 0 loaded from the wrong reference slot (slot " + std::to_string(slot) +
                               " instead of film_grain_params_ref_idx's)",
                           [p = set, mc = f.matrix_coefficients, threads](const FrameView& c, const FrameView&,
                                                                          const FrameView& d) {
                               reference_av1(p, mc, c, d, threads);
                           }});
    } else if (f.model == PictureFacts::Model::kFgc) {
        for (const FgcMistakeInfo& m : fgc_picture_mistakes()) {
            if (!fgc_mistake_applies(m.mistake, f.fgc, clean)) continue;
            out.push_back({m.id, m.description, [facts = f.fgc, mistake = m.mistake, threads](
                                                    const FrameView& c, const FrameView&, const FrameView& d) {
                               synthesize_fgc_with_mistake(facts, mistake, c, d, threads);
                           }});
        }
    }
    if (f.grain_expected()) {
        out.push_back({kNotApplied, "grain not applied: the decoder output the clean picture",
                       [](const FrameView& c, const FrameView&, const FrameView& d) { copy_frame(c, d); }});
        out.push_back({kAppliedTwice, "grain applied twice: the reference's grain added again to its own output",
                       [f, threads](const FrameView&, const FrameView& e, const FrameView& d) {
                           if (f.model == PictureFacts::Model::kAv1)
                               reference_av1(f.av1, f.matrix_coefficients, e, d, threads);
                           else
                               synthesize_fgc_with_mistake(f.fgc, FgcMistake::kNone, e, d, threads);
                       }});
    }
    return out;
}

std::vector<std::string> certain_hypotheses(const PictureFacts& f, const FrameView& clean) {
    std::vector<std::string> out;
    const bool grain = f.model == PictureFacts::Model::kAv1 ? av1_has_grain(f.av1, clean.plane_count())
                                                            : f.grain_expected();
    if (!grain) return out;
    out.push_back(kNotApplied);
    out.push_back(kAppliedTwice);
    if (f.model == PictureFacts::Model::kAv1) {
        if (f.av1_show_existing_frame && f.av1_previous && !(*f.av1_previous == f.av1))
            out.push_back(kShowExistingReuse);
        if (!f.av1_other_slots.empty()) out.push_back(kWrongSlot);
    } else if (f.model == PictureFacts::Model::kFgc) {
        for (FgcMistake m : {FgcMistake::kSemanticPersistence, FgcMistake::kIdrTermToggled})
            if (fgc_mistake_applies(m, f.fgc, clean)) out.push_back(fgc_mistake_id(m));
    }
    return out;
}

std::vector<HypothesisOutcome> judge_hypotheses(const PictureFacts& facts, const FrameView& clean,
                                                const FrameView& expected, const FrameView* decoded,
                                                const std::string& decoded_md5, int threads) {
    FrameBuffer out = FrameBuffer::uninitialized(clean.width, clean.height, PixelFormat{clean.format, clean.bit_depth});
    std::vector<HypothesisOutcome> outcomes;
    for (const Hypothesis& h : picture_hypotheses(facts, clean, threads)) {
        try {
            h.synthesize(clean, expected, out.view());
        } catch (const Error&) {
            continue;  // a reading the picture does not allow (vtm's size limits...): no decoder makes it
        }
        HypothesisOutcome o;
        o.id = h.id;
        o.description = h.description;
        if (decoded) {
            const Distance d = picture_distance(out.view(), *decoded);
            o.exact = d.exact();
            o.differing = d.differing;
            o.squared_error = d.squared_error;
        } else {
            o.exact = picture_md5(out.view()) == decoded_md5;
            o.differing = o.exact ? 0 : -1;
        }
        // several candidates under one id (the wrong slot): the closest speaks for it
        auto same = std::find_if(outcomes.begin(), outcomes.end(), [&](const HypothesisOutcome& e) { return e.id == o.id; });
        if (same == outcomes.end())
            outcomes.push_back(o);
        else if (o.exact || (!same->exact && o.differing >= 0 && o.differing < same->differing))
            *same = o;
    }
    std::stable_sort(outcomes.begin(), outcomes.end(), [](const HypothesisOutcome& a, const HypothesisOutcome& b) {
        if (a.exact != b.exact) return a.exact;
        if ((a.differing < 0) != (b.differing < 0)) return b.differing < 0;
        if (a.differing != b.differing) return a.differing < b.differing;
        return a.squared_error < b.squared_error;
    });
    return outcomes;
}

std::vector<StreamDiagnosis> diagnose_stream(const std::vector<FrameVerification>& frames,
                                             const std::vector<std::vector<std::string>>& contradictions) {
    std::vector<StreamDiagnosis> out;
    std::map<std::string, std::size_t> at;
    for (const FrameVerification& f : frames) {
        if (f.missing || f.exact || f.hypotheses.empty()) continue;
        for (const HypothesisOutcome& h : f.hypotheses) {
            auto [it, added] = at.emplace(h.id, out.size());
            if (added) out.push_back(StreamDiagnosis{h.id, h.description});
            StreamDiagnosis& d = out[it->second];
            d.frames_tried++;
            d.frames_exact += h.exact;
            if (h.differing > 0) d.differing += h.differing;
            d.squared_error += h.squared_error;
        }
    }
    // A picture a hypothesis was not tried on (it cannot change it) is one it does not explain:
    // the reference's own departure stands there.
    for (StreamDiagnosis& d : out) {
        for (const FrameVerification& f : frames) {
            if (f.missing || f.exact || f.hypotheses.empty()) continue;
            const bool tried = std::any_of(f.hypotheses.begin(), f.hypotheses.end(),
                                           [&](const HypothesisOutcome& h) { return h.id == d.id; });
            if (!tried && f.comparison) {
                d.differing += f.comparison->differing();
                d.squared_error += f.comparison->squared_error;
            }
        }
        for (std::size_t i = 0; i < frames.size() && i < contradictions.size(); i++)
            if (frames[i].exact && !frames[i].missing &&
                std::find(contradictions[i].begin(), contradictions[i].end(), d.id) != contradictions[i].end())
                d.frames_contradicted++;
    }
    std::stable_sort(out.begin(), out.end(), [](const StreamDiagnosis& a, const StreamDiagnosis& b) {
        if (a.frames_exact != b.frames_exact) return a.frames_exact > b.frames_exact;
        if (a.frames_contradicted != b.frames_contradicted) return a.frames_contradicted < b.frames_contradicted;
        if (a.differing != b.differing) return a.differing < b.differing;
        return a.squared_error < b.squared_error;
    });
    return out;
}

}  // namespace filmgrain::verify

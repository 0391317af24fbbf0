// Each hypothesis, made the "decoder's" output, is the one judge_hypotheses names first, and
// the stream diagnosis ranks by pictures reproduced exactly, then by contradicting pictures.
#include <gtest/gtest.h>

#include "verify/av1_mistakes.hpp"
#include "verify/mistake_hypotheses.hpp"
#include "verify_test_pictures.hpp"

using namespace filmgrain;
using namespace filmgrain::verify;

namespace {

PictureFacts av1_facts() {
    PictureFacts f;
    f.model = PictureFacts::Model::kAv1;
    f.av1 = test_pictures::full_av1_params();
    f.matrix_coefficients = 1;
    f.av1_show_existing_frame = true;
    Av1FilmGrainParams previous = f.av1;
    previous.grain_seed = 999;
    f.av1_previous = previous;
    Av1FilmGrainParams slot = f.av1;
    slot.point_y_scaling = {20, 30, 40};
    f.av1_other_slots = {{5, slot}};
    return f;
}

PictureFacts fgc_facts() {
    PictureFacts f;
    f.model = PictureFacts::Model::kFgc;
    f.fgc.params = test_pictures::full_fgc_params();
    f.fgc.codec = FgcCodec::kHevc;
    f.fgc.params.film_grain_characteristics_persistence_flag = false;
    f.fgc.ids = FgcPictureIds{9, 2};
    f.fgc.persisted = true;
    return f;
}

// For every hypothesis of `facts`: its picture as the decoder's output must be named first.
// Mistakes that give the same picture as another on this content are allowed to tie, and
// listed in `same_picture`.
void expect_each_named_first(const PictureFacts& facts, const FrameView& clean, const FrameView& expected,
                             const std::vector<std::pair<std::string, std::string>>& same_picture) {
    const std::vector<Hypothesis> hs = picture_hypotheses(facts, clean, 1);
    ASSERT_GE(hs.size(), 10u);
    for (const Hypothesis& h : hs) {
        FrameBuffer broken(clean.width, clean.height, PixelFormat{clean.format, clean.bit_depth});
        h.synthesize(clean, expected, broken.view());
        const FrameView decoded = broken.view();
        const std::vector<HypothesisOutcome> judged = judge_hypotheses(facts, clean, expected, &decoded, "", 1);
        ASSERT_FALSE(judged.empty());
        EXPECT_TRUE(judged[0].exact) << h.id;
        if (judged[0].id == h.id) continue;
        // named another: only if that one gives the identical picture (and is listed as such)
        const bool listed = std::any_of(same_picture.begin(), same_picture.end(), [&](const auto& p) {
            return (p.first == h.id && p.second == judged[0].id) || (p.second == h.id && p.first == judged[0].id);
        });
        EXPECT_TRUE(listed) << h.id << " was named " << judged[0].id;
        const auto own = std::find_if(judged.begin(), judged.end(), [&](const auto& o) { return o.id == h.id; });
        ASSERT_NE(own, judged.end());
        EXPECT_TRUE(own->exact) << h.id;
    }
}

}  // namespace

TEST(MistakeHypotheses, Av1EachMistakeIsNamedFirst) {
    for (int bd : {8, 10}) {
        const PixelFormat fmt{ChromaFormat::k420, bd};
        FrameBuffer clean = test_pictures::textured_picture(97, 75, fmt, 11);
        const PictureFacts f = av1_facts();
        FrameBuffer expected(97, 75, fmt);
        synthesize_av1_with_mistake(f.av1, Av1Mistake::kNone, clean.view(), expected.view(), 1);
        expect_each_named_first(f, clean.view(), expected.view(), {});
    }
}

TEST(MistakeHypotheses, FgcEachMistakeIsNamedFirst) {
    const PixelFormat fmt{ChromaFormat::k420, 8};
    FrameBuffer clean = test_pictures::textured_picture(204, 132, fmt, 12);
    test_pictures::add_edge_step(clean);
    const PictureFacts f = fgc_facts();
    FrameBuffer expected(204, 132, fmt);
    synthesize_fgc_with_mistake(f.fgc, FgcMistake::kNone, clean.view(), expected.view(), 1);
    // Semantic persistence leaves the picture clean: the same picture as grain not applied
    // (told apart over a stream by the pictures with their own SEI, see below).
    expect_each_named_first(f, clean.view(), expected.view(),
                            {{"fgc.semantic_persistence", "grain_not_applied"}});
}

TEST(MistakeHypotheses, StreamDiagnosisPrefersTheUncontradicted) {
    // Picture 0 had its own SEI and matched; pictures 1 and 2 persisted it and came out clean.
    std::vector<FrameVerification> frames(3);
    std::vector<std::vector<std::string>> contradictions(3);
    frames[0].exact = true;
    contradictions[0] = {"grain_not_applied", "grain_applied_twice"};
    for (int i = 1; i < 3; i++) {
        frames[std::size_t(i)].index = i;
        frames[std::size_t(i)].hypotheses = {
            {"grain_not_applied", "not applied", true, 0, 0},
            {"fgc.semantic_persistence", "semantic", true, 0, 0},
            {"fgc.no_deblocking", "no deblocking", false, 5000, 9000},
        };
    }
    const std::vector<StreamDiagnosis> d = diagnose_stream(frames, contradictions);
    ASSERT_EQ(d.size(), 3u);
    EXPECT_EQ(d[0].id, "fgc.semantic_persistence");
    EXPECT_EQ(d[0].frames_exact, 2);
    EXPECT_EQ(d[0].frames_contradicted, 0);
    EXPECT_EQ(d[1].id, "grain_not_applied");
    EXPECT_EQ(d[1].frames_contradicted, 1);
    EXPECT_EQ(d[2].id, "fgc.no_deblocking");
    EXPECT_EQ(d[2].differing, 10000);
}

TEST(MistakeHypotheses, Md5ListsJudgeExactnessOnly) {
    const PixelFormat fmt{ChromaFormat::k420, 8};
    FrameBuffer clean = test_pictures::textured_picture(204, 132, fmt, 2);
    const PictureFacts f = fgc_facts();
    FrameBuffer expected(204, 132, fmt);
    synthesize_fgc_with_mistake(f.fgc, FgcMistake::kNone, clean.view(), expected.view(), 1);
    FrameBuffer broken(204, 132, fmt);
    synthesize_fgc_with_mistake(f.fgc, FgcMistake::kNoDeblocking, clean.view(), broken.view(), 1);
    const std::vector<HypothesisOutcome> judged =
        judge_hypotheses(f, clean.view(), expected.view(), nullptr, picture_md5(broken.view()), 1);
    ASSERT_FALSE(judged.empty());
    EXPECT_EQ(judged[0].id, "fgc.no_deblocking");
    EXPECT_TRUE(judged[0].exact);
    EXPECT_EQ(judged[1].differing, -1);
}

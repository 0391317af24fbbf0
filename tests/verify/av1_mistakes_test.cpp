// The AV1 mistakes of verify: with none made the picture is the library's reference
// (random sets, every format and depth), and every mistake changes a picture that uses
// what it gets wrong, each differently from the others (or verify could not tell them apart).
#include <gtest/gtest.h>

#include <random>

#include "av1/av1_picture_synthesis.hpp"
#include "random_av1_params.hpp"
#include "verify/av1_mistakes.hpp"
#include "verify/picture_comparison.hpp"
#include "verify_test_pictures.hpp"

using namespace filmgrain;
using namespace filmgrain::verify;

namespace {

// A valid set: 4:2:0 needs both chroma functions or neither (AV1 6.8.20).
Av1FilmGrainParams random_params(std::mt19937& rng, bool mono) {
    Av1FilmGrainParams p = test_support::random_av1_params(rng, mono);
    if ((p.num_cb_points == 0) != (p.num_cr_points == 0)) p.num_cb_points = p.num_cr_points = 0;
    p.chroma_point_counts_signalled = true;
    return p;
}

}  // namespace

TEST(Av1Mistakes, NoMistakeIsTheReferenceOnRandomSets) {
    std::mt19937 rng(2026);
    int compared = 0;
    for (ChromaFormat cf : {ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444, ChromaFormat::k400})
        for (int bd : {8, 10, 12})
            for (int i = 0; i < 4; i++) {
                const PixelFormat fmt{cf, bd};
                const int w = 67 + 13 * i, h = 70 + 9 * i;  // partial blocks and stripes, odd chroma
                FrameBuffer clean = test_pictures::textured_picture(w, h, fmt, unsigned(i + bd));
                FrameBuffer ref(w, h, fmt), mine(w, h, fmt);
                const Av1FilmGrainParams p = random_params(rng, cf == ChromaFormat::k400);
                const int mc = i == 3 ? 0 : 1;  // MC_IDENTITY changes the restricted chroma clip
                av1::apply_film_grain(p, clean.view(), ref.view(), mc);
                synthesize_av1_with_mistake(p, Av1Mistake::kNone, clean.view(), mine.view(), mc);
                ASSERT_TRUE(picture_distance(ref.view(), mine.view()).exact())
                    << "format " << int(cf) << ", " << bd << " bits, set " << i;
                compared++;
            }
    EXPECT_EQ(compared, 48);
}

TEST(Av1Mistakes, EveryMistakeChangesThePictureItsOwnWay) {
    for (int bd : {8, 10}) {
        const PixelFormat fmt{ChromaFormat::k420, bd};
        FrameBuffer clean = test_pictures::textured_picture(97, 75, fmt, 7);
        const Av1FilmGrainParams p = test_pictures::full_av1_params();
        FrameBuffer ref(97, 75, fmt);
        synthesize_av1_with_mistake(p, Av1Mistake::kNone, clean.view(), ref.view(), 1);
        std::vector<FrameBuffer> outs;
        std::vector<const char*> ids;
        for (const Av1MistakeInfo& m : av1_picture_mistakes()) {
            if (!av1_mistake_applies(m.mistake, p, clean.view())) {
                EXPECT_TRUE(bd == 8 && m.mistake == Av1Mistake::kHighBitDepthAs8Bit) << m.id;
                continue;
            }
            FrameBuffer out(97, 75, fmt);
            synthesize_av1_with_mistake(p, m.mistake, clean.view(), out.view(), 1);
            EXPECT_FALSE(picture_distance(ref.view(), out.view()).exact()) << m.id << " at " << bd << " bits";
            outs.push_back(std::move(out));
            ids.push_back(m.id);
        }
        EXPECT_EQ(outs.size(), av1_picture_mistakes().size() - (bd == 8 ? 1 : 0));
        for (std::size_t a = 0; a < outs.size(); a++)
            for (std::size_t b = a + 1; b < outs.size(); b++)
                EXPECT_FALSE(picture_distance(outs[a].view(), outs[b].view()).exact()) << ids[a] << " vs " << ids[b];
    }
}

TEST(Av1Mistakes, MistakesThatCannotChangeAPictureAreNotTried) {
    Av1FilmGrainParams p = test_pictures::full_av1_params();
    FrameBuffer clean = test_pictures::textured_picture(64, 64, PixelFormat{ChromaFormat::k444, 8}, 1);
    p.overlap_flag = 0;
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kNoOverlap, p, clean.view()));
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kHighBitDepthAs8Bit, p, clean.view()));
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kLumaAverageTruncated, p, clean.view()));  // 4:4:4
    p.ar_coeff_shift_minus_6 = 3;
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kArCoeffShiftPlusOne, p, clean.view()));
    p.num_cb_points = p.num_cr_points = 0;
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kChromaSeedsSwapped, p, clean.view()));
    p.apply_grain = 0;
    EXPECT_FALSE(av1_mistake_applies(Av1Mistake::kBlockOffsetsSwapped, p, clean.view()));
}

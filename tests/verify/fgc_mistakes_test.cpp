// The FGC mistakes of verify: with none made the picture is what the session gives for the
// flavour, and every mistake changes a picture that uses what it gets wrong, each
// differently from the others.
#include <gtest/gtest.h>

#include "filmgrain/session.hpp"
#include "verify/fgc_mistakes.hpp"
#include "verify/picture_comparison.hpp"
#include "verify_test_pictures.hpp"

using namespace filmgrain;
using namespace filmgrain::verify;

namespace {

FgcPictureFacts facts_for(FgcFlavour flavour) {
    FgcPictureFacts f;
    f.params = test_pictures::full_fgc_params();
    f.codec = FgcCodec::kAvc;
    f.params.film_grain_characteristics_repetition_period = 0;
    f.ids = FgcPictureIds{6, 3};
    f.flavour = flavour;
    f.persisted = true;
    return f;
}

}  // namespace

TEST(FgcMistakes, NoMistakeIsTheSessionsPicture) {
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kFfmpeg})
        for (int bd : {8, 10}) {
            const PixelFormat fmt{ChromaFormat::k420, bd};
            FrameBuffer clean = test_pictures::textured_picture(204, 132, fmt, 3);
            const FgcPictureFacts f = facts_for(flavour);
            FrameBuffer ref(204, 132, fmt), mine(204, 132, fmt);
            SessionOptions o;
            o.flavour = flavour;
            Session session(o);
            session.receive_fgc_params(f.params, f.codec);
            FrameInfo info;
            info.ids = f.ids;
            ASSERT_TRUE(session.apply(clean.view(), ref.view(), &info).grain_applied);
            synthesize_fgc_with_mistake(f, FgcMistake::kNone, clean.view(), mine.view(), 1);
            EXPECT_TRUE(picture_distance(ref.view(), mine.view()).exact()) << fgc_flavour_name(flavour) << " " << bd;
            EXPECT_FALSE(picture_distance(ref.view(), clean.view()).exact());
        }
}

TEST(FgcMistakes, EveryMistakeChangesThePictureItsOwnWay) {
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm}) {
        const PixelFormat fmt{ChromaFormat::k420, 8};
        FrameBuffer clean = test_pictures::textured_picture(204, 132, fmt, 5);
        test_pictures::add_edge_step(clean);
        const FgcPictureFacts f = facts_for(flavour);
        FrameBuffer ref(204, 132, fmt);
        synthesize_fgc_with_mistake(f, FgcMistake::kNone, clean.view(), ref.view(), 1);
        std::vector<FrameBuffer> outs;
        std::vector<const char*> ids;
        for (const FgcMistakeInfo& m : fgc_picture_mistakes()) {
            if (!fgc_mistake_applies(m.mistake, f, clean.view())) continue;
            FrameBuffer out(204, 132, fmt);
            synthesize_fgc_with_mistake(f, m.mistake, clean.view(), out.view(), 1);
            EXPECT_FALSE(picture_distance(ref.view(), out.view()).exact()) << m.id << " (" << fgc_flavour_name(flavour) << ")";
            outs.push_back(std::move(out));
            ids.push_back(m.id);
        }
        // all but the flavour's own flavour and block size (8 for both at this size)
        EXPECT_EQ(outs.size(), fgc_picture_mistakes().size() - 2) << fgc_flavour_name(flavour);
        for (std::size_t a = 0; a < outs.size(); a++)
            for (std::size_t b = a + 1; b < outs.size(); b++)
                EXPECT_FALSE(picture_distance(outs[a].view(), outs[b].view()).exact()) << ids[a] << " vs " << ids[b];
    }
}

TEST(FgcMistakes, BlockSizeFollowsTheCodedSizeForVtm) {
    FgcPictureFacts f = facts_for(FgcFlavour::kVtm);
    // x265 codes 1080p as 1920x1088: more than 1920x1080 luma samples, so HM takes 16
    EXPECT_EQ(fgc_reference_block_size(f, 1920, 1080), 16);
    f.coded_width = 1920, f.coded_height = 1080;
    EXPECT_EQ(fgc_reference_block_size(f, 1920, 1080), 8);
    f.flavour = FgcFlavour::kRdd5;
    EXPECT_EQ(fgc_reference_block_size(f, 3840, 2160), 8);
}

TEST(FgcMistakes, PersistenceMistakeOnlyWherePersistenceEnds) {
    FrameBuffer clean = test_pictures::textured_picture(64, 64, PixelFormat{ChromaFormat::k420, 8}, 1);
    FgcPictureFacts f = facts_for(FgcFlavour::kRdd5);
    EXPECT_TRUE(fgc_mistake_applies(FgcMistake::kSemanticPersistence, f, clean.view()));
    f.persisted = false;  // its own SEI
    EXPECT_FALSE(fgc_mistake_applies(FgcMistake::kSemanticPersistence, f, clean.view()));
    f.persisted = true;
    f.params.film_grain_characteristics_repetition_period = 1;
    EXPECT_FALSE(fgc_mistake_applies(FgcMistake::kSemanticPersistence, f, clean.view()));
    f.codec = FgcCodec::kHevc;
    f.params.film_grain_characteristics_persistence_flag = false;
    EXPECT_TRUE(fgc_mistake_applies(FgcMistake::kSemanticPersistence, f, clean.view()));
    f.ids.idr_pic_id = 0;
    EXPECT_FALSE(fgc_mistake_applies(FgcMistake::kIdrTermToggled, f, clean.view()));
}

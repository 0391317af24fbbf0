// FGC SEI grain (TR 23002-9 clause 7 as RDD 5, HM/VTM and FFmpeg apply it) re-synthesized
// with one mistake decoders are known to make, so that `filmgrain verify` can name the one
// that reproduces a decoder's picture. The picture-level departures run on the reference
// stripe (fgc::FgcDeviations); the others are misreadings of the parameters, the seed, the
// block size or the persistence. FgcMistake::kNone is the flavour's own output.
#pragma once
#include <vector>

#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::verify {

// What a picture's grain derives from, as the stream gives it.
struct FgcPictureFacts {
    FgcParams params;  // the SEI in force for the picture
    FgcCodec codec = FgcCodec::kHevc;
    FgcPictureIds ids;
    FgcFlavour flavour = FgcFlavour::kRdd5;  // the reference the decoder should match
    int coded_width = 0, coded_height = 0;   // vtm's block size rule; 0: rounded up to 16
    bool persisted = false;  // the picture has no SEI of its own: the SEI in force came earlier
};

enum class FgcMistake {
    kNone,
    kFlavourRdd5,                // RDD 5 (HM-2020) where another flavour is the reference
    kFlavourVtm,                 // HM/VTM
    kFlavourFfmpeg,              // FFmpeg's h274
    kIdrTermToggled,             // pic_offset with idr_pic_id << 5 where the flavour has none, or without
    kBlockSize8,                 // another block size than the flavour's (e.g. chosen by the
    kBlockSize16,                //   visible instead of the coded picture size)
    kBlockSize32,
    kNoDeblocking,
    kBlankBlockDeblockingToggled,  // edges beside blocks without grain deblocked the other way
    kPartialBlocksToggled,         // partial blocks over padding (or inside only)
    kSemanticPersistence,        // persistence_flag = 0 honoured: a picture without SEI gets none
    kLog2ScaleFactorPlusOne,
    kLog2ScaleFactorMinusOne,
    kChromaIntervalsFromLuma,    // 4:2:0 chroma blocks choose intervals by the co-sited luma average
};

struct FgcMistakeInfo {
    FgcMistake mistake;
    const char* id;
    const char* description;
};
const std::vector<FgcMistakeInfo>& fgc_picture_mistakes();
// The id fgc_picture_mistakes() gives `mistake` ("" for kNone).
const char* fgc_mistake_id(FgcMistake mistake);

// false when the mistake cannot change this picture (the reference's own flavour or block
// size, idr_pic_id 0, a picture with its own SEI for kSemanticPersistence, no chroma...).
bool fgc_mistake_applies(FgcMistake mistake, const FgcPictureFacts& facts, const FrameView& picture);

// The picture's grain with `mistake` made (kNone: the reference) into dst (dst may not be
// src). Throws Error when the facts' parameters are invalid for the reference flavour.
void synthesize_fgc_with_mistake(const FgcPictureFacts& facts, FgcMistake mistake, const FrameView& src,
                                 const FrameView& dst, int threads);

// The flavour's block size for the picture (TR 23002-9 / HM deriveFGSBlkSize for vtm).
int fgc_reference_block_size(const FgcPictureFacts& facts, int width, int height);

}  // namespace filmgrain::verify

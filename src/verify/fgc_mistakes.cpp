#include "verify/fgc_mistakes.hpp"

#include "core/frame_buffer.hpp"
#include "fgc/fgc_picture_synthesis.hpp"
#include "fgc/params_resolution.hpp"

namespace filmgrain::verify {
namespace {

FgcFlavour flavour_of(FgcMistake m, FgcFlavour reference) {
    switch (m) {
    case FgcMistake::kFlavourRdd5: return FgcFlavour::kRdd5;
    case FgcMistake::kFlavourVtm: return FgcFlavour::kVtm;
    case FgcMistake::kFlavourFfmpeg: return FgcFlavour::kFfmpeg;
    default: return reference;
    }
}

int forced_block_size(FgcMistake m) {
    return m == FgcMistake::kBlockSize8 ? 8 : m == FgcMistake::kBlockSize16 ? 16 : m == FgcMistake::kBlockSize32 ? 32 : 0;
}

bool persistence_ends_with_picture(const FgcPictureFacts& f) {
    return f.codec == FgcCodec::kAvc ? f.params.film_grain_characteristics_repetition_period == 0
                                     : !f.params.film_grain_characteristics_persistence_flag;
}

}  // namespace

const std::vector<FgcMistakeInfo>& fgc_picture_mistakes() {
    static const std::vector<FgcMistakeInfo> list = {
        {FgcMistake::kFlavourRdd5, "fgc.flavour_rdd5", "RDD 5 (HM-2020) synthesis instead of the reference flavour"},
        {FgcMistake::kFlavourVtm, "fgc.flavour_vtm", "HM/VTM synthesis instead of the reference flavour"},
        {FgcMistake::kFlavourFfmpeg, "fgc.flavour_ffmpeg", "FFmpeg's h274 synthesis instead of the reference flavour"},
        {FgcMistake::kIdrTermToggled, "fgc.idr_term_in_seed",
         "IDR term in the seed: pic_offset with idr_pic_id << 5 where the flavour has none, or without it"},
        {FgcMistake::kBlockSize8, "fgc.block_size_8", "block size 8 (block size not chosen by the coded picture size)"},
        {FgcMistake::kBlockSize16, "fgc.block_size_16", "block size 16 (block size not chosen by the coded picture size)"},
        {FgcMistake::kBlockSize32, "fgc.block_size_32", "block size 32 (block size not chosen by the coded picture size)"},
        {FgcMistake::kNoDeblocking, "fgc.no_deblocking", "no deblocking of the grain's block edges"},
        {FgcMistake::kBlankBlockDeblockingToggled, "fgc.blank_block_deblocking",
         "blank-block deblocking: edges beside blocks without grain deblocked against the flavour's rule"},
        {FgcMistake::kPartialBlocksToggled, "fgc.partial_blocks_over_padding",
         "partial blocks at the picture edge averaged over padding (or only inside, against the flavour)"},
        {FgcMistake::kSemanticPersistence, "fgc.semantic_persistence",
         "persistence handled semantically: persistence_flag = 0 (H.264 repetition_period 0) ends with its picture, "
         "where the reference reuses the SEI"},
        {FgcMistake::kLog2ScaleFactorPlusOne, "fgc.log2_scale_factor_plus_1", "log2_scale_factor off by one (one too high)"},
        {FgcMistake::kLog2ScaleFactorMinusOne, "fgc.log2_scale_factor_minus_1", "log2_scale_factor off by one (one too low)"},
        {FgcMistake::kChromaIntervalsFromLuma, "fgc.chroma_intervals_from_luma",
         "chroma on sub-sampled intervals: chroma blocks take the intensity interval of the co-sited luma average"},
    };
    return list;
}

const char* fgc_mistake_id(FgcMistake mistake) {
    for (const FgcMistakeInfo& m : fgc_picture_mistakes())
        if (m.mistake == mistake) return m.id;
    return "";
}

int fgc_reference_block_size(const FgcPictureFacts& facts, int width, int height) {
    const int coded_w = facts.coded_width ? facts.coded_width : (width + 15) & ~15;
    const int coded_h = facts.coded_height ? facts.coded_height : (height + 15) & ~15;
    return fgc::default_block_size(facts.flavour, coded_w, coded_h);
}

bool fgc_mistake_applies(FgcMistake m, const FgcPictureFacts& facts, const FrameView& picture) {
    if (facts.params.film_grain_characteristics_cancel_flag) return false;
    switch (m) {
    case FgcMistake::kNone: return true;
    case FgcMistake::kFlavourRdd5:
    case FgcMistake::kFlavourVtm:
    case FgcMistake::kFlavourFfmpeg: return flavour_of(m, facts.flavour) != facts.flavour;
    case FgcMistake::kIdrTermToggled: return facts.ids.idr_pic_id != 0;
    case FgcMistake::kBlockSize8:
    case FgcMistake::kBlockSize16:
    case FgcMistake::kBlockSize32:
        return forced_block_size(m) != fgc_reference_block_size(facts, picture.width, picture.height);
    case FgcMistake::kSemanticPersistence: return facts.persisted && persistence_ends_with_picture(facts);
    case FgcMistake::kLog2ScaleFactorMinusOne: return facts.params.log2_scale_factor > 0;
    case FgcMistake::kChromaIntervalsFromLuma:
        return picture.plane_count() > 1 &&
               (facts.params.comp[1].comp_model_present_flag || facts.params.comp[2].comp_model_present_flag);
    default: return true;
    }
}

void synthesize_fgc_with_mistake(const FgcPictureFacts& facts, FgcMistake m, const FrameView& src,
                                 const FrameView& dst, int threads) {
    if (m == FgcMistake::kSemanticPersistence && fgc_mistake_applies(m, facts, src)) {
        copy_frame(src, dst);
        return;
    }
    const FgcFlavour flavour = flavour_of(m, facts.flavour);
    fgc::ResolvedFgc resolved =
        fgc::resolve_fgc_params(facts.params, flavour, fgc::PictureFormat{src.format, src.bit_depth, src.width, src.height});
    if (resolved.cancelled) {
        copy_frame(src, dst);
        return;
    }
    if (m == FgcMistake::kLog2ScaleFactorPlusOne) resolved.log2_scale_factor++;
    if (m == FgcMistake::kLog2ScaleFactorMinusOne) resolved.log2_scale_factor--;
    FgcPictureFacts as_read = facts;
    as_read.flavour = flavour;
    const int block = forced_block_size(m) ? forced_block_size(m) : fgc_reference_block_size(as_read, src.width, src.height);
    // RDD 5 and FFmpeg: pic_offset = POC + (idr_pic_id << 5); HM/VTM: the POC alone
    const bool idr_term = (flavour != FgcFlavour::kVtm) != (m == FgcMistake::kIdrTermToggled);
    const int32_t pic_offset = int32_t(uint32_t(facts.ids.poc) + (idr_term ? uint32_t(facts.ids.idr_pic_id) << 5 : 0u));
    // The scalar reference stripes: a misread scale factor leaves the range the tables of the
    // optimized path were made for.
    fgc::FgcPictureSynthesis synthesis(flavour, block, threads, fgc::Kernels::kReference);
    fgc::FgcDeviations d;
    d.no_deblocking = m == FgcMistake::kNoDeblocking;
    d.blank_block_deblocking_toggled = m == FgcMistake::kBlankBlockDeblockingToggled;
    d.partial_blocks_toggled = m == FgcMistake::kPartialBlocksToggled;
    d.chroma_interval_from_luma = m == FgcMistake::kChromaIntervalsFromLuma;
    synthesis.set_deviations(d);
    synthesis.prepare(resolved);
    synthesis.apply(resolved, src, dst, pic_offset);
}

}  // namespace filmgrain::verify

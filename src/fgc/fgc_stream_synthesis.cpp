#include "fgc/fgc_stream_synthesis.hpp"

#include "core/frame_buffer.hpp"
#include "core/plane_layout.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain {

struct FgcStreamSynthesis::Active {
    FgcParams params;
    FgcCodec codec = FgcCodec::kHevc;
    // resolution cache, valid for one picture format
    fgc::PictureFormat format{};
    std::optional<fgc::ResolvedFgc> resolved;
    ErrorCode error_code = ErrorCode::kOk;
    std::string error;
    bool have_format = false;
};

FgcStreamSynthesis::FgcStreamSynthesis(const FgcOptions& options) : options_(options) {
    if (options.flavour == FgcFlavour::kVfgs)
        throw Error(ErrorCode::kInvalidArgument, "FgcStreamSynthesis handles the rdd5, ffmpeg, vtm and tr flavours; vfgs has its own");
    if (options.block_size != 0 && options.block_size != 8 && options.block_size != 16 && options.block_size != 32)
        throw Error(ErrorCode::kInvalidArgument, "block_size = " + std::to_string(options.block_size) +
                                                     " is not allowed (allowed 0 = flavour default, 8, 16, 32)");
    const int n = options.single_line_blocks;
    if (n != 0 && n != 8 && n != 16 && n != 32)
        throw Error(ErrorCode::kInvalidArgument, "single-line blocks of " + std::to_string(n) +
                                                     "x1 are not allowed (allowed 0 = square blocks, 8, 16, 32)");
    if (n != 0 && (options.flavour == FgcFlavour::kRdd5 || options.flavour == FgcFlavour::kFfmpeg))
        throw Error(ErrorCode::kInvalidArgument,
                    "single-line blocks are an option of the vtm and tr flavours (RDD 5 fixes 8x8 blocks)");
    if (options.flavour == FgcFlavour::kFfmpeg && options.block_size != 0 && options.block_size != 8)
        throw Error(ErrorCode::kInvalidArgument, "block_size = " + std::to_string(options.block_size) +
                                                     " is not allowed by the ffmpeg flavour (allowed 0, 8: FFmpeg "
                                                     "fixes 8x8 blocks)");
    if (n != 0 && options.block_size != 0 && options.block_size != n)
        throw Error(ErrorCode::kInvalidArgument, "single-line blocks of " + std::to_string(n) + "x1 set the block size to " +
                                                     std::to_string(n) + ", not " + std::to_string(options.block_size));
}

FgcStreamSynthesis::~FgcStreamSynthesis() = default;

const FgcParams* FgcStreamSynthesis::params_in_force(FgcCodec* codec) const {
    if (!active_) return nullptr;
    if (codec) *codec = active_->codec;
    return &active_->params;
}

void FgcStreamSynthesis::receive_sei(const FgcParams& params, FgcCodec codec) {
    pending_ = params;  // copy-assignment into kept storage: no allocation for a repeated SEI
    has_pending_ = true;
    pending_codec_ = codec;
}

void FgcStreamSynthesis::reset() {
    has_pending_ = false;
    active_.reset();
}

int FgcStreamSynthesis::templates_built() const {
    return synthesis_ ? synthesis_->templates_built() : 0;
}

std::size_t FgcStreamSynthesis::scratch_bytes() const { return synthesis_ ? synthesis_->scratch_bytes() : 0; }

std::size_t FgcStreamSynthesis::working_bytes() const {
    if (!synthesis_) return 0;
    return synthesis_->scratch_bytes() + synthesis_->scaled_template_bytes() +
           std::size_t(synthesis_->templates_built()) * sizeof(fgc::GrainTemplate);
}

namespace {
// A repeated SEI (encoders commonly send the same one with every picture) keeps the
// active state, so its validation and resolution are not redone and nothing is allocated.
bool same_sei(const FgcParams& a, const FgcParams& b) {
    auto intervals_equal = [](const FgcComponentModel& x, const FgcComponentModel& y) {
        if (x.comp_model_present_flag != y.comp_model_present_flag ||
            x.num_model_values_minus1 != y.num_model_values_minus1 || x.intervals.size() != y.intervals.size())
            return false;
        for (std::size_t i = 0; i < x.intervals.size(); i++) {
            const auto &u = x.intervals[i], &v = y.intervals[i];
            if (u.intensity_interval_lower_bound != v.intensity_interval_lower_bound ||
                u.intensity_interval_upper_bound != v.intensity_interval_upper_bound ||
                u.comp_model_value != v.comp_model_value)
                return false;
        }
        return true;
    };
    for (int c = 0; c < 3; c++)
        if (!intervals_equal(a.comp[c], b.comp[c])) return false;
    return a.film_grain_characteristics_cancel_flag == b.film_grain_characteristics_cancel_flag &&
           a.film_grain_model_id == b.film_grain_model_id &&
           a.separate_colour_description_present_flag == b.separate_colour_description_present_flag &&
           a.film_grain_bit_depth_luma_minus8 == b.film_grain_bit_depth_luma_minus8 &&
           a.film_grain_bit_depth_chroma_minus8 == b.film_grain_bit_depth_chroma_minus8 &&
           a.film_grain_full_range_flag == b.film_grain_full_range_flag &&
           a.film_grain_colour_primaries == b.film_grain_colour_primaries &&
           a.film_grain_transfer_characteristics == b.film_grain_transfer_characteristics &&
           a.film_grain_matrix_coeffs == b.film_grain_matrix_coeffs && a.blending_mode_id == b.blending_mode_id &&
           a.log2_scale_factor == b.log2_scale_factor &&
           a.film_grain_characteristics_persistence_flag == b.film_grain_characteristics_persistence_flag &&
           a.film_grain_characteristics_repetition_period == b.film_grain_characteristics_repetition_period;
}

bool persists_beyond_picture(const FgcParams& p, FgcCodec codec) {
    if (codec == FgcCodec::kAvc) return p.film_grain_characteristics_repetition_period != 0;
    return p.film_grain_characteristics_persistence_flag;
}

void check_frame(const FrameView& src, const FrameView& dst) {
    if (src.width <= 0 || src.height <= 0)
        throw Error(ErrorCode::kInvalidArgument, "frame size " + std::to_string(src.width) + "x" +
                                                     std::to_string(src.height) + " is empty");
    if (src.bit_depth < 8 || src.bit_depth > 16)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("bit_depth", src.bit_depth, 8, 16));
    if (dst.width != src.width || dst.height != src.height || dst.bit_depth != src.bit_depth || dst.format != src.format)
        throw Error(ErrorCode::kInvalidArgument, "output frame does not match the input frame's size, bit depth or format");
    check_plane_layout(src, "src");
    check_plane_layout(dst, "dst");
    for (int c = 0; c < src.plane_count(); c++) {
        const int pw = plane_width(src.format, c, src.width), ph = plane_height(src.format, c, src.height);
        if (!src.planes[c].data || !dst.planes[c].data)
            throw Error(ErrorCode::kInvalidArgument, "plane " + std::to_string(c) + " has no data pointer");
        if (src.planes[c].width != pw || src.planes[c].height != ph || dst.planes[c].width != pw ||
            dst.planes[c].height != ph)
            throw Error(ErrorCode::kInvalidArgument, "plane " + std::to_string(c) + " is " +
                                                         std::to_string(src.planes[c].width) + "x" +
                                                         std::to_string(src.planes[c].height) + ", expected " +
                                                         std::to_string(pw) + "x" + std::to_string(ph));
    }
}
}  // namespace

// The SEI in force for the next picture: the one that arrived with it, else the previous
// one as far as persistence allows. Synthesis plays no part, so a stream can be followed
// over pictures that are not synthesized (skip_picture).
void FgcStreamSynthesis::advance_to_next_picture() {
    if (has_pending_ && active_ && active_->codec == pending_codec_ && same_sei(active_->params, pending_)) {
        has_pending_ = false;
    } else if (has_pending_) {
        active_ = std::make_unique<Active>();
        active_->params = pending_;
        active_->codec = pending_codec_;
        has_pending_ = false;
    } else if (active_ && options_.persistence == FgcPersistence::kSemantic &&
               !persists_beyond_picture(active_->params, active_->codec)) {
        // The SEI applied to its own picture only (H.274 persistence semantics).
        active_.reset();
    }
}

void FgcStreamSynthesis::skip_picture() { advance_to_next_picture(); }

FgcFrameResult FgcStreamSynthesis::apply(const FrameView& src, const FrameView& dst, const FgcPictureIds& ids) {
    check_frame(src, dst);
    FgcFrameResult result;
    advance_to_next_picture();
    if (!active_) {
        copy_frame(src, dst);
        return result;
    }
    result.sei_in_force = true;
    Active& a = *active_;
    fgc::PictureFormat fmt{src.format, src.bit_depth, src.width, src.height};
    if (!a.have_format || a.format.chroma != fmt.chroma || a.format.bit_depth != fmt.bit_depth ||
        a.format.width != fmt.width || a.format.height != fmt.height) {
        a.have_format = true;
        a.format = fmt;
        a.resolved.reset();
        a.error.clear();
        a.error_code = ErrorCode::kOk;
        try {
            a.resolved = fgc::resolve_fgc_params(a.params, options_.flavour, fmt);
        } catch (const Error& e) {
            a.error_code = e.code();
            a.error = e.what();
        }
    }
    if (!a.resolved) {
        if (!options_.passthrough_invalid) throw Error(a.error_code, a.error);
        copy_frame(src, dst);
        result.message = "film grain not applied: " + a.error;
        result.parameters_refused = true;
        return result;
    }
    if (a.resolved->cancelled) {
        copy_frame(src, dst);
        result.message = "film grain cancelled (film_grain_characteristics_cancel_flag = 1)";
        return result;
    }
    const int coded_w = options_.coded_width ? options_.coded_width : (src.width + 15) & ~15;
    const int coded_h = options_.coded_height ? options_.coded_height : (src.height + 15) & ~15;
    const int bs = options_.single_line_blocks ? options_.single_line_blocks
                   : options_.block_size       ? options_.block_size
                                               : fgc::default_block_size(options_.flavour, coded_w, coded_h);
    // RDD 5 pic_offset = POC + (idr_pic_id << 5), vtm the POC alone, in wrapping (unsigned)
    // arithmetic: any int32 ids are legal and only the low 8 bits reach the seed.
    uint32_t offset = uint32_t(ids.poc);
    if (options_.flavour != FgcFlavour::kVtm) offset += uint32_t(ids.idr_pic_id) << 5;
    const int32_t pic_offset = int32_t(offset);
    if (!synthesis_ || synthesis_->block_size() != bs)
        synthesis_ = std::make_unique<fgc::FgcPictureSynthesis>(
            options_.flavour, bs, options_.threads,
            options_.reference_kernels ? fgc::Kernels::kReference : fgc::Kernels::kOptimized,
            options_.single_line_blocks);
    synthesis_->apply(*a.resolved, src, dst, pic_offset);
    bool any = false;
    for (int c = 0; c < src.plane_count(); c++) any |= a.resolved->comp[c].present;
    result.grain_applied = any;
    return result;
}

}  // namespace filmgrain

// AV1 spec 7.18.3 (film grain synthesis process), stripe-driven.
#include "av1/av1_synthesis.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "av1/block_synthesis.hpp"
#include "av1/params_validation.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::av1 {

Av1SynthesisContext::Av1SynthesisContext(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width,
                                         int height, int matrix_coefficients)
    : p_(p), format_(format), bit_depth_(bit_depth), width_(width), height_(height) {
    validate_params(p, format, bit_depth);
    if (width <= 0 || height <= 0)
        throw Error(ErrorCode::kInvalidArgument,
                    "frame size " + std::to_string(width) + "x" + std::to_string(height) + " must be positive");
    subx_ = chroma_shift_x(format);
    suby_ = chroma_shift_y(format);
    clip_ = clip_limits(p.clip_to_restricted_range != 0, bit_depth, matrix_coefficients);
    if (!p.apply_grain) return;

    has_grain_[0] = p.num_y_points > 0;
    if (format != ChromaFormat::k400) {
        has_grain_[1] = p.num_cb_points > 0 || p.chroma_scaling_from_luma;
        has_grain_[2] = p.num_cr_points > 0 || p.chroma_scaling_from_luma;
    }
    // 7.18.3.3: the luma template is also the source of the chroma filters'
    // luma term, so it is built whenever any plane gets grain.
    templates_[0] = generate_luma_template(p, bit_depth);
    for (int pl = 1; pl <= 2; ++pl)
        if (has_grain_[pl]) templates_[pl] = generate_chroma_template(p, bit_depth, pl, subx_, suby_, templates_[0]);

    scaling_[0] = ScalingLookup(p.point_y_value.data(), p.point_y_scaling.data(), p.num_y_points, bit_depth);
    if (p.chroma_scaling_from_luma) {
        scaling_[1] = scaling_[2] = scaling_[0];
    } else {
        scaling_[1] = ScalingLookup(p.point_cb_value.data(), p.point_cb_scaling.data(), p.num_cb_points, bit_depth);
        scaling_[2] = ScalingLookup(p.point_cr_value.data(), p.point_cr_scaling.data(), p.num_cr_points, bit_depth);
    }
    chroma_index_[1] = {p.chroma_scaling_from_luma != 0, p.cb_mult - 128, p.cb_luma_mult - 128, p.cb_offset - 256};
    chroma_index_[2] = {p.chroma_scaling_from_luma != 0, p.cr_mult - 128, p.cr_luma_mult - 128, p.cr_offset - 256};
}

int Av1SynthesisContext::stripe_count() const { return num_stripes(height_); }

template <typename Pixel>
void Av1SynthesisContext::apply_stripe(const FrameView& src, const FrameView& dst, int stripe) const {
    const int scaling_shift = p_.grain_scaling_minus_8 + 8;
    const bool overlap = p_.overlap_flag != 0;
    const int luma_y0 = stripe * kBlockSize;
    const int luma_rows = std::min(kBlockSize, height_ - luma_y0);

    // Chroma first: it reads the clean luma of this stripe, which must not yet
    // have been overwritten when dst aliases src.
    for (int pl = 1; pl < num_planes(format_); ++pl) {
        const int pw = plane_width(format_, pl, width_);
        const int ph = plane_height(format_, pl, height_);
        const int y0 = luma_y0 >> suby_;
        const int rows = std::min((luma_rows + suby_) >> suby_, ph - y0);
        const PlaneView& s = src.planes[pl];
        const PlaneView& d = dst.planes[pl];
        if (!has_grain_[pl]) {
            if (s.data != d.data)
                for (int y = y0; y < y0 + rows; ++y)
                    std::memcpy(d.row<Pixel>(y), s.row<Pixel>(y), sizeof(Pixel) * static_cast<std::size_t>(pw));
            continue;
        }
        const StripeNoise noise =
            build_stripe_noise(templates_[pl], p_.grain_seed, stripe, width_, pw, ph, subx_, suby_, overlap, bit_depth_);
        for (int i = 0; i < rows; ++i) {
            const int y = y0 + i;
            blend_chroma_row<Pixel>(s.row<Pixel>(y), d.row<Pixel>(y), src.planes[0].row<Pixel>(y << suby_), width_,
                                    noise.row(i), pw, subx_, chroma_index_[pl], scaling_[pl], scaling_shift,
                                    bit_depth_, clip_.min_value, clip_.max_chroma);
        }
    }

    const PlaneView& s = src.planes[0];
    const PlaneView& d = dst.planes[0];
    if (!has_grain_[0]) {
        if (s.data != d.data)
            for (int y = luma_y0; y < luma_y0 + luma_rows; ++y)
                std::memcpy(d.row<Pixel>(y), s.row<Pixel>(y), sizeof(Pixel) * static_cast<std::size_t>(width_));
        return;
    }
    const StripeNoise noise =
        build_stripe_noise(templates_[0], p_.grain_seed, stripe, width_, width_, height_, 0, 0, overlap, bit_depth_);
    for (int i = 0; i < luma_rows; ++i) {
        const int y = luma_y0 + i;
        blend_luma_row<Pixel>(s.row<Pixel>(y), d.row<Pixel>(y), noise.row(i), width_, scaling_[0], scaling_shift,
                              clip_.min_value, clip_.max_luma);
    }
}

void Av1SynthesisContext::apply_stripes(const FrameView& src, const FrameView& dst, int s0, int s1) const {
    s0 = std::max(s0, 0);
    s1 = std::min(s1, stripe_count());
    for (int s = s0; s < s1; ++s) {
        if (bit_depth_ > 8)
            apply_stripe<uint16_t>(src, dst, s);
        else
            apply_stripe<uint8_t>(src, dst, s);
    }
}

void check_frame_view(const FrameView& v, const char* name) {
    const std::string n(name);
    if (v.width <= 0 || v.height <= 0)
        throw Error(ErrorCode::kInvalidArgument,
                    n + " size " + std::to_string(v.width) + "x" + std::to_string(v.height) + " must be positive");
    if (v.bit_depth < 8 || v.bit_depth > 16)
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message(n + ".bit_depth", v.bit_depth, 8, 16));
    for (int pl = 0; pl < v.plane_count(); ++pl) {
        const PlaneView& p = v.planes[pl];
        if (!p.data) throw Error(ErrorCode::kInvalidArgument, n + ".planes[" + std::to_string(pl) + "] is null");
        const int pw = plane_width(v.format, pl, v.width), ph = plane_height(v.format, pl, v.height);
        if ((p.width && p.width < pw) || (p.height && p.height < ph))
            throw Error(ErrorCode::kInvalidArgument, n + ".planes[" + std::to_string(pl) + "] is " +
                                                         std::to_string(p.width) + "x" + std::to_string(p.height) +
                                                         ", smaller than " + std::to_string(pw) + "x" +
                                                         std::to_string(ph));
        const long long row_bytes = static_cast<long long>(pw) * v.bytes_per_sample();
        if (ph > 1 && (p.stride < 0 ? -p.stride : p.stride) < row_bytes)
            throw Error(ErrorCode::kInvalidArgument, n + ".planes[" + std::to_string(pl) + "].stride = " +
                                                         std::to_string(p.stride) + " is smaller than a row (" +
                                                         std::to_string(row_bytes) + " bytes)");
    }
}

void apply_film_grain(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                      int matrix_coefficients) {
    check_frame_view(src, "src");
    check_frame_view(dst, "dst");
    if (src.format != dst.format || src.bit_depth != dst.bit_depth || src.width != dst.width ||
        src.height != dst.height)
        throw Error(ErrorCode::kInvalidArgument, "src and dst frames differ in format, bit depth or size");
    const Av1SynthesisContext ctx(p, src.format, src.bit_depth, src.width, src.height, matrix_coefficients);
    ctx.apply_stripes(src, dst, 0, ctx.stripe_count());
}

}  // namespace filmgrain::av1

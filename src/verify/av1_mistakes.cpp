#include "verify/av1_mistakes.hpp"

#include <algorithm>

#include "av1/block_synthesis.hpp"
#include "av1/grain_blending.hpp"
#include "av1/grain_template_generation.hpp"
#include "av1/random_number.hpp"
#include "av1/scaling_lookup.hpp"
#include "core/frame_buffer.hpp"

namespace filmgrain::verify {
namespace {

using av1::GrainTemplate;

bool chroma_has_grain(const Av1FilmGrainParams& p, int plane) {
    return (plane == 1 ? p.num_cb_points : p.num_cr_points) > 0 || p.chroma_scaling_from_luma;
}

// The parameter set as the mistaken decoder reads it (the mistakes that are misreadings).
Av1FilmGrainParams misread_params(Av1FilmGrainParams p, Av1Mistake m) {
    switch (m) {
    case Av1Mistake::kNoOverlap: p.overlap_flag = 0; break;
    case Av1Mistake::kClipToRestrictedRangeToggled: p.clip_to_restricted_range ^= 1; break;
    case Av1Mistake::kChromaScalingFromLumaToggled: p.chroma_scaling_from_luma ^= 1; break;
    case Av1Mistake::kArCoeffShiftPlusOne: p.ar_coeff_shift_minus_6++; break;
    case Av1Mistake::kArCoeffShiftMinusOne: p.ar_coeff_shift_minus_6--; break;
    default: break;
    }
    return p;
}

// The Cb / Cr template with its seed as the mistake derives it. generate_chroma_template
// XORs the plane's constant (7.18.3.3) itself, so the seed handed to it is pre-XORed.
void chroma_template(const Av1FilmGrainParams& p, Av1Mistake m, int bit_depth, int plane, int sx, int sy,
                     const GrainTemplate& luma, GrainTemplate& out) {
    Av1FilmGrainParams q = p;
    const int own = plane == 1 ? 0xb524 : 0x49d8;
    const int other = plane == 1 ? 0x49d8 : 0xb524;
    if (m == Av1Mistake::kChromaSeedsNotPerPlane) q.grain_seed = p.grain_seed ^ own;
    if (m == Av1Mistake::kChromaSeedsSwapped) q.grain_seed = p.grain_seed ^ own ^ other;
    av1::generate_chroma_template(q, bit_depth, plane, sx, sy, luma, out);
}

// Windows taken from the template's corner: the sample a window at (ty, tx) reads is the one
// the reference reads at (ty - margin_y, tx - margin_x), margins 9 (full resolution) / 6.
GrainTemplate uncentred(const GrainTemplate& t, int sx, int sy) {
    const int my = sy ? 6 : 9, mx = sx ? 6 : 9;
    GrainTemplate out = t;
    for (int y = 0; y < t.height; y++)
        for (int x = 0; x < t.width; x++)
            out.ref(y, x) = int16_t(y >= my && x >= mx ? t.at(y - my, x - mx) : 0);
    return out;
}

std::vector<uint8_t> block_offsets(int seed, int stripe, int blocks, bool swapped) {
    std::vector<uint8_t> o = av1::stripe_block_offsets(seed, stripe, blocks);
    if (swapped)
        for (uint8_t& b : o) b = uint8_t((b >> 4) | (b << 4));
    return o;
}

// The plane's noise for one stripe (7.18.3.5) from the block offsets the mistake draws.
av1::StripeNoise stripe_noise(const GrainTemplate& t, const Av1FilmGrainParams& p, Av1Mistake m, int stripe,
                              int luma_width, int pw, int ph, int sx, int sy, int bit_depth) {
    const int blocks = av1::num_blocks_across(luma_width);
    const bool overlap = p.overlap_flag != 0, swapped = m == Av1Mistake::kBlockOffsetsSwapped;
    return av1::build_stripe_noise(
        t, block_offsets(p.grain_seed, stripe, blocks, swapped),
        overlap && stripe > 0 ? block_offsets(p.grain_seed, stripe - 1, blocks, swapped) : std::vector<uint8_t>{},
        stripe, pw, ph, sx, sy, overlap, bit_depth);
}

template <typename Pixel>
struct PlaneBlend {
    const Av1FilmGrainParams& p;
    Av1Mistake m;
    int bit_depth;     // the picture's
    int grain_depth;   // the depth the grain was made at (8 for kHighBitDepthAs8Bit)
    av1::ClipLimits clip;

    int scaled_noise(int scale, int grain) const {
        const int shift = p.grain_scaling_minus_8 + 8;
        const int n = m == Av1Mistake::kScalingShiftTruncated ? (scale * grain) >> shift
                                                              : av1::round2_signed(scale * grain, shift);
        return n * (1 << (bit_depth - grain_depth));
    }
    int down(int v) const { return v >> (bit_depth - grain_depth); }

    void luma_row(const Pixel* src, Pixel* dst, const int16_t* noise, int width, const av1::ScalingLookup& s) const {
        for (int x = 0; x < width; x++)
            dst[x] = Pixel(std::clamp(src[x] + scaled_noise(s(down(src[x])), noise[x]), clip.min_value, clip.max_luma));
    }

    void chroma_row(const Pixel* src, Pixel* dst, const Pixel* luma, int luma_width, const int16_t* noise, int width,
                    int sx, int plane, const av1::ScalingLookup& s) const {
        const bool from_luma = p.chroma_scaling_from_luma != 0;
        const int mult = (plane == 1 ? p.cb_mult : p.cr_mult) - 128;
        const int luma_mult = (plane == 1 ? p.cb_luma_mult : p.cr_luma_mult) - 128;
        const int offset = (plane == 1 ? p.cb_offset : p.cr_offset) - 256;
        const int round = m == Av1Mistake::kLumaAverageTruncated ? 0 : 1;
        for (int x = 0; x < width; x++) {
            const int average = sx ? (luma[2 * x] + luma[std::min(2 * x + 1, luma_width - 1)] + round) >> 1 : luma[x];
            const int a = down(average), orig = down(src[x]);
            int merged = a;
            if (!from_luma)
                merged = std::clamp(((a * luma_mult + orig * mult) >> 6) + offset * (1 << (grain_depth - 8)), 0,
                                    (1 << grain_depth) - 1);
            dst[x] = Pixel(std::clamp(src[x] + scaled_noise(s(merged), noise[x]), clip.min_value, clip.max_chroma));
        }
    }
};

template <typename Pixel>
void synthesize(const Av1FilmGrainParams& real, Av1Mistake m, const FrameView& src, const FrameView& dst, int mc) {
    const Av1FilmGrainParams p = misread_params(real, m);
    const int bd = src.bit_depth;
    const int gd = m == Av1Mistake::kHighBitDepthAs8Bit ? 8 : bd;
    const int sx = chroma_shift_x(src.format), sy = chroma_shift_y(src.format);
    const int planes = src.plane_count();
    GrainTemplate templates[3];
    av1::generate_luma_template(p, gd, templates[0]);
    for (int pl = 1; pl < planes; pl++) chroma_template(p, m, gd, pl, sx, sy, templates[0], templates[pl]);
    if (m == Av1Mistake::kTemplateNotCentred)
        for (int pl = 0; pl < planes; pl++) templates[pl] = uncentred(templates[pl], pl ? sx : 0, pl ? sy : 0);
    const av1::ScalingLookup luma_scaling(p.point_y_value.data(), p.point_y_scaling.data(), p.num_y_points, gd);
    const av1::ScalingLookup cb_scaling(p.point_cb_value.data(), p.point_cb_scaling.data(), p.num_cb_points, gd);
    const av1::ScalingLookup cr_scaling(p.point_cr_value.data(), p.point_cr_scaling.data(), p.num_cr_points, gd);
    const av1::ScalingLookup* scaling[3] = {&luma_scaling, p.chroma_scaling_from_luma ? &luma_scaling : &cb_scaling,
                                            p.chroma_scaling_from_luma ? &luma_scaling : &cr_scaling};
    const PlaneBlend<Pixel> blend{p, m, bd, gd, av1::clip_limits(p.clip_to_restricted_range != 0, bd, mc)};
    for (int pl = 0; pl < planes; pl++) {
        const bool grain = pl ? chroma_has_grain(p, pl) : p.num_y_points > 0;
        const PlaneView& s = src.planes[pl];
        const PlaneView& d = dst.planes[pl];
        if (!grain || !p.apply_grain) {
            for (int y = 0; y < s.height; y++) std::copy_n(s.row<const Pixel>(y), s.width, d.row<Pixel>(y));
            continue;
        }
        const int psx = pl ? sx : 0, psy = pl ? sy : 0;
        for (int stripe = 0; stripe < av1::num_stripes(src.height); stripe++) {
            const av1::StripeNoise noise = stripe_noise(templates[pl], p, m, stripe, src.width, s.width, s.height, psx,
                                                        psy, gd);
            for (int i = 0; i < noise.rows; i++) {
                const int y = stripe * (av1::kBlockSize >> psy) + i;
                if (pl == 0)
                    blend.luma_row(s.row<const Pixel>(y), d.row<Pixel>(y), noise.row(i), s.width, *scaling[0]);
                else
                    blend.chroma_row(s.row<const Pixel>(y), d.row<Pixel>(y), src.planes[0].row<const Pixel>(y << sy),
                                     src.width, noise.row(i), s.width, sx, pl, *scaling[pl]);
            }
        }
    }
}

}  // namespace

const std::vector<Av1MistakeInfo>& av1_picture_mistakes() {
    static const std::vector<Av1MistakeInfo> list = {
        {Av1Mistake::kNoOverlap, "av1.no_overlap", "overlap_flag ignored: 32x32 blocks without the overlap cross-fade"},
        {Av1Mistake::kChromaSeedsNotPerPlane, "av1.chroma_seed_not_per_plane",
         "random_seed not updated per plane: Cb/Cr templates seeded without the XOR 0xb524 / 0x49d8"},
        {Av1Mistake::kChromaSeedsSwapped, "av1.chroma_seeds_swapped", "Cb and Cr template seeds swapped"},
        {Av1Mistake::kBlockOffsetsSwapped, "av1.block_offsets_swapped",
         "block offsets swapped: horizontal offset from the low nibble, vertical from the high"},
        {Av1Mistake::kClipToRestrictedRangeToggled, "av1.clip_to_restricted_range",
         "clip_to_restricted_range ignored (or applied when 0)"},
        {Av1Mistake::kChromaScalingFromLumaToggled, "av1.chroma_scaling_from_luma",
         "chroma_scaling_from_luma taken the wrong way (off when on, on when off)"},
        {Av1Mistake::kArCoeffShiftPlusOne, "av1.ar_coeff_shift_plus_1", "ar_coeff_shift off by one (one too high)"},
        {Av1Mistake::kArCoeffShiftMinusOne, "av1.ar_coeff_shift_minus_1", "ar_coeff_shift off by one (one too low)"},
        {Av1Mistake::kScalingShiftTruncated, "av1.scaling_shift_not_rounded",
         "no rounding in the scaling shift: (scaling * grain) >> shift instead of Round2"},
        {Av1Mistake::kTemplateNotCentred, "av1.template_not_centred",
         "grain template not centred: block windows taken without the 9 (luma) / 6 (chroma) sample margin"},
        {Av1Mistake::kLumaAverageTruncated, "av1.luma_average_not_rounded",
         "co-sited luma average of subsampled chroma without rounding: (a + b) >> 1"},
        {Av1Mistake::kHighBitDepthAs8Bit, "av1.high_bit_depth_as_8bit",
         "high bit depth treated as 8-bit: grain made at 8 bits on the samples shifted down, then shifted up"},
    };
    return list;
}

bool av1_mistake_applies(Av1Mistake m, const Av1FilmGrainParams& p, const FrameView& picture) {
    const bool chroma = picture.plane_count() > 1 && (chroma_has_grain(p, 1) || chroma_has_grain(p, 2));
    if (!p.apply_grain) return false;
    switch (m) {
    case Av1Mistake::kNone: return true;
    case Av1Mistake::kNoOverlap: return p.overlap_flag != 0;
    case Av1Mistake::kChromaSeedsNotPerPlane:
    case Av1Mistake::kChromaSeedsSwapped: return chroma;
    case Av1Mistake::kChromaScalingFromLumaToggled: return picture.plane_count() > 1;
    case Av1Mistake::kArCoeffShiftPlusOne: return p.ar_coeff_shift_minus_6 < 3 && p.ar_coeff_lag > 0;
    case Av1Mistake::kArCoeffShiftMinusOne: return p.ar_coeff_shift_minus_6 > 0 && p.ar_coeff_lag > 0;
    case Av1Mistake::kLumaAverageTruncated: return chroma && chroma_shift_x(picture.format) != 0;
    case Av1Mistake::kHighBitDepthAs8Bit: return picture.bit_depth > 8;
    default: return p.num_y_points > 0 || chroma;
    }
}

void synthesize_av1_with_mistake(const Av1FilmGrainParams& p, Av1Mistake mistake, const FrameView& src,
                                 const FrameView& dst, int matrix_coefficients) {
    if (src.bit_depth > 8)
        synthesize<uint16_t>(p, mistake, src, dst, matrix_coefficients);
    else
        synthesize<uint8_t>(p, mistake, src, dst, matrix_coefficients);
}

}  // namespace filmgrain::verify

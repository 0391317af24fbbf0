// AV1 spec 7.18.3 (film grain synthesis process), stripe-driven.
#include "av1/av1_picture_synthesis.hpp"


#include <algorithm>
#include <cstring>
#include <string>

#include "av1/block_synthesis.hpp"
#include "av1/grain_template_optimized.hpp"
#include "av1/stripe_block_origins.hpp"
#include "core/plane_layout.hpp"
#include "av1/params_validation.hpp"
#include "av1/simd/av1_kernels.hpp"
#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::av1 {

namespace {
// A plane (or stripe) that gets no grain is only copied, and only when not in place.
template <typename Pixel>
void copy_rows_without_grain(const PlaneView& s, const PlaneView& d, int y0, int rows, int width) {
    if (s.data == d.data) return;
    for (int y = y0; y < y0 + rows; ++y)
        std::memcpy(d.row<Pixel>(y), s.row<Pixel>(y), sizeof(Pixel) * static_cast<std::size_t>(width));
}

// Rows [y, y + count) of source plane s and output plane d for the u16 row kernels, the noise
// `step` down a row, each prefetching the source row `ahead` rows below it
// (simd::kSourcePrefetchRows) where that lies in the plane (`plane_rows`: a view's own height
// may be left 0).
simd::PlaneRows rows_ahead(const PlaneView& s, const PlaneView& d, int y, int count, std::ptrdiff_t step, int ahead,
                           int plane_rows) {
    simd::PlaneRows rows{count, s.stride, d.stride, 0, step};
    if (y + ahead < plane_rows) {
        rows.ahead = s.row<const uint16_t>(y + ahead);
        rows.ahead_count = std::min(count, plane_rows - (y + ahead));
    }
    return rows;
}
}  // namespace


Av1SynthesisContext::Av1SynthesisContext(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width,
                                         int height, int matrix_coefficients, Kernels templates) {
    reset(p, format, bit_depth, width, height, matrix_coefficients, templates);
}

void Av1SynthesisContext::reset(const Av1FilmGrainParams& p, ChromaFormat format, int bit_depth, int width,
                                int height, int matrix_coefficients, Kernels templates) {
    validate_params(p, format, bit_depth);
    if (width <= 0 || height <= 0)
        throw Error(ErrorCode::kInvalidArgument,
                    "frame size " + std::to_string(width) + "x" + std::to_string(height) + " must be positive");
    p_ = p;
    format_ = format;
    bit_depth_ = bit_depth;
    width_ = width;
    height_ = height;
    has_grain_[0] = has_grain_[1] = has_grain_[2] = false;
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
    // luma term, so it is built whenever any plane gets grain. Built in place, so a
    // context reset for the next frame reuses its storage.
    if (templates == Kernels::kOptimized) {
        generate_luma_template_optimized(p, bit_depth, templates_[0]);
        if (has_grain_[1] || has_grain_[2])
            generate_chroma_templates_optimized(p, bit_depth, subx_, suby_, templates_[0], templates_[1],
                                                templates_[2]);
    } else {
        generate_luma_template(p, bit_depth, templates_[0]);
        for (int pl = 1; pl <= 2; ++pl)
            if (has_grain_[pl]) generate_chroma_template(p, bit_depth, pl, subx_, suby_, templates_[0], templates_[pl]);
    }

    luma_template_bytes_.clear();
    if (bit_depth == 8 && has_grain_[0] && simd::luma_rows_read_byte_noise())
        simd::copy_noise_as_bytes(templates_[0].samples, luma_template_bytes_);

    scaling_[0].assign(p.point_y_value.data(), p.point_y_scaling.data(), p.num_y_points, bit_depth);
    if (p.chroma_scaling_from_luma) {
        scaling_[1] = scaling_[2] = scaling_[0];
    } else {
        scaling_[1].assign(p.point_cb_value.data(), p.point_cb_scaling.data(), p.num_cb_points, bit_depth);
        scaling_[2].assign(p.point_cr_value.data(), p.point_cr_scaling.data(), p.num_cr_points, bit_depth);
    }
    chroma_index_[1] = {p.chroma_scaling_from_luma != 0, p.cb_mult - 128, p.cb_luma_mult - 128, p.cb_offset - 256};
    chroma_index_[2] = {p.chroma_scaling_from_luma != 0, p.cr_mult - 128, p.cr_luma_mult - 128, p.cr_offset - 256};
}

void StripeScratch::reserve(int luma_width, std::size_t co_sited_bytes) {
    const std::size_t pitch = std::size_t(noise_stripe_width(luma_width, 0));
    const std::size_t blocks = std::size_t(num_blocks_across(luma_width));
    if (noise.size() < pitch * 2) noise.resize(pitch * 2);
    if (previous.size() < pitch * 2) previous.resize(pitch * 2);
    if (origins.size() < blocks) origins.resize(blocks);
    if (previous_origins.size() < blocks) previous_origins.resize(blocks);
    if (block_rows.size() < blocks) block_rows.resize(blocks);
    if (previous_block_rows.size() < blocks) previous_block_rows.resize(blocks);
    if (byte_block_rows.size() < blocks) byte_block_rows.resize(blocks);
    if (shared_rows.size() < blocks) shared_rows.resize(blocks);
    if (seams.size() < blocks) seams.resize(blocks);
    for (DrawnOffsets& d : drawn_)
        if (d.bytes.size() < blocks) d.bytes.resize(blocks);
    const std::size_t co_sited = (co_sited_bytes + 1) / 2;
    if (co_sited_luma.size() < co_sited) co_sited_luma.resize(co_sited);
}

const uint8_t* StripeScratch::block_offsets(int grain_seed, int stripe, int blocks) {
    DrawnOffsets& d = drawn_[stripe & 1];
    if (d.grain_seed != grain_seed || d.stripe != stripe || d.blocks != blocks) {
        // (reserve() sized it for the frame's width; this only guards a call without it)
        if (d.bytes.size() < std::size_t(blocks)) d.bytes.resize(std::size_t(blocks));
        fill_stripe_block_offsets(grain_seed, stripe, blocks, d.bytes.data());
        d.grain_seed = grain_seed, d.stripe = stripe, d.blocks = blocks;
    }
    return d.bytes.data();
}

std::size_t StripeScratch::bytes() const {
    return (noise.capacity() + previous.capacity()) * sizeof(int16_t) +
           (origins.capacity() + previous_origins.capacity()) * sizeof(int32_t) +
           (block_rows.capacity() + previous_block_rows.capacity() + shared_rows.capacity()) * sizeof(const int16_t*) +
           byte_block_rows.capacity() * sizeof(const int8_t*) +
           seams.capacity() * sizeof(uint32_t) + co_sited_luma.capacity() * sizeof(uint16_t) +
           drawn_[0].bytes.capacity() + drawn_[1].bytes.capacity();
}

int Av1SynthesisContext::stripe_count() const { return num_stripes(height_); }

std::size_t Av1SynthesisContext::co_sited_bytes() const {
    if (!subx_ || num_planes(format_) < 2 || bit_depth_ <= 8) return 0;
    return std::size_t(kBlockSize >> suby_) * std::size_t(plane_width(format_, 1, width_)) * sizeof(uint16_t);
}

template <typename Pixel, typename Blend>
void Av1SynthesisContext::for_each_stripe_plane(const FrameView& src, const FrameView& dst, int stripe,
                                                Blend&& blend, bool luma_first) const {
    const int luma_y0 = stripe * kBlockSize;
    const int luma_rows = std::min(kBlockSize, height_ - luma_y0);
    // Chroma first: it reads the clean luma of this stripe, which must not yet have been
    // overwritten when dst aliases src (unless `blend` keeps what chroma needs of it before
    // overwriting it, and asks for luma first).
    const int planes = num_planes(format_);
    for (int n = 1; n <= planes; ++n) {
        const int pl = luma_first ? n - 1 : n % planes;  // 1, 2, then 0 (or 0, 1, 2)
        const int sy = pl ? suby_ : 0;
        const int pw = plane_width(format_, pl, width_);
        const int ph = plane_height(format_, pl, height_);
        const int y0 = luma_y0 >> sy;
        const int rows = std::min((luma_rows + sy) >> sy, ph - y0);
        if (!has_grain_[pl])
            copy_rows_without_grain<Pixel>(src.planes[pl], dst.planes[pl], y0, rows, pw);
        else if (rows > 0)
            blend(pl, y0, rows, pw, ph);
    }
}

template <typename Pixel>
void Av1SynthesisContext::apply_stripe(const FrameView& src, const FrameView& dst, int stripe) const {
    const int scaling_shift = p_.grain_scaling_minus_8 + 8;
    const bool overlap = p_.overlap_flag != 0;
    for_each_stripe_plane<Pixel>(src, dst, stripe, [&](int pl, int y0, int rows, int pw, int ph) {
        const PlaneView& s = src.planes[pl];
        const PlaneView& d = dst.planes[pl];
        const int sx = pl ? subx_ : 0, sy = pl ? suby_ : 0;
        const StripeNoise noise =
            build_stripe_noise(templates_[pl], p_.grain_seed, stripe, width_, pw, ph, sx, sy, overlap, bit_depth_);
        for (int i = 0; i < rows; ++i) {
            const int y = y0 + i;
            if (pl)
                blend_chroma_row<Pixel>(s.row<Pixel>(y), d.row<Pixel>(y), src.planes[0].row<Pixel>(y << suby_),
                                        width_, noise.row(i), pw, subx_, chroma_index_[pl], scaling_[pl],
                                        scaling_shift, bit_depth_, clip_.min_value, clip_.max_chroma);
            else
                blend_luma_row<Pixel>(s.row<Pixel>(y), d.row<Pixel>(y), noise.row(i), width_, scaling_[0],
                                      scaling_shift, clip_.min_value, clip_.max_luma);
        }
    });
}

template <typename Pixel>
void Av1SynthesisContext::apply_stripe_optimized(const FrameView& src, const FrameView& dst, int stripe,
                                                 StripeScratch& scratch) const {
    const int scaling_shift = p_.grain_scaling_minus_8 + 8;
    const bool overlap = p_.overlap_flag != 0;
    const GrainRange range = grain_range(bit_depth_);
    const int blocks = num_blocks_across(width_);
    scratch.reserve(width_, co_sited_bytes());
    const std::size_t pitch = std::size_t(noise_stripe_width(width_, 0));

    // Each row's noise is read straight from the template at every block's offset; only the
    // rows a stripe shares with the one above (overlap_flag: two, one when subsampled
    // vertically) are built in scratch.noise, cross-faded with the previous stripe's bottom
    // rows as build_stripe_noise does.
    // blend_rows(i, count, noise, step) blends rows [i, i + count) of the plane's stripe, row
    // i + k with `noise` moved `k * step` samples down the template (PlaneRows).
    auto blend_plane = [&](int pl, int sx, int sy, int rows, auto&& blend_rows) {
        const GrainTemplate& tmpl = templates_[pl];
        const int block_w = kBlockSize >> sx;
        const int pw = plane_width(format_, pl, width_);
        const int shared_rows = overlap && stripe > 0 ? std::min(rows, 2 >> sy) : 0;
        // The horizontal overlap is faded inside the kernels where 16-bit lanes hold it, else
        // precomputed per row (12 bits).
        const bool fade_in_kernel = overlap && bit_depth_ <= 10;
        simd::BlockNoiseRow row = kernel_faded_row(sx, bit_depth_);
        row.fade = false;
        // Where the seams are precomputed (12 bits with overlap), overlap_seams reads every row
        // through its own pointers; elsewhere `pointers` point at the blocks' first rows, set
        // once per stripe by first_rows(), and a row only moves row_offset.
        const bool row_pointers = overlap && !fade_in_kernel;
        auto first_rows = [&](const int32_t* origins, const int16_t** pointers) {
            for (int b = 0; b < blocks; ++b) pointers[b] = tmpl.samples.data() + origins[b];
        };
        // Row `i` of the blocks at `origins`, as it reads the template, through `pointers`.
        auto template_row = [&](const int32_t* origins, int i, const int16_t** pointers) {
            simd::BlockNoiseRow r = row;
            r.blocks = pointers;
            r.fade = fade_in_kernel;
            if (!row_pointers) {
                r.row_offset = std::ptrdiff_t(i) * tmpl.width;
                return r;
            }
            const int16_t* t = tmpl.samples.data() + std::ptrdiff_t(i) * tmpl.width;
            for (int b = 0; b < blocks; ++b) pointers[b] = t + origins[b];
            overlap_seams(pointers, blocks, sx, bit_depth_, scratch.seams.data());
            r.seams = scratch.seams.data();
            return r;
        };
        // The previous stripe's blocks continue below it for the vertical overlap.
        if (shared_rows) {
            stripe_block_origins(tmpl, scratch.block_offsets(p_.grain_seed, stripe - 1, blocks), blocks, sx, sy,
                                 scratch.previous_origins.data());
            if (!row_pointers) first_rows(scratch.previous_origins.data(), scratch.previous_block_rows.data());
            for (int b = 0; b < blocks; ++b) scratch.shared_rows[std::size_t(b)] = scratch.noise.data() + b * block_w;
        }
        stripe_block_origins(tmpl, scratch.block_offsets(p_.grain_seed, stripe, blocks), blocks, sx, sy,
                             scratch.origins.data());
        if (!row_pointers) first_rows(scratch.origins.data(), scratch.block_rows.data());
        // 8-bit luma rows read from the template also have its int8 copy (the rows shared with
        // the stripe above, faded in scratch.noise, have none)
        const bool byte_noise = pl == 0 && !luma_template_bytes_.empty();
        if (byte_noise)
            for (int b = 0; b < blocks; ++b)
                scratch.byte_block_rows[std::size_t(b)] = luma_template_bytes_.data() + scratch.origins[std::size_t(b)];
        const int stripe_h = kBlockSize >> sy;
        for (int i = 0; i < shared_rows; ++i) {
            int16_t* cur = scratch.noise.data() + pitch * std::size_t(i);
            const OverlapWeights w = overlap_weights(i, sy);
            if (fade_in_kernel) {
                simd::assemble_cross_faded_row(
                    template_row(scratch.previous_origins.data(), stripe_h + i, scratch.previous_block_rows.data()),
                    template_row(scratch.origins.data(), i, scratch.block_rows.data()), pw, w.old_weight,
                    w.new_weight, cur);
                continue;
            }
            // 12 bits: the rows one after the other (they share scratch.seams), faded in 32-bit lanes.
            int16_t* above = scratch.previous.data() + pitch * std::size_t(i);
            simd::assemble_noise_row(
                template_row(scratch.previous_origins.data(), stripe_h + i, scratch.previous_block_rows.data()), pw,
                above);
            simd::assemble_noise_row(template_row(scratch.origins.data(), i, scratch.block_rows.data()), pw, cur);
            simd::cross_fade_row(above, cur, pw, w.old_weight, w.new_weight, range.min, range.max);
        }
        for (int i = 0; i < shared_rows; ++i) {
            // The faded row, contiguous: no overlap left to apply.
            simd::BlockNoiseRow r = row;
            r.blocks = scratch.shared_rows.data();
            r.row_offset = std::ptrdiff_t(pitch) * i;
            blend_rows(i, 1, r, 0);
        }
        // The others read the template, one template row further down per row: all in one call
        // (the kernels' constants made once), unless every row needs its own pointers.
        if (row_pointers)
            for (int i = shared_rows; i < rows; ++i)
                blend_rows(i, 1, template_row(scratch.origins.data(), i, scratch.block_rows.data()), 0);
        else if (rows > shared_rows) {
            simd::BlockNoiseRow r = template_row(scratch.origins.data(), shared_rows, scratch.block_rows.data());
            if (byte_noise) r.byte_blocks = scratch.byte_block_rows.data();
            blend_rows(shared_rows, rows - shared_rows, r, tmpl.width);
        }
    };

    // Subsampled horizontally above 8 bits, both chroma planes scale by the same luma averages
    // (co_sited_luma_row): made once per stripe into scratch, and read by the chroma kernels
    // as unsubsampled luma. The luma kernel makes them from each clean luma row as it loads
    // it to blend (in place, before it is overwritten), so the row is read once and the
    // look-up's work hides the picture's memory; chroma then comes after luma. (At 8 bits,
    // where the chroma kernels average a pair in three operations per vector, sharing measured
    // no faster, so 8 bits average in the kernels; they take luma first only out of place.)
    const bool share_co_sited = co_sited_bytes() != 0;
    const int chroma_width = plane_width(format_, 1, width_);
    Pixel* co_sited = reinterpret_cast<Pixel*>(scratch.co_sited_luma.data());  // sized by reserve()
    auto make_co_sited_row = [&](int luma_y, int chroma_row) {
        if constexpr (sizeof(Pixel) > 1)
            simd::co_sited_luma_row_u16(src.planes[0].row<Pixel>(luma_y), width_, chroma_width,
                                        co_sited + std::ptrdiff_t(chroma_row) * chroma_width);
    };
    bool co_sited_made = false;
    for_each_stripe_plane<Pixel>(src, dst, stripe, [&](int pl, int y0, int rows, int pw, int) {
        const PlaneView& s = src.planes[pl];
        const PlaneView& d = dst.planes[pl];
        if (pl == 0) {
            blend_plane(0, 0, 0, rows, [&](int i0, int count, const simd::BlockNoiseRow& nz, std::ptrdiff_t step) {
                if constexpr (sizeof(Pixel) == 1) {
                    const simd::PlaneRows in_rows{count, s.stride, d.stride, 0, step};
                    simd::blend_luma_rows_u8(s.row<Pixel>(y0 + i0), d.row<Pixel>(y0 + i0), in_rows, nz, width_,
                                             scaling_[0], scaling_shift, clip_.min_value, clip_.max_luma);
                } else {
                    simd::CoSitedRows shared;
                    if (share_co_sited) shared = {co_sited, chroma_width, suby_, i0};
                    simd::blend_luma_rows_u16(s.row<Pixel>(y0 + i0), d.row<Pixel>(y0 + i0),
                                              rows_ahead(s, d, y0 + i0, count, step, simd::kSourcePrefetchRows, height_),
                                              nz, width_, scaling_[0], scaling_shift, bit_depth_, clip_.min_value,
                                              clip_.max_luma, shared);
                }
            });
            co_sited_made = share_co_sited;
            return;
        }
        if (share_co_sited && !co_sited_made) {  // luma without grain: no luma pass made them
            for (int i = 0; i < rows; ++i) make_co_sited_row((y0 + i) << suby_, i);
            co_sited_made = true;
        }
        blend_plane(pl, subx_, suby_, rows, [&](int i0, int count, const simd::BlockNoiseRow& nz, std::ptrdiff_t step) {
            if constexpr (sizeof(Pixel) == 1) {  // (no shared co-sited rows at 8 bits)
                const simd::PlaneRows in_rows{count, s.stride, d.stride, src.planes[0].stride << suby_, step};
                simd::blend_chroma_rows_u8(s.row<Pixel>(y0 + i0), d.row<Pixel>(y0 + i0),
                                           src.planes[0].row<Pixel>((y0 + i0) << suby_), width_, in_rows, nz, pw,
                                           subx_, chroma_index_[pl], scaling_[pl], scaling_shift, bit_depth_,
                                           clip_.min_value, clip_.max_chroma);
            } else {
                const int y = y0 + i0;
                simd::PlaneRows in_rows = rows_ahead(s, d, y, count, step, simd::kSourcePrefetchRows >> suby_,
                                                     plane_height(format_, pl, height_));
                // the shared co-sited rows are unsubsampled luma of the chroma width
                in_rows.luma_stride = share_co_sited ? std::ptrdiff_t(sizeof(Pixel)) * pw : src.planes[0].stride << suby_;
                const Pixel* luma =
                    share_co_sited ? co_sited + std::ptrdiff_t(i0) * pw : src.planes[0].row<Pixel>(y << suby_);
                simd::blend_chroma_rows_u16(s.row<Pixel>(y), d.row<Pixel>(y), luma, share_co_sited ? pw : width_,
                                            in_rows, nz, pw, share_co_sited ? 0 : subx_, chroma_index_[pl],
                                            scaling_[pl], scaling_shift, bit_depth_, clip_.min_value,
                                            clip_.max_chroma);
            }
        });
    // Luma first where that is safe (out of place, or the co-sited rows made before luma is
    // overwritten): the chroma rows then read their luma while the luma pass has it in cache,
    // instead of fetching it for chroma and again for luma (8-bit 1080p in one process: the
    // per-frame cost fell by about 5 %).
    }, share_co_sited || src.planes[0].data != dst.planes[0].data);
}

void Av1SynthesisContext::apply_stripes(const FrameView& src, const FrameView& dst, int s0, int s1, Kernels kernels,
                                        StripeScratch& scratch) const {
    if (kernels == Kernels::kReference) return apply_stripes(src, dst, s0, s1);
    s0 = std::max(s0, 0);
    s1 = std::min(s1, stripe_count());
    for (int s = s0; s < s1; ++s) {
        if (bit_depth_ > 8)
            apply_stripe_optimized<uint16_t>(src, dst, s, scratch);
        else
            apply_stripe_optimized<uint8_t>(src, dst, s, scratch);
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
    }
    // strides (at least a row, within PTRDIFF_MAX, no negation of PTRDIFF_MIN) and 16-bit alignment
    check_plane_layout(v, n);
}

namespace {
void check_frame_pair(const FrameView& src, const FrameView& dst) {
    check_frame_view(src, "src");
    check_frame_view(dst, "dst");
    if (src.format != dst.format || src.bit_depth != dst.bit_depth || src.width != dst.width ||
        src.height != dst.height)
        throw Error(ErrorCode::kInvalidArgument, "src and dst frames differ in format, bit depth or size");
}
}  // namespace

void apply_film_grain(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                      int matrix_coefficients) {
    check_frame_pair(src, dst);
    const Av1SynthesisContext ctx(p, src.format, src.bit_depth, src.width, src.height, matrix_coefficients);
    ctx.apply_stripes(src, dst, 0, ctx.stripe_count());
}

Av1PictureSynthesis::Av1PictureSynthesis(int threads, Kernels kernels)
    : kernels_(kernels), pool_(std::make_unique<ThreadPool>(threads)), scratch_(std::size_t(pool_->size())) {}

Av1PictureSynthesis::~Av1PictureSynthesis() = default;

int Av1PictureSynthesis::threads() const { return pool_->size(); }

std::size_t Av1PictureSynthesis::working_bytes() const {
    std::size_t n = 0;
    for (const auto& s : scratch_) n += s.bytes();
    if (context_) n += context_->table_bytes();
    return n;
}

std::size_t Av1SynthesisContext::table_bytes() const {
    std::size_t n = 0;
    for (int pl = 0; pl < 3; ++pl)
        n += templates_[pl].samples.capacity() * sizeof(int16_t) +
             scaling_[pl].table8().capacity() + (std::size_t(1) << bit_depth_) + 3 * 256;
    return n + luma_template_bytes_.capacity();
}

void Av1PictureSynthesis::apply(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                           int matrix_coefficients) {
    check_frame_pair(src, dst);
    if (!context_)
        context_ = std::make_unique<Av1SynthesisContext>(p, src.format, src.bit_depth, src.width, src.height,
                                                         matrix_coefficients, kernels_);
    else
        context_->reset(p, src.format, src.bit_depth, src.width, src.height, matrix_coefficients, kernels_);
    const Av1SynthesisContext& ctx = *context_;
    // Every worker's scratch is sized here, on the calling thread, so that a worker that
    // happened to get no stripe in the first frames cannot allocate later.
    if (kernels_ == Kernels::kOptimized)
        for (auto& s : scratch_) s.reserve(src.width, ctx.co_sited_bytes());
    pool_->parallel_for(ctx.stripe_count(), [&](int stripe, int worker) {
        ctx.apply_stripes(src, dst, stripe, stripe + 1, kernels_, scratch_[std::size_t(worker)]);
    });
}

void apply_film_grain(const Av1FilmGrainParams& p, const FrameView& src, const FrameView& dst,
                      int matrix_coefficients, int threads) {
    Av1PictureSynthesis synth(threads);
    synth.apply(p, src, dst, matrix_coefficients);
}

}  // namespace filmgrain::av1

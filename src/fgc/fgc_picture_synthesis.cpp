#include "fgc/fgc_picture_synthesis.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "fgc/ar_template_generation.hpp"
#include "fgc/block_randomization.hpp"
#include "fgc/colour_correlation.hpp"
#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::fgc {

int default_block_size(FgcFlavour flavour, int luma_width, int luma_height) {
    if (flavour != FgcFlavour::kVtm) return 8;
    const long long area = (long long)luma_width * luma_height;
    if (area <= 1920LL * 1080) return 8;
    if (area <= 3840LL * 2160) return 16;
    return 32;
}

FgcPictureSynthesis::FgcPictureSynthesis(FgcFlavour flavour, int block_size, int threads, Kernels kernels,
                                     int single_line_blocks)
    : flavour_(flavour),
      block_size_(block_size),
      single_line_(single_line_blocks),
      kernels_(kernels),
      cache_(flavour == FgcFlavour::kVtm ? TemplateTransform::kVvcDct2 : TemplateTransform::kRdd5Matrix, block_size) {
    if (flavour == FgcFlavour::kVfgs)
        throw Error(ErrorCode::kInvalidArgument, "FgcPictureSynthesis runs the rdd5, ffmpeg, vtm and tr flavours; vfgs has its own");
    if (block_size != 8 && block_size != 16 && block_size != 32)
        throw Error(ErrorCode::kInvalidArgument, "block size " + std::to_string(block_size) + " is not 8, 16 or 32");
    if (single_line_blocks != 0 && single_line_blocks != block_size)
        throw Error(ErrorCode::kInvalidArgument, "single-line blocks of " + std::to_string(single_line_blocks) +
                                                     "x1 need block size " + std::to_string(single_line_blocks));
    pool_ = std::make_unique<ThreadPool>(threads);
    scratch_.resize(std::size_t(pool_->size()));
}

FgcPictureSynthesis::~FgcPictureSynthesis() = default;

int FgcPictureSynthesis::threads() const { return pool_->size(); }

std::size_t FgcPictureSynthesis::scratch_bytes() const {
    std::size_t n = 0;
    for (const auto& st : states_) n += st.capacity() * sizeof(uint32_t);
    for (const auto& s : scratch_)
        n += s.stripe.capacity() * sizeof(int32_t) + s.has_grain.capacity() + s.rho.capacity() * sizeof(int16_t) +
             s.sums.capacity() * sizeof(uint32_t) +
             s.blocks.capacity() * sizeof(const int16_t*) + s.narrow_blocks.capacity() * sizeof(const int8_t*) + s.places.capacity() * sizeof(int32_t) +
             s.band.capacity() * sizeof(int16_t) + s.narrow_band.capacity() +
             s.scaled.capacity() * sizeof(int16_t) + s.copies.capacity() * sizeof(simd::BlockCopy);
    for (const auto& g : plane_grain_) n += g.capacity() * sizeof(int32_t);
    return n;
}

std::size_t FgcPictureSynthesis::scaled_template_bytes() const {
    std::size_t n = 0;
    for (const auto& t : scaled_) n += t.bytes();
    return n;
}

void FgcPictureSynthesis::prepare(const ResolvedFgc& params) {
    for (int c = 0; c < 3; c++) {
        auto& list = interval_template_[std::size_t(c)];
        list.clear();
        for (const ResolvedInterval& ri : params.comp[std::size_t(c)].intervals) {
            if (single_line_ && !list.empty()) break;  // one template per component and picture
            if (params.model_id == 0) {
                list.push_back(&cache_.ensure(ri.cutoff_h, ri.cutoff_v));
                continue;
            }
            // Intervals of one component share the noise field (Seed_LUT[c]), so that their
            // templates differ only by the filter and the texture changes smoothly with
            // intensity; components get different fields.
            const std::array<int, 6> key{c, params.log2_scale_factor, ri.ar[1], ri.ar[3], ri.ar[4], ri.ar[5]};
            auto& slot = ar_cache_[key];
            if (!slot)
                slot = std::make_unique<GrainTemplate>(make_ar_template_rdd5_noise(ri.ar, params.log2_scale_factor, c));
            list.push_back(slot.get());
        }
    }
}

void FgcPictureSynthesis::set_deviations(const FgcDeviations& deviations) {
    deviations_ = deviations;
    // template rows are pre-deblocked for the block size (template_generation.hpp); 0: not at all
    cache_.reconfigure(flavour_ == FgcFlavour::kVtm ? TemplateTransform::kVvcDct2 : TemplateTransform::kRdd5Matrix,
                       deviations.no_deblocking ? 0 : block_size_);
    ar_cache_.clear();
}

bool FgcPictureSynthesis::optimized_for(const ResolvedFgc& params, const FrameView& src) const {
    if (deviations_.any()) return false;
    if (kernels_ != Kernels::kOptimized || single_line_ || params.model_id != 0 || params.blending_mode_id != 0)
        return false;
    // ffmpeg: its deblocking depends on which blocks got grain, which the fused deblocking +
    // blending kernels do not know.
    if (flavour_ == FgcFlavour::kFfmpeg) return false;
    // tr with a film grain bit depth above the picture's: scales beyond 255 << (bd - 8),
    // whose products the int16 tables and kernels were not made for.
    for (int c = 0; c < 3; c++)
        if (params.comp[std::size_t(c)].present && params.grain_bit_depth[std::size_t(c)] > src.bit_depth)
            return false;
    return true;
}

void copy_plane(const PlaneView& src, const PlaneView& dst, int bytes_per_sample) {
    if (src.data == dst.data && src.stride == dst.stride) return;
    const std::size_t row_bytes = std::size_t(src.width) * bytes_per_sample;
    for (int y = 0; y < src.height; y++) std::memmove(dst.data + dst.stride * y, src.data + src.stride * y, row_bytes);
}


void FgcPictureSynthesis::apply(const ResolvedFgc& params, const FrameView& src, const FrameView& dst,
                              int32_t pic_offset) {
    prepare(params);
    const bool optimized = optimized_for(params, src);
    const int bps = src.bytes_per_sample();
    const int rb = block_size_ == 32 ? 32 : 16;
    // Sequential part: the LFSR walk of each component (cheap). Then every stripe of every
    // component is an independent task.
    int first_task[4] = {0, 0, 0, 0};
    for (int c = 0; c < 3; c++) {
        int stripes = 0;
        correlate_[std::size_t(c)] = keep_grain_[std::size_t(c)] = false;
        if (c < src.plane_count()) {
            const PlaneView& p = src.planes[c];
            if (params.cancelled || !params.comp[c].present) {
                copy_plane(p, dst.planes[c], bps);
            } else {
                const int blocks_x = (p.width + rb - 1) / rb;
                stripes = (p.height + rb - 1) / rb;
                fill_block_states(component_seed(pic_offset, c), blocks_x, stripes, states_[c]);
                correlate_[std::size_t(c)] = has_colour_correlation(params, c);
                // The next component's colour term reads this one's grain.
                if (c + 1 < src.plane_count() && has_colour_correlation(params, c + 1)) {
                    keep_grain_[std::size_t(c)] = true;
                    plane_grain_[std::size_t(c)].resize(std::size_t(p.width) * std::size_t(p.height));
                }
            }
        }
        first_task[c + 1] = first_task[c] + stripes;
    }
    // Every worker's buffers are sized here, on the calling thread, for the widest plane:
    // a worker that got no stripe in the first frames cannot allocate later.
    const int blocks_x = (src.width + rb - 1) / rb;
    bool all_tables = true, any_narrow = false, any_wide = false;
    if (optimized)
        for (int c = 0; c < src.plane_count() && c < 3; c++)
            if (!params.cancelled && params.comp[c].present) {
                have_scaled_[c] = scaled_[c].update(params.comp[c], cache_, params.log2_scale_factor + 6);
                if (have_scaled_[c])
                    for (int a = 0; a < 256; a++) {
                        const int iv = params.comp[c].interval_of_intensity[std::size_t(a)];
                        table_offsets_[c][std::size_t(a)] =
                            (iv < 0 ? scaled_[c].zero_interval() : iv) * 2 * kTemplateSize * kTemplateSize;
                    }
                all_tables &= have_scaled_[c];
                const bool narrow = have_scaled_[c] && scaled_[c].narrow();
                any_narrow |= narrow;
                any_wide |= !narrow;
            }
    auto grow = [](auto& v, std::size_t n) {
        if (v.size() < n) v.resize(n);
    };
    const bool any_correlation = correlate_[1] || correlate_[2];
    for (auto& s : scratch_) {
        if (!optimized) {
            grow(s.stripe, std::size_t(blocks_x * rb + 2) * rb);
            if (flavour_ == FgcFlavour::kFfmpeg || deviations_.blank_block_deblocking_toggled)
                grow(s.has_grain, std::size_t(blocks_x) * 4);
            if (any_correlation) grow(s.rho, std::size_t(blocks_x * rb + 2) * rb);
        } else {
            grow(s.sums, std::size_t(blocks_x) * 4);
            if (flavour_ == FgcFlavour::kVtm) grow(s.last_row_sums, std::size_t(blocks_x) * 4);
            grow(s.blocks, std::size_t(blocks_x) * 4);
            grow(s.narrow_blocks, std::size_t(blocks_x) * 4);
            grow(s.places, std::size_t(blocks_x) * 2);
            // kBandRows rows of the stripe's grain width and 3 columns of padding for the
            // gathered bands, and what the 8-bit block-row kernel asks for its rows (the
            // widest plane, grain to the end of its blocks)
            const std::size_t band =
                std::max(std::size_t(blocks_x * rb + 3) * std::size_t(kBandRows),
                         simd::deblock_blend_block_rows_scratch(kBandRows, src.width, blocks_x * rb, block_size_));
            if (any_narrow) grow(s.narrow_band, band);
            if (any_wide) grow(s.band, band);
            if (!all_tables) {
                grow(s.scaled, std::size_t(blocks_x) * rb * rb);
                grow(s.copies, std::size_t(blocks_x) * 4);
            }
        }
    }
    // The stripes go to the threads in runs of consecutive ones, because each stripe's blend
    // prefetches the rows of the stripe below (deblock_blend_row_*), which helps only if the
    // same thread takes it: handed out one by one, two threads would alternate and fetch each
    // other's rows. Eight runs per thread keep the threads' shares within a small fraction of
    // a frame of each other when one of them is held up.
    auto run_tasks = [&](int first, int last) {
        const int stripes = last - first;
        if (stripes <= 0) return;
        const int runs = std::min(stripes, pool_->size() == 1 ? 1 : pool_->size() * 8);
        pool_->parallel_for(runs, [&](int run, int worker) {
            const int t0 = first + int(int64_t(stripes) * run / runs);
            const int t1 = first + int(int64_t(stripes) * (run + 1) / runs);
            Scratch& scratch = scratch_[std::size_t(worker)];
            for (int task = t0; task < t1; task++) {
                int c = 0;
                while (task >= first_task[c + 1]) c++;
                const int by = task - first_task[c];
                if (!optimized) {
                    if (bps == 1)
                        reference_stripe<uint8_t>(params, c, src, dst, by, scratch);
                    else
                        reference_stripe<uint16_t>(params, c, src, dst, by, scratch);
                    continue;
                }
                const bool prefetch_next = task + 1 < t1 && task + 1 < first_task[c + 1];
                const PlaneView &s = src.planes[c], &d = dst.planes[c];
                if (bps == 1)
                    optimized_stripe_of<uint8_t>(params, c, s, d, src.bit_depth, by, prefetch_next, scratch);
                else
                    optimized_stripe_of<uint16_t>(params, c, s, d, src.bit_depth, by, prefetch_next, scratch);
            }
        });
    };
    if (!any_correlation) {
        run_tasks(0, first_task[3]);
        return;
    }
    // A component with the colour term starts when the previous one's grain is complete.
    for (int c = 0; c < 3; c++) run_tasks(first_task[c], first_task[c + 1]);
}

}  // namespace filmgrain::fgc

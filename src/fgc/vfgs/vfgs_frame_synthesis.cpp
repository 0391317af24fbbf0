// One frame of VFGS synthesis on stripe threads: see vfgs_frame_synthesis.hpp.
#include "fgc/vfgs/vfgs_frame_synthesis.hpp"

#include <algorithm>
#include <cstring>

#include "core/thread_pool.hpp"
#include "fgc/vfgs/vfgs_block_grains.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "fgc/vfgs/vfgs_stripe_states.hpp"

namespace filmgrain::vfgs {

static_assert(sizeof(TemplateBank::luma) == sizeof(int8_t) * kTemplateBytes * kMaxTemplates,
              "the kernels step from one template of a pool to the next by kTemplateBytes");

namespace {

// What every stripe of the frame reads.
struct FrameJob {
    const FrameView& src;
    const FrameView& dst;
    const SynthesisSetup& setup;
    std::array<bool, 3> vector_kernels{};
    int blocks = 0;  // per stripe
    bool vector_block_grains = false;
};

void grain_row(bool vec, const GrainRowJob& job, const uint8_t* in, int16_t* grain, int16_t* scale) {
    vec ? simd::grain_row_u8(job, in, grain, scale) : scalar::grain_row_u8(job, in, grain, scale);
}
void grain_row(bool vec, const GrainRowJob& job, const uint16_t* in, int16_t* grain, int16_t* scale) {
    vec ? simd::grain_row_u16(job, in, grain, scale) : scalar::grain_row_u16(job, in, grain, scale);
}
void blend_row(bool vec, const BlendRowJob& job, const uint8_t* in, const int16_t* g, const int16_t* s, uint8_t* out) {
    vec ? simd::blend_row_u8(job, in, g, s, out) : scalar::blend_row_u8(job, in, g, s, out);
}
void blend_row(bool vec, const BlendRowJob& job, const uint16_t* in, const int16_t* g, const int16_t* s,
               uint16_t* out) {
    vec ? simd::blend_row_u16(job, in, g, s, out) : scalar::blend_row_u16(job, in, g, s, out);
}
void blend_row(bool vec, const BlendRowJob& job, const uint16_t* in, const int16_t* g, const int16_t* s,
               uint8_t* out) {
    vec ? simd::blend_row_u16_to_u8(job, in, g, s, out) : scalar::blend_row_u16_to_u8(job, in, g, s, out);
}

bool grain_blend_row(const GrainRowJob& job, const BlendRowJob& blend, const uint8_t* in, uint8_t* out) {
    return simd::grain_blend_row_u8(job, blend, in, out);
}
bool grain_blend_row(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint16_t* out) {
    return simd::grain_blend_row_u16(job, blend, in, out);
}
bool grain_blend_row(const GrainRowJob& job, const BlendRowJob& blend, const uint16_t* in, uint8_t* out) {
    return simd::grain_blend_row_u16_to_u8(job, blend, in, out);
}

const int8_t* pool_base(const SynthesisSetup& st, int c) {
    return c ? &st.bank->chroma[0][0][0] : &st.bank->luma[0][0][0];
}

BlendRowJob blend_job(const FrameJob& f, int plane_width) {
    BlendRowJob blend;
    blend.width = plane_width;
    blend.shift = f.setup.scale_shift;
    blend.bit_depth = f.src.bit_depth;
    return blend;
}

// Row `py` of plane `c`; `j` is the luma row inside the block stripe.
template <typename In, typename Out>
void synthesize_row(const FrameJob& f, int c, int py, int j, bool first_stripe, const GrainBlock* blocks,
                    FrameSynthesis::Scratch& s) {
    const int subx = c ? (1 << chroma_shift_x(f.src.format)) : 1;
    const int suby = c ? (1 << chroma_shift_y(f.src.format)) : 1;
    const int bw = 16 / subx;
    const int pw = f.src.planes[c].width;
    const bool vec = f.vector_kernels[static_cast<size_t>(c)];

    const In* in = f.src.planes[c].template row<const In>(py);
    int16_t* grain = s.grain.data();
    int16_t* scale = s.scale.data();
    if (f.setup.has_grain[static_cast<size_t>(c)]) {
        const auto [c1, c2] = overlap_weights(j, suby, first_stripe);
        const int8_t* base = pool_base(f.setup, c);
        GrainRowJob job;
        job.pool = base + (j / suby) * kTemplatePitch;
        job.pool_up = base + ((16 + j) / suby) * kTemplatePitch;  // the block above continues below its 16 rows
        job.luts = &f.setup.luts[static_cast<size_t>(c)];
        job.runs = &f.setup.runs[static_cast<size_t>(c)];
        job.blocks = blocks;
        job.block_count = pw / bw;  // the blocks inside the row, read in place
        job.block_width = bw;
        job.overlap_c1 = c1;
        job.overlap_c2 = c2;
        job.intensity_shift = f.src.bit_depth - 8;
        job.pattern_interpolation = f.setup.pattern_interpolation;
        if (vec && job.block_count == f.blocks &&
            grain_blend_row(job, blend_job(f, pw), in, f.dst.planes[c].template row<Out>(py)))
            return;
        grain_row(vec, job, in, grain, scale);
        if (job.block_count < f.blocks) {
            // A last block that sticks out of the row. There the reference reads its
            // (uninitialised) stride padding; that only selects templates for grain that is
            // never written, except when the block holds a single sample: then the
            // deblocking of the last edge reads it. The last sample is replicated there.
            const int x0 = job.block_count * bw;
            In* padded = reinterpret_cast<In*>(s.in.data());
            std::copy(in + x0, in + pw, padded);
            std::fill(padded + (pw - x0), padded + bw, in[pw - 1]);
            job.blocks = blocks + job.block_count;
            job.block_count = f.blocks - job.block_count;
            grain_row(vec, job, padded, grain + x0, scale + x0);
            if (x0 > 0) {
                int g[4] = {grain[x0 - 2], grain[x0 - 1], grain[x0], grain[x0 + 1]};
                deblock_edge(g, 2);  // the edge between the two calls
                grain[x0 - 1] = static_cast<int16_t>(g[1]);
                grain[x0] = static_cast<int16_t>(g[2]);
            }
        }
    } else {
        // no grain: the reference still clips the plane (blend of 0)
        std::fill(s.grain.begin(), s.grain.end(), int16_t{0});
        std::fill(s.scale.begin(), s.scale.end(), int16_t{0});
    }
    blend_row(vec, blend_job(f, pw), in, grain, scale, f.dst.planes[c].template row<Out>(py));
}

template <typename In, typename Out>
void synthesize_stripe(const FrameJob& f, int k, uint32_t first_state, uint32_t first_state_up,
                       FrameSynthesis::Scratch& s) {
    const int nb = f.blocks;
    const int planes = f.src.plane_count();
    const bool first_stripe = k == 0;
    fill_block_states(first_state, nb, s.states_cur.data());
    if (!first_stripe) fill_block_states(first_state_up, nb, s.states_up.data());
    for (int c = 0; c < planes; ++c) {
        if (!f.setup.has_grain[static_cast<size_t>(c)]) continue;
        BlockGrainsJob job;
        job.component = c;
        job.subx = c ? (1 << chroma_shift_x(f.src.format)) : 1;
        job.suby = c ? (1 << chroma_shift_y(f.src.format)) : 1;
        job.states = s.states_cur.data();
        job.states_up = first_stripe ? s.states_cur.data() : s.states_up.data();  // no block above: unused
        job.count = nb;
        GrainBlock* blocks = s.blocks.data() + static_cast<size_t>(c) * static_cast<size_t>(nb);
        f.vector_block_grains ? simd::block_grains(job, blocks) : scalar::block_grains(job, blocks);
    }
    const int suby_c = 1 << chroma_shift_y(f.src.format);
    const int y_end = std::min(16 * (k + 1), f.src.height);
    for (int y = 16 * k; y < y_end; ++y) {
        const int j = y - 16 * k;
        synthesize_row<In, Out>(f, 0, y, j, first_stripe, s.blocks.data(), s);
        if (planes > 1 && y % suby_c == 0)
            for (int c = 1; c < planes; ++c)
                synthesize_row<In, Out>(f, c, y / suby_c, j, first_stripe,
                                        s.blocks.data() + static_cast<size_t>(c) * static_cast<size_t>(nb), s);
    }
}

}  // namespace

FrameSynthesis::FrameSynthesis(int threads, Kernels kernels)
    : pool_(std::make_unique<ThreadPool>(threads)), kernels_(kernels) {
    scratch_.resize(static_cast<size_t>(pool_->size()));
}

FrameSynthesis::~FrameSynthesis() = default;

int FrameSynthesis::threads() const { return pool_->size(); }

void FrameSynthesis::plan_stripes(int luma_width, int luma_height, LfsrCursor& cursor) {
    const int nb = blocks_per_stripe(luma_width);
    if (stripe_step_blocks_ != nb) {
        stripe_step_ = LfsrJump(static_cast<uint64_t>(nb));
        stripe_step_blocks_ = nb;
    }
    plan_stripe_states(cursor, stripes_per_frame(luma_height), stripe_step_, stripe_starts_);
}

void FrameSynthesis::skip(int luma_width, int luma_height, LfsrCursor& cursor) {
    plan_stripes(luma_width, luma_height, cursor);
}

void FrameSynthesis::apply(const FrameView& src, const FrameView& dst, const SynthesisSetup& setup, LfsrCursor& cursor) {
    const int nb = blocks_per_stripe(src.width);
    const int ns = stripes_per_frame(src.height);
    FrameJob f{src, dst, setup, {}, nb};
    for (size_t c = 0; c < 3; ++c)
        f.vector_kernels[c] = kernels_ == Kernels::kOptimized && !setup.pattern_interpolation &&
                              setup.runs[c].count <= kMaxVectorRuns;
    f.vector_block_grains = kernels_ == Kernels::kOptimized;
    plan_stripes(src.width, src.height, cursor);

    // Every worker's buffers are sized here, on the calling thread: a worker that got no
    // stripe in the first frames cannot allocate later.
    const size_t row = static_cast<size_t>(nb) * 16;
    for (Scratch& s : scratch_) {
        s.states_cur.resize(static_cast<size_t>(nb));
        s.states_up.resize(static_cast<size_t>(nb));
        s.blocks.resize(3 * static_cast<size_t>(nb));
        s.in.resize(row);
        s.grain.resize(row + 2);
        s.scale.resize(row);
    }

    // Runs of consecutive stripes per task, as FgcPictureSynthesis hands them out, but finer:
    // a vfgs stripe costs about four of FGC's, and with eight runs per thread the last run
    // left the other thread idle for a good part of it (1080p 8-bit, 2 threads: 0.74-0.79 ms
    // with eight, 0.69 ms with 32, one thread 1.33 ms). Each run recomputes the block states
    // of the stripe above its first (fill_block_states, about 1 % of the time).
    const int runs = std::min(ns, pool_->size() == 1 ? 1 : pool_->size() * 32);
    pool_->parallel_for(runs, [&](int run, int worker) {
        const int k0 = static_cast<int>(int64_t(ns) * run / runs);
        const int k1 = static_cast<int>(int64_t(ns) * (run + 1) / runs);
        Scratch& s = scratch_[static_cast<size_t>(worker)];
        for (int k = k0; k < k1; ++k) {
            const uint32_t cur = stripe_starts_[static_cast<size_t>(k) + 1], up = stripe_starts_[static_cast<size_t>(k)];
            if (src.bit_depth == 8) synthesize_stripe<uint8_t, uint8_t>(f, k, cur, up, s);
            else if (dst.bit_depth == 8) synthesize_stripe<uint16_t, uint8_t>(f, k, cur, up, s);
            else synthesize_stripe<uint16_t, uint16_t>(f, k, cur, up, s);
        }
    });
}

}  // namespace filmgrain::vfgs

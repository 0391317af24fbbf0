// The public VFGS synthesizer (include/filmgrain/vfgs.hpp): holds the random
// state across frames and rebuilds templates and LUTs when the parameters or
// the picture format change.
#include <algorithm>
#include <string>

#include "core/plane_layout.hpp"
#include "core/thread_pool.hpp"
#include "fgc/vfgs/vfgs_frame_setup.hpp"
#include "fgc/vfgs/vfgs_frame_synthesis.hpp"
#include "fgc/vfgs/vfgs_parameters.hpp"
#include "fgc/vfgs/vfgs_picture_synthesis.hpp"
#include "fgc/vfgs/vfgs_random.hpp"
#include "fgc/vfgs/vfgs_templates.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/vfgs.hpp"

namespace filmgrain::vfgs {

struct Synthesizer::Impl {
    Options options;
    LfsrCursor cursor;
    std::optional<FgcParams> params;
    bool prepared = false;
    ChromaFormat prepared_format = ChromaFormat::k420;
    int prepared_bit_depth = 0;
    TemplateBank bank;  // persists across parameter sets, as VFGS's template memory
    SynthesisSetup setup;
    FrameSynthesis frames;

    explicit Impl(const Options& o) : frames(o.threads, o.reference_kernels ? Kernels::kReference : Kernels::kOptimized) {}

    void prepare(ChromaFormat format, int bit_depth) {
        setup = prepare_setup(*params, format, bit_depth, options, bank);
        prepared = true;
        prepared_format = format;
        prepared_bit_depth = bit_depth;
    }
};

namespace {
// Before the stripe workers exist: a bad thread count must not reach the pool.
const Options& checked(const Options& options) {
    if (options.threads < 0 || options.threads > kMaxThreads)
        throw Error(ErrorCode::kInvalidArgument, "vfgs: threads = " + std::to_string(options.threads) +
                                                     " (allowed 0 = every hardware thread, 1.." +
                                                     std::to_string(kMaxThreads) + ")");
    if (options.gain_percent < 0)
        throw Error(ErrorCode::kInvalidArgument,
                    "vfgs: gain = " + std::to_string(options.gain_percent) + " percent is negative (allowed 0 and above)");
    if (options.output_bit_depth != 0 && options.output_bit_depth != 8 && options.output_bit_depth != 10)
        throw Error(ErrorCode::kInvalidArgument,
                    "vfgs: output bit depth = " + std::to_string(options.output_bit_depth) +
                        " (allowed 0 = same as input, 8, 10)");
    if (options.block_size != 0 && options.block_size != 16)
        throw Error(ErrorCode::kUnsupported,
                    "vfgs: block size " + std::to_string(options.block_size) +
                        " is not supported (allowed 0 or 16: VFGS randomizes 16x16 blocks, its LFSR bit fields give "
                        "offsets for 16-sample blocks in 64x64 templates, and its overlap and stripes are 16 rows)");
    return options;
}
}  // namespace

Synthesizer::Synthesizer(const Options& options) : impl_(std::make_unique<Impl>(checked(options))) {
    impl_->options = options;
    const uint32_t r0 = options.seed ? lfsr_state_from_seed(*options.seed) : kDefaultLfsrState;
    impl_->cursor = LfsrCursor{r0, r0};
}

Synthesizer::~Synthesizer() = default;
Synthesizer::Synthesizer(Synthesizer&&) noexcept = default;
Synthesizer& Synthesizer::operator=(Synthesizer&&) noexcept = default;

void Synthesizer::set_params(const FgcParams& params) {
    validate_params(params, impl_->options.gain_percent);
    impl_->params = params;
    impl_->prepared = false;
}

uint32_t Synthesizer::lfsr_state() const { return impl_->cursor.stripe; }

namespace {

[[noreturn]] void unsupported(const std::string& msg) { throw Error(ErrorCode::kUnsupported, "vfgs: " + msg); }
[[noreturn]] void bad_arg(const std::string& msg) { throw Error(ErrorCode::kInvalidArgument, "vfgs: " + msg); }

// The reference asserts width > 128 and height >= 128.
void check_picture_size(int width, int height) {
    if (width <= 128) unsupported(out_of_range_message("width", width, 129, 65535) + " (VFGS limit)");
    if (height < 128) unsupported(out_of_range_message("height", height, 128, 65535) + " (VFGS limit)");
}

void check_frame(const FrameView& src, const FrameView& dst, int out_bd) {
    if (src.format == ChromaFormat::k400) unsupported("chroma format 4:0:0 is not supported by VFGS (allowed 4:2:0, 4:2:2, 4:4:4)");
    if (src.bit_depth != 8 && src.bit_depth != 10)
        unsupported("bit_depth = " + std::to_string(src.bit_depth) + " is not supported by VFGS (allowed 8, 10)");
    check_picture_size(src.width, src.height);
    if (chroma_shift_x(src.format) && (src.width & 1))
        unsupported("width = " + std::to_string(src.width) + " is odd; VFGS needs even widths for subsampled chroma");
    if (chroma_shift_y(src.format) && (src.height & 1))
        unsupported("height = " + std::to_string(src.height) + " is odd; VFGS needs even heights for 4:2:0");
    if (dst.width != src.width || dst.height != src.height || dst.format != src.format)
        bad_arg("destination frame size/format differs from the source");
    if (dst.bit_depth != out_bd)
        bad_arg("destination bit_depth = " + std::to_string(dst.bit_depth) + ", expected " + std::to_string(out_bd));
    try {
        check_plane_layout(src, "src");
        check_plane_layout(dst, "dst");
    } catch (const Error& e) {
        bad_arg(e.what());
    }
    for (int p = 0; p < src.plane_count(); ++p) {
        const int pw = plane_width(src.format, p, src.width), ph = plane_height(src.format, p, src.height);
        if (!src.planes[p].data || !dst.planes[p].data) bad_arg("plane " + std::to_string(p) + " has no data");
        if (src.planes[p].width != pw || src.planes[p].height != ph || dst.planes[p].width != pw ||
            dst.planes[p].height != ph)
            bad_arg("plane " + std::to_string(p) + " size does not match the frame size and format");
    }
}

void copy_frame(const FrameView& src, const FrameView& dst) {
    for (int p = 0; p < src.plane_count(); ++p)
        for (int y = 0; y < src.planes[p].height; ++y)
            for (int x = 0; x < src.planes[p].width; ++x) {
                const int v = src.bit_depth > 8 ? src.planes[p].row<const uint16_t>(y)[x] : src.planes[p].row<const uint8_t>(y)[x];
                if (dst.bit_depth > 8) dst.planes[p].row<uint16_t>(y)[x] = static_cast<uint16_t>(v);
                else dst.planes[p].row<uint8_t>(y)[x] = static_cast<uint8_t>(dst.bit_depth < src.bit_depth ? to_8bit(v) : v);
            }
}

}  // namespace

void Synthesizer::pass_through(const FrameView& src, const FrameView& dst) const {
    const int out_bd = impl_->options.output_bit_depth ? impl_->options.output_bit_depth : src.bit_depth;
    if (dst.bit_depth != out_bd)
        bad_arg("destination bit_depth = " + std::to_string(dst.bit_depth) + ", expected " + std::to_string(out_bd));
    if (dst.planes[0].data == src.planes[0].data) return;  // in place, same depth
    copy_frame(src, dst);
}

void Synthesizer::apply(const FrameView& src, const FrameView& dst) {
    Impl& m = *impl_;
    if (!m.params) bad_arg("apply() called before set_params()");
    int out_bd = m.options.output_bit_depth ? m.options.output_bit_depth : src.bit_depth;
    if (out_bd > src.bit_depth)
        bad_arg("output bit depth " + std::to_string(out_bd) + " is above the input bit depth " +
                std::to_string(src.bit_depth));
    check_frame(src, dst, out_bd);
    if (m.params->film_grain_characteristics_cancel_flag) {
        copy_frame(src, dst);
        return;
    }
    if (!m.prepared || m.prepared_format != src.format || m.prepared_bit_depth != src.bit_depth)
        m.prepare(src.format, src.bit_depth);
    m.frames.apply(src, dst, m.setup, m.cursor);
}

void Synthesizer::skip(int luma_width, int luma_height) {
    Impl& m = *impl_;
    if (!m.params) bad_arg("skip() called before set_params()");
    check_picture_size(luma_width, luma_height);
    if (m.params->film_grain_characteristics_cancel_flag) return;
    m.frames.skip(luma_width, luma_height, m.cursor);
}

}  // namespace filmgrain::vfgs

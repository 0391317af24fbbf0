// The Versatile Film Grain (VFGS) flavour of the FGC SEI film grain model:
// bit-exact with InterDigital's VersatileFilmGrain reference (ISO/IEC TR
// 23002-9 clause 7.5 / Annex B.2.2), for FGC SEI input.
//
// Supported as the reference: 8- and 10-bit; 4:2:0 with luma and chroma grain;
// 4:2:2 and 4:4:4 with luma grain only; model 0 (frequency filtering) and
// model 1 (auto-regression, luma only); width > 128, height >= 128, even sizes
// for subsampled chroma. Anything else throws filmgrain::Error(kUnsupported).
#pragma once
#include <cstdint>
#include <memory>
#include <optional>

#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"

namespace filmgrain::vfgs {

struct Options {
    // VFGS -r: the LFSR starts at (seed << 1). Absent (or 0, as in VFGS) =
    // the reference's default state 0xDEADBEEF.
    std::optional<uint32_t> seed;
    // VFGS --gain (percent, >= 0): a global grain strength outside the SEI.
    int gain_percent = 100;
    // VFGS --outdepth: 0 = same as the input; 8 = round 10-bit output to 8 bit.
    int output_bit_depth = 0;
    // TR 23002-9 7.2.4.2 / 7.5.4 pattern interpolation, compiled out of the
    // reference. Off = bit-exact with the reference.
    bool pattern_interpolation = false;
    // The block size, as FgcOptions::block_size: 0 or 16, the only one VFGS has. VFGS has
    // no averaging block (its adaptation is per sample); its 16x16 block is the unit of
    // randomization, and the reference's structure is built on it: the LFSR bit fields
    // give offsets 0..48 / 0..44 in steps of 4 that keep 16 samples inside the 64x64
    // template, a frame is processed in 16-row stripes with one register value per block,
    // and the vertical overlap blends rows 16k and 16k+1 (4:2:0 chroma 8k). 8 or 32 would
    // change all three and is not a VFGS any more: it throws Error(kUnsupported).
    int block_size = 0;
    // Stripe workers including the calling thread: 0..256, 0 = every hardware thread. Each
    // stripe starts from its own LFSR state, jumped ahead at set-up from the reference's one
    // sequence through the picture, so the output is the same for every count.
    int threads = 1;
    // true: the scalar reference row kernels instead of the vector ones (verification and
    // benchmarks, as SessionOptions::reference_kernels); the output is identical.
    bool reference_kernels = false;
};

class Synthesizer {
public:
    // Throws Error(kInvalidArgument) for a negative gain or an output bit depth other than 0/8/10.
    explicit Synthesizer(const Options& options);
    ~Synthesizer();
    Synthesizer(Synthesizer&&) noexcept;
    Synthesizer& operator=(Synthesizer&&) noexcept;
    Synthesizer(const Synthesizer&) = delete;
    Synthesizer& operator=(const Synthesizer&) = delete;

    // Installs a parameter set from the next frame on. Validates what does not
    // depend on the picture format (throws Error naming field, value and range);
    // format-dependent checks run at the next apply(). The random state is not
    // touched: VFGS never reseeds. film_grain_characteristics_cancel_flag = 1
    // turns grain off (apply() then copies) - VFGS itself never sees a cancel.
    void set_params(const FgcParams& params);

    // Adds grain to one frame, in output order. dst has src's size and format,
    // and src's bit depth or Options::output_bit_depth; it may alias src when
    // the bit depths match. Throws when no parameters were set.
    void apply(const FrameView& src, const FrameView& dst);
    // Follows one frame of this luma size without synthesizing it: the random state moves on
    // exactly as apply() would move it (one LFSR step per 16x16 block, jumped; not at all
    // under a cancel), so that work on a range of a stream can start mid-way. Throws as
    // apply() does for a size VFGS refuses (kUnsupported), and kInvalidArgument when no
    // parameters were set; the chroma format and bit depth are apply()'s to check.
    void skip(int luma_width, int luma_height);
    // A picture without grain (no parameter set yet, or an invalid one passed through):
    // src copied to dst, rounded to Options::output_bit_depth as the reference outputs it.
    void pass_through(const FrameView& src, const FrameView& dst) const;

    // The LFSR state the next frame's first block stripe starts from.
    uint32_t lfsr_state() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace filmgrain::vfgs

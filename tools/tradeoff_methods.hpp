// The methods `filmgrain tradeoff` compares, each fitted to one target grain (the Boolean
// model's closed-form covariance at one grey level) and run on the same flat content.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/frame_buffer.hpp"
#include "filmgrain/av1_params.hpp"
#include "filmgrain/fgc_params.hpp"

namespace filmgrain::cli {

// The target: covariance at a lag of output pixels, in units of full scale squared.
using TargetCovariance = std::function<double(int dx, int dy)>;

// Model-0 (frequency filtering) FGC SEI for luma over the whole intensity range.
FgcParams fgc_params(int scale, int log2_scale_factor, int cutoff_h, int cutoff_v);
// AV1 grain parameters: a lag-3 auto-regressive luma template from Yule-Walker equations on
// the target, and a flat scaling function.
Av1FilmGrainParams av1_params(const TargetCovariance& target, int scaling, int scaling_shift_minus_8, int seed);

// A synthesizer of grain on an 8-bit yuv420p frame, for one frame index.
using FrameSynthesizer = std::function<void(const FrameBuffer& src, FrameBuffer& dst, int frame)>;
FrameSynthesizer fgc_synthesizer(const FgcParams& p, FgcFlavour flavour);
FrameSynthesizer av1_synthesizer(const Av1FilmGrainParams& p);

// v with `decimals` digits after the point, as the report's tables print numbers.
std::string fixed_decimals(double v, int decimals);

}  // namespace filmgrain::cli

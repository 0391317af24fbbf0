// The one grain template type of the frequency-filtering model's flavours: 64x64 int8
// samples, [row][column]. The frequency-filtered templates (template_generation), the
// auto-regressive ones (ar_template_generation) and VFGS's (vfgs/vfgs_templates, whose
// 4:2:0 chroma templates fill the top-left 32x32) are all of it.
#pragma once
#include <array>
#include <cstdint>

namespace filmgrain::fgc {

inline constexpr int kTemplateSize = 64;
using GrainTemplate = std::array<std::array<int8_t, kTemplateSize>, kTemplateSize>;

}  // namespace filmgrain::fgc

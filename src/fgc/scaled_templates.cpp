#include "fgc/scaled_templates.hpp"

#include <algorithm>

#include "fgc/simd/fgc_kernels.hpp"

namespace filmgrain::fgc {

bool ScaledTemplates::update(const ResolvedComponent& comp, const TemplateCache& cache, int shift) {
    const std::size_t n = comp.intervals.size();
    if (n > std::size_t(kMaxIntervals)) {
        valid_ = false;
        keys_.clear();
        data_ = {};
        narrow_data_ = {};
        return false;
    }
    bool same = valid_ && shift == shift_ && keys_.size() == n;
    for (std::size_t i = 0; same && i < n; i++) {
        const ResolvedInterval& ri = comp.intervals[i];
        same = keys_[i] == Key{ri.scale, ri.cutoff_h, ri.cutoff_v};
    }
    if (same) return true;
    keys_.clear();
    narrow_data_.clear();
    data_.resize((n + 1) * 2 * kTemplateSize * kTemplateSize);
    std::fill(data_.begin() + std::ptrdiff_t(n * 2 * kTemplateSize * kTemplateSize), data_.end(), int16_t(0));
    std::vector<simd::BlockCopy> copies;
    copies.reserve(n * 2);
    for (std::size_t i = 0; i < n; i++) {
        const ResolvedInterval& ri = comp.intervals[i];
        keys_.push_back({ri.scale, ri.cutoff_h, ri.cutoff_v});
        const GrainTemplate& t = cache.get(ri.cutoff_h, ri.cutoff_v);
        // LFSR bit 0 set means a negative block (block_offset_from_state)
        for (uint32_t negative = 0; negative < 2; negative++)
            copies.push_back({t[0].data(), data_.data() + (i * 2 + negative) * kTemplateSize * kTemplateSize,
                              negative ? -ri.scale : ri.scale, kTemplateSize});
    }
    simd::scale_template_blocks(copies.data(), int(copies.size()), kTemplateSize, shift, kTemplateSize);
    if (std::all_of(data_.begin(), data_.end(), [](int16_t v) { return v >= -128 && v <= 127; })) {
        narrow_data_.assign(data_.begin(), data_.end());
        data_ = {};
    }
    shift_ = shift;
    valid_ = true;
    return true;
}

}  // namespace filmgrain::fgc

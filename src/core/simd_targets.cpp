#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/simd_targets.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include <algorithm>
#include <cctype>

#include "core/simd_targets.hpp"

HWY_BEFORE_NAMESPACE();
namespace filmgrain::simd {
namespace HWY_NAMESPACE {
int64_t CompiledTarget() { return HWY_TARGET; }
}  // namespace HWY_NAMESPACE
}  // namespace filmgrain::simd
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace filmgrain::simd {

HWY_EXPORT(CompiledTarget);

std::vector<Target> available_targets() {
    std::vector<Target> out;
    const int64_t supported = hwy::SupportedTargets() & HWY_TARGETS;
    // Highway numbers better targets with lower bits on x86 and ARM.
    for (int64_t t = supported; t != 0; t &= t - 1) {
        const int64_t bit = t & ~(t - 1);
        out.push_back({bit, hwy::TargetName(bit)});
    }
    return out;
}

bool force_target(int64_t bits) {
    if (bits == 0) {
        hwy::SetSupportedTargetsForTest(0);
        return true;
    }
    const auto all = available_targets();
    if (std::none_of(all.begin(), all.end(), [&](const Target& t) { return t.bits == bits; })) return false;
    hwy::SetSupportedTargetsForTest(bits);
    return true;
}

bool force_target(const std::string& name) {
    auto lower = [](std::string s) {
        for (auto& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        return s;
    };
    for (const auto& t : available_targets())
        if (lower(t.name) == lower(name)) return force_target(t.bits);
    return false;
}

std::string dispatched_target() { return hwy::TargetName(HWY_DYNAMIC_DISPATCH(CompiledTarget)()); }

}  // namespace filmgrain::simd
#endif  // HWY_ONCE

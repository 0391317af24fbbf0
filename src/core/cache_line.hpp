#pragma once

#include <cstddef>

namespace filmgrain {

// The cache line of the x86-64 CPUs the kernels were tuned on (Zen 3, 4 and 5). A vector store
// that straddles two lines costs a second line fill: picture rows, the FGC grain band and the
// zero grain table start on one. std::hardware_destructive_interference_size would say the
// same, but GCC warns that its value follows -mtune, so a header cannot rely on it.
inline constexpr std::size_t kCacheLineBytes = 64;

}  // namespace filmgrain

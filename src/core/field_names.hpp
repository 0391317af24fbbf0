// The names error messages give indexed syntax fields: name[i][j]..., as the specs write them
// (point_y_value[3], comp_model_value[0][1][2]). Appended piece by piece: prepending "[" to
// a temporary string makes GCC 12 warn (-Wrestrict, a false positive).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace filmgrain {

// The colour component a plane index names in messages and reports: Y, Cb, Cr (the
// specs' component order, H.274 and AV1 alike); "?" past the third.
constexpr const char* plane_name(std::size_t plane) {
    constexpr const char* kNames[3] = {"Y", "Cb", "Cr"};
    return plane < 3 ? kNames[plane] : "?";
}

template <typename... Index>
std::string indexed(std::string_view name, Index... index) {
    std::string s(name);
    ((s += '[', s += std::to_string(index), s += ']'), ...);
    return s;
}

}  // namespace filmgrain

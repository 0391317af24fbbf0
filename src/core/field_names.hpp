// The names error messages give indexed syntax fields: name[i][j]..., as the specs write them
// (point_y_value[3], comp_model_value[0][1][2]). Appended piece by piece: prepending "[" to
// a temporary string makes GCC 12 warn (-Wrestrict, a false positive).
#pragma once
#include <string>
#include <string_view>

namespace filmgrain {

template <typename... Index>
std::string indexed(std::string_view name, Index... index) {
    std::string s(name);
    ((s += '[', s += std::to_string(index), s += ']'), ...);
    return s;
}

}  // namespace filmgrain

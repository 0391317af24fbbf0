#include "filmgrain/error.hpp"

namespace filmgrain {

std::string out_of_range_message(const std::string& field, long long value, long long lo, long long hi) {
    return field + " = " + std::to_string(value) + " is out of range (allowed " + std::to_string(lo) + ".." +
           std::to_string(hi) + ")";
}

}  // namespace filmgrain

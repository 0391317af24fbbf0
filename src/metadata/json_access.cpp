#include "metadata/json_access.hpp"

namespace filmgrain {

int JsonObject::to_int(const nlohmann::json& v, long long lo, long long hi, const std::string& name) {
    long long x;
    if (v.is_boolean()) x = v.get<bool>() ? 1 : 0;
    else if (v.is_number_integer()) x = v.get<long long>();
    else if (v.is_number_float() && v.get<double>() == double((long long)v.get<double>())) x = (long long)v.get<double>();
    else throw Error(ErrorCode::kInvalidParams, name + " = " + v.dump() + " is not an integer");
    if (x < lo || x > hi) throw Error(ErrorCode::kInvalidParams, out_of_range_message(name, x, lo, hi));
    return int(x);
}

int JsonObject::get_int(const char* key, int fallback, long long lo, long long hi) const {
    if (!has(key)) return fallback;
    return to_int(j_[key], lo, hi, ctx_ + "." + key);
}

int JsonObject::require_int(const char* key, long long lo, long long hi) const {
    if (!has(key)) throw Error(ErrorCode::kInvalidParams, ctx_ + ": required key '" + key + "' is missing");
    return to_int(j_[key], lo, hi, ctx_ + "." + key);
}

const nlohmann::json* JsonObject::array(const char* key) const {
    if (!has(key)) return nullptr;
    if (!j_[key].is_array()) throw Error(ErrorCode::kInvalidParams, ctx_ + "." + key + " must be an array");
    return &j_[key];
}

std::vector<int> JsonObject::get_int_array(const char* key, std::size_t n, long long lo, long long hi,
                                           bool required) const {
    const nlohmann::json* a = array(key);
    if (!a) {
        if (required) throw Error(ErrorCode::kInvalidParams, ctx_ + ": required key '" + key + "' is missing");
        return {};
    }
    if (a->size() < n)
        throw Error(ErrorCode::kInvalidParams, ctx_ + "." + key + " has " + std::to_string(a->size()) +
                                                   " entries (needs " + std::to_string(n) + ")");
    std::vector<int> out;
    for (std::size_t i = 0; i < n; i++)
        out.push_back(to_int((*a)[i], lo, hi, ctx_ + "." + key + "[" + std::to_string(i) + "]"));
    return out;
}

std::vector<int> JsonObject::int_array_at(const nlohmann::json& outer, std::size_t i, std::size_t n, long long lo,
                                          long long hi, const std::string& name) {
    if (!outer.is_array() || outer.size() <= i || !outer[i].is_array())
        throw Error(ErrorCode::kInvalidParams, name + " is missing or not an array");
    const auto& a = outer[i];
    if (a.size() < n)
        throw Error(ErrorCode::kInvalidParams,
                    name + " has " + std::to_string(a.size()) + " entries (needs " + std::to_string(n) + ")");
    std::vector<int> out;
    for (std::size_t k = 0; k < n; k++) out.push_back(to_int(a[k], lo, hi, name + "[" + std::to_string(k) + "]"));
    return out;
}

}  // namespace filmgrain

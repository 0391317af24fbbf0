// Checked access to JSON parameter objects: every failure names the key, the value and
// the allowed range, so a user can fix the file.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "filmgrain/error.hpp"

namespace filmgrain {

class JsonObject {
public:
    JsonObject(const nlohmann::json& j, std::string context) : j_(j), ctx_(std::move(context)) {
        if (!j.is_object()) throw Error(ErrorCode::kInvalidParams, ctx_ + ": expected a JSON object");
    }
    bool has(const char* key) const { return j_.contains(key) && !j_[key].is_null(); }
    int get_int(const char* key, int fallback, long long lo, long long hi) const;
    int require_int(const char* key, long long lo, long long hi) const;
    // An array of `n` integers; empty result when absent and not required.
    std::vector<int> get_int_array(const char* key, std::size_t n, long long lo, long long hi, bool required = true) const;
    const nlohmann::json* array(const char* key) const;
    // Element `i` of an array of arrays, itself an array of `n` integers.
    static std::vector<int> int_array_at(const nlohmann::json& outer, std::size_t i, std::size_t n, long long lo,
                                         long long hi, const std::string& name);
    static int to_int(const nlohmann::json& v, long long lo, long long hi, const std::string& name);
    const std::string& context() const { return ctx_; }

private:
    const nlohmann::json& j_;
    std::string ctx_;
};

}  // namespace filmgrain

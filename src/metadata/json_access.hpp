// Checked access to JSON parameter objects: every failure names the key, the value and
// the allowed range, so a user can fix the file.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "filmgrain/error.hpp"

namespace filmgrain {

// Limits of every JSON document the project reads (parameter files, case.json, the C
// API's JSON): a parameter file is a few kilobytes and nests six levels deep, so these
// leave ample room while keeping a hostile file from exhausting memory or the stack.
inline constexpr std::size_t kMaxJsonBytes = 16u << 20;
inline constexpr int kMaxJsonDepth = 64;

// Parses one JSON document of at most kMaxJsonBytes and kMaxJsonDepth levels of nesting.
// Errors (Error(kInvalidParams)) name `what` (a file name or "JSON parameters"), and for
// a syntax error the byte offset nlohmann reports.
nlohmann::json parse_json_document(const uint8_t* data, std::size_t size, const std::string& what);
// The same for a file (read with the same size bound; Error(kIo) when it cannot be read).
nlohmann::json read_json_file(const std::string& path);

// A value as an error message may quote it: scalars as written (strings cut at 40
// characters), containers by kind and size, never recursively.
std::string json_brief(const nlohmann::json& v);

// An integer JSON value (or a boolean, or a float with an integral value) as a long long,
// range-checked against lo..hi without wrapping: unsigned values above the range and
// floats beyond it are errors naming `name`, the value and the range.
long long json_to_integer(const nlohmann::json& v, long long lo, long long hi, const std::string& name);

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

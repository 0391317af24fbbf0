#include "metadata/json_access.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>

#include "core/field_names.hpp"

namespace filmgrain {

using nlohmann::json;

json parse_json_document(const uint8_t* data, std::size_t size, const std::string& what) {
    if (size > kMaxJsonBytes)
        throw Error(ErrorCode::kMalformedPayload, what + " has " + std::to_string(size) + " bytes (allowed at most " +
                                                   std::to_string(kMaxJsonBytes) + " for a JSON document)");
    // The depth is bounded while parsing: nlohmann's parser keeps its own stack, but every
    // consumer of the document (dump, comparison, the readers) recurses over it.
    const json::parser_callback_t bound_depth = [&](int depth, json::parse_event_t event, json&) {
        if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
            depth >= kMaxJsonDepth)
            throw Error(ErrorCode::kMalformedPayload, what + " nests JSON objects/arrays deeper than " +
                                                       std::to_string(kMaxJsonDepth) + " levels (allowed at most " +
                                                       std::to_string(kMaxJsonDepth) + ")");
        return true;
    };
    try {
        return json::parse(data, data + size, bound_depth);
    } catch (const json::exception& e) {
        throw Error(ErrorCode::kMalformedPayload, what + " is not valid JSON: " + e.what());
    }
}

namespace {
// Reads at most `limit` bytes, so that /dev/zero or a huge file fails fast.
std::vector<uint8_t> read_at_most(const std::string& path, std::size_t limit) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw Error(ErrorCode::kIo, "cannot open '" + path + "' for reading: " + std::strerror(errno));
    std::vector<uint8_t> out;
    uint8_t buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) {
        if (out.size() + n > limit)
            throw Error(ErrorCode::kInvalidParams, "'" + path + "' is larger than " + std::to_string(limit) +
                                                       " bytes, the most a JSON parameter file may have");
        out.insert(out.end(), buf, buf + n);
    }
    if (std::ferror(f.get())) throw Error(ErrorCode::kIo, "read error on '" + path + "': " + std::strerror(errno));
    return out;
}
}  // namespace

json read_json_file(const std::string& path) {
    const std::vector<uint8_t> bytes = read_at_most(path, kMaxJsonBytes);
    return parse_json_document(bytes.data(), bytes.size(), "'" + path + "'");
}

std::string json_brief(const json& v) {
    if (v.is_array()) return "an array of " + std::to_string(v.size()) + " entries";
    if (v.is_object()) return "an object of " + std::to_string(v.size()) + " keys";
    if (v.is_string()) {
        const std::string& s = v.get_ref<const std::string&>();
        return s.size() <= 40 ? json(s).dump() : json(s.substr(0, 40)).dump() + "...";
    }
    return v.dump();
}

long long json_to_integer(const json& v, long long lo, long long hi, const std::string& name) {
    if (v.is_boolean()) {
        const long long x = v.get<bool>() ? 1 : 0;
        if (x < lo || x > hi) throw Error(ErrorCode::kInvalidParams, out_of_range_message(name, x, lo, hi));
        return x;
    }
    if (v.is_number_unsigned()) {
        const unsigned long long u = v.get<unsigned long long>();
        if (u > (unsigned long long)std::numeric_limits<long long>::max() || (long long)u > hi)
            throw Error(ErrorCode::kInvalidParams, name + " = " + std::to_string(u) + " is out of range (allowed " +
                                                       std::to_string(lo) + ".." + std::to_string(hi) + ")");
        const long long x = (long long)u;
        if (x < lo) throw Error(ErrorCode::kInvalidParams, out_of_range_message(name, x, lo, hi));
        return x;
    }
    if (v.is_number_integer()) {
        const long long x = v.get<long long>();
        if (x < lo || x > hi) throw Error(ErrorCode::kInvalidParams, out_of_range_message(name, x, lo, hi));
        return x;
    }
    if (v.is_number_float()) {
        const double d = v.get<double>();
        // compared as doubles first: converting a double beyond long long is undefined
        if (std::isfinite(d) && d == std::floor(d)) {
            if (d < double(lo) || d > double(hi))
                throw Error(ErrorCode::kInvalidParams, name + " = " + v.dump() + " is out of range (allowed " +
                                                           std::to_string(lo) + ".." + std::to_string(hi) + ")");
            return (long long)d;
        }
    }
    throw Error(ErrorCode::kInvalidParams, name + " = " + json_brief(v) + " is not an integer");
}

int JsonObject::to_int(const nlohmann::json& v, long long lo, long long hi, const std::string& name) {
    return int(json_to_integer(v, std::max<long long>(lo, std::numeric_limits<int>::min()),
                               std::min<long long>(hi, std::numeric_limits<int>::max()), name));
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
        out.push_back(to_int((*a)[i], lo, hi, indexed(ctx_ + "." + key, i)));
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
    for (std::size_t k = 0; k < n; k++) out.push_back(to_int(a[k], lo, hi, indexed(name, k)));
    return out;
}

}  // namespace filmgrain

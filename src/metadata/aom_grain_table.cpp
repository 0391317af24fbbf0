#include "metadata/aom_grain_table.hpp"

#include <charconv>
#include <cstdio>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain {
namespace {

[[noreturn]] void fail(int line, const std::string& msg) {
    throw Error(ErrorCode::kMalformedPayload, "grain table line " + std::to_string(line) + ": " + msg);
}

struct Line {
    int number = 0;
    std::vector<std::string_view> tokens;
};

std::vector<Line> split_lines(std::string_view text) {
    std::vector<Line> lines;
    int number = 0;
    std::size_t pos = 0;
    while (pos <= text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view l = text.substr(pos, end - pos);
        ++number;
        Line line{number, {}};
        std::size_t i = 0;
        while (i < l.size()) {
            while (i < l.size() && (l[i] == ' ' || l[i] == '\t' || l[i] == '\r' || l[i] == '\v' || l[i] == '\f')) ++i;
            std::size_t s = i;
            while (i < l.size() && !(l[i] == ' ' || l[i] == '\t' || l[i] == '\r' || l[i] == '\v' || l[i] == '\f')) ++i;
            if (i > s) line.tokens.push_back(l.substr(s, i - s));
        }
        if (!line.tokens.empty()) lines.push_back(std::move(line));
        if (end == text.size()) break;
        pos = end + 1;
    }
    return lines;
}

// Reads the fields of one line in order, with range checks naming the field.
class FieldReader {
public:
    FieldReader(const Line& line, std::string_view keyword) : line_(line), keyword_(keyword) {}

    int64_t next(const std::string& field, int64_t lo, int64_t hi) {
        if (index_ >= line_.tokens.size())
            fail(line_.number, "'" + std::string(keyword_) + "' line ends before " + field);
        const std::string_view tok = line_.tokens[index_++];
        int64_t v = 0;
        const char* b = tok.data();
        const char* e = tok.data() + tok.size();
        if (b != e && *b == '+') ++b;
        auto [ptr, ec] = std::from_chars(b, e, v);
        if (ec != std::errc() || ptr != e || b == e)
            fail(line_.number, field + " = '" + std::string(tok) + "' is not an integer");
        if (v < lo || v > hi) fail(line_.number, out_of_range_message(field, v, lo, hi));
        return v;
    }
    int next_int(const std::string& field, int lo, int hi) { return static_cast<int>(next(field, lo, hi)); }

    void finish() const {
        if (index_ < line_.tokens.size())
            fail(line_.number, "unexpected extra value '" + std::string(line_.tokens[index_]) + "' on '" +
                                   std::string(keyword_) + "' line");
    }

private:
    const Line& line_;
    std::string_view keyword_;
    std::size_t index_ = 1;  // token 0 is the keyword
};

}  // namespace

std::optional<std::size_t> AomGrainTable::find_index(int64_t t) const {
    for (std::size_t i = 0; i < entries.size(); ++i)
        if (t >= entries[i].start_time && t < entries[i].end_time) return i;
    return std::nullopt;
}

const AomGrainTableEntry* AomGrainTable::find(int64_t t) const {
    const auto i = find_index(t);
    return i ? &entries[*i] : nullptr;
}

Av1FilmGrainParams AomGrainTable::resolved_params(std::size_t index) const {
    if (index >= entries.size())
        throw Error(ErrorCode::kInvalidArgument, "grain table entry index " + std::to_string(index) +
                                                     " is out of range (table has " +
                                                     std::to_string(entries.size()) + " entries)");
    const Av1FilmGrainParams& own = entries[index].params;
    if (own.update_grain || !own.apply_grain) return own;
    for (std::size_t i = index; i-- > 0;) {
        if (entries[i].params.update_grain && entries[i].params.apply_grain) {
            Av1FilmGrainParams p = entries[i].params;
            p.apply_grain = own.apply_grain;
            p.grain_seed = own.grain_seed;
            p.update_grain = 1;
            return p;
        }
    }
    throw Error(ErrorCode::kInvalidParams, "grain table entry " + std::to_string(index) +
                                               " has update_parameters = 0 but no earlier entry has parameters");
}

AomGrainTable parse_aom_grain_table(std::string_view text) {
    const std::vector<Line> lines = split_lines(text);
    if (lines.empty() || lines[0].tokens[0] != "filmgrn1")
        fail(lines.empty() ? 1 : lines[0].number, "missing 'filmgrn1' file magic");
    if (lines[0].tokens.size() != 1) fail(lines[0].number, "unexpected text after 'filmgrn1'");

    AomGrainTable table;
    std::size_t li = 1;
    auto expect = [&](const char* keyword, int after_line) -> const Line& {
        if (li >= lines.size()) fail(after_line + 1, std::string("expected '") + keyword + "' line, got end of file");
        const Line& l = lines[li];
        if (l.tokens[0] != keyword)
            fail(l.number, std::string("expected '") + keyword + "' line, got '" + std::string(l.tokens[0]) + "'");
        ++li;
        return l;
    };

    while (li < lines.size()) {
        const Line& el = expect("E", 0);
        AomGrainTableEntry entry;
        Av1FilmGrainParams& p = entry.params;
        FieldReader e(el, "E");
        entry.start_time = e.next("start_time", INT64_MIN, INT64_MAX);
        entry.end_time = e.next("end_time", INT64_MIN, INT64_MAX);
        p.apply_grain = e.next_int("apply_grain", 0, 1);
        p.grain_seed = e.next_int("random_seed", 0, 65535);
        p.update_grain = e.next_int("update_parameters", 0, 1);
        e.finish();

        if (p.update_grain) {
            const Line& pl = expect("p", el.number);
            FieldReader r(pl, "p");
            p.ar_coeff_lag = r.next_int("ar_coeff_lag", 0, 3);
            p.ar_coeff_shift_minus_6 = r.next_int("ar_coeff_shift", 6, 9) - 6;
            p.grain_scale_shift = r.next_int("grain_scale_shift", 0, 3);
            p.grain_scaling_minus_8 = r.next_int("scaling_shift", 8, 11) - 8;
            p.chroma_scaling_from_luma = r.next_int("chroma_scaling_from_luma", 0, 1);
            p.overlap_flag = r.next_int("overlap_flag", 0, 1);
            p.cb_mult = r.next_int("cb_mult", 0, 255);
            p.cb_luma_mult = r.next_int("cb_luma_mult", 0, 255);
            p.cb_offset = r.next_int("cb_offset", 0, 511);
            p.cr_mult = r.next_int("cr_mult", 0, 255);
            p.cr_luma_mult = r.next_int("cr_luma_mult", 0, 255);
            p.cr_offset = r.next_int("cr_offset", 0, 511);
            r.finish();

            auto read_points = [&](const char* keyword, const char* num_name, const char* value_name,
                                   const char* scaling_name, int max, int& num, int* values, int* scalings,
                                   int prev_line) {
                const Line& l = expect(keyword, prev_line);
                FieldReader s(l, keyword);
                num = s.next_int(num_name, 0, max);
                for (int i = 0; i < num; ++i) {
                    values[i] = s.next_int(indexed(value_name, i), 0, 255);
                    scalings[i] = s.next_int(indexed(scaling_name, i), 0, 255);
                }
                s.finish();
                return l.number;
            };
            int n = read_points("sY", "num_y_points", "point_y_value", "point_y_scaling", 14, p.num_y_points,
                                p.point_y_value.data(), p.point_y_scaling.data(), pl.number);
            n = read_points("sCb", "num_cb_points", "point_cb_value", "point_cb_scaling", 10, p.num_cb_points,
                            p.point_cb_value.data(), p.point_cb_scaling.data(), n);
            n = read_points("sCr", "num_cr_points", "point_cr_value", "point_cr_scaling", 10, p.num_cr_points,
                            p.point_cr_value.data(), p.point_cr_scaling.data(), n);

            const int npl = p.num_pos_luma();
            auto read_coeffs = [&](const char* keyword, const char* name, int count, int* out, int prev_line) {
                const Line& l = expect(keyword, prev_line);
                FieldReader c(l, keyword);
                for (int i = 0; i < count; ++i) out[i] = c.next_int(indexed(name, i), -128, 127) + 128;
                c.finish();
                return l.number;
            };
            n = read_coeffs("cY", "ar_coeffs_y", npl, p.ar_coeffs_y_plus_128.data(), n);
            // libaom always stores the chroma filters' luma coefficient, even
            // when num_y_points is 0 and the bitstream would not carry it.
            n = read_coeffs("cCb", "ar_coeffs_cb", npl + 1, p.ar_coeffs_cb_plus_128.data(), n);
            read_coeffs("cCr", "ar_coeffs_cr", npl + 1, p.ar_coeffs_cr_plus_128.data(), n);
        }
        table.entries.push_back(entry);
    }
    return table;
}

std::string format_aom_grain_table(const AomGrainTable& table) {
    std::string out = "filmgrn1\n";
    // appended piece by piece: no temporary strings (and none of the -Wrestrict false
    // positives GCC 12 gives for "literal" + std::string temporaries)
    auto add = [&out](const auto&... parts) { ((out += parts), ...); };
    auto num = [](long long v) { return std::to_string(v); };
    for (const auto& e : table.entries) {
        const Av1FilmGrainParams& p = e.params;
        add("E ", num(e.start_time), " ", num(e.end_time), " ", num(p.apply_grain), " ", num(p.grain_seed),
            " ", num(p.update_grain), "\n");
        if (!p.update_grain) continue;
        add("\tp ", num(p.ar_coeff_lag), " ", num(p.ar_coeff_shift_minus_6 + 6), " ", num(p.grain_scale_shift),
            " ", num(p.grain_scaling_minus_8 + 8), " ", num(p.chroma_scaling_from_luma), " ",
            num(p.overlap_flag), " ", num(p.cb_mult), " ", num(p.cb_luma_mult), " ", num(p.cb_offset), " ",
            num(p.cr_mult), " ", num(p.cr_luma_mult), " ", num(p.cr_offset), "\n");
        // libaom's layout: "sY n " then " v s" pairs (so a double space), and
        // "sCb n"/"sCr n" without the trailing space.
        add("\tsY ", num(p.num_y_points), " ");
        for (int i = 0; i < p.num_y_points && i < 14; ++i)
            add(" ", num(p.point_y_value[i]), " ", num(p.point_y_scaling[i]));
        add("\n\tsCb ", num(p.num_cb_points));
        for (int i = 0; i < p.num_cb_points && i < 10; ++i)
            add(" ", num(p.point_cb_value[i]), " ", num(p.point_cb_scaling[i]));
        add("\n\tsCr ", num(p.num_cr_points));
        for (int i = 0; i < p.num_cr_points && i < 10; ++i)
            add(" ", num(p.point_cr_value[i]), " ", num(p.point_cr_scaling[i]));
        const int lag = p.ar_coeff_lag < 0 ? 0 : (p.ar_coeff_lag > 3 ? 3 : p.ar_coeff_lag);
        const int npl = 2 * lag * (lag + 1);
        add("\n\tcY");
        for (int i = 0; i < npl; ++i) add(" ", num(p.ar_coeffs_y_plus_128[i] - 128));
        add("\n\tcCb");
        for (int i = 0; i <= npl; ++i) add(" ", num(p.ar_coeffs_cb_plus_128[i] - 128));
        add("\n\tcCr");
        for (int i = 0; i <= npl; ++i) add(" ", num(p.ar_coeffs_cr_plus_128[i] - 128));
        add("\n");
    }
    return out;
}

}  // namespace filmgrain

#include "verify/verification_report.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"
#include "io/output_file.hpp"
#include "report/png_file.hpp"

namespace filmgrain::verify {
namespace {

namespace fs = std::filesystem;

std::string printf_string(const char* format, ...) __attribute__((format(printf, 1, 2)));
// Formats are literals (checked by the attribute); the text is sized to fit, so that long
// ids, descriptions or paths are never cut.
std::string printf_string(const char* format, ...) {
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int length = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string out(std::size_t(std::max(length, 0)), '\0');
    if (length > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
    va_end(again);
    return out;
}

std::string plural(int64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

// ---- the block grid -------------------------------------------------------------------

struct WorstBlock {
    int bx = -1, by = -1;
    int32_t count = 0;
};

// The first block in raster order with the most differing samples.
WorstBlock worst_block(const PlaneComparison& plane) {
    WorstBlock w;
    for (std::size_t i = 0; i < plane.differing_per_block.size(); i++)
        if (plane.differing_per_block[i] > w.count && plane.blocks_x > 0)
            w = WorstBlock{int(i % std::size_t(plane.blocks_x)), int(i / std::size_t(plane.blocks_x)),
                           plane.differing_per_block[i]};
    return w;
}

int blocks_with_differences(const PlaneComparison& plane) {
    return int(std::count_if(plane.differing_per_block.begin(), plane.differing_per_block.end(),
                             [](int32_t n) { return n > 0; }));
}

// A grid that does not tile the picture would tint the wrong places: a caller's mistake.
void check_block_grid(const FrameView& decoded, const PlaneComparison& luma) {
    if (luma.differing_per_block.empty() && luma.differing == 0) return;  // nothing to tint
    const bool tiles = luma.block_width > 0 && luma.block_height > 0 && luma.blocks_x > 0 && luma.blocks_y > 0 &&
                       int64_t(luma.blocks_x) * luma.block_width >= decoded.width &&
                       int64_t(luma.blocks_x - 1) * luma.block_width < decoded.width &&
                       int64_t(luma.blocks_y) * luma.block_height >= decoded.height &&
                       int64_t(luma.blocks_y - 1) * luma.block_height < decoded.height &&
                       luma.differing_per_block.size() == std::size_t(luma.blocks_x) * std::size_t(luma.blocks_y);
    if (!tiles)
        throw Error(ErrorCode::kInvalidArgument,
                    printf_string("heat map: a %dx%d grid of %dx%d blocks (%zu counts) does not tile the %dx%d luma plane",
                                  luma.blocks_x, luma.blocks_y, luma.block_width, luma.block_height,
                                  luma.differing_per_block.size(), decoded.width, decoded.height));
}

// ---- heat map pictures ----------------------------------------------------------------

struct RgbImage {
    int width = 0, height = 0;
    std::vector<uint8_t> pixels;  // RGB, rows without padding
    uint8_t* at(int x, int y) { return &pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3]; }
};

// The smallest integer factor that brings `width` to kMaxWidth or less: integer, so that every
// output pixel covers the same whole luma samples and block edges stay sharp.
int downscale_factor(int width) { return std::max(1, (width + HeatMapWriter::kMaxWidth - 1) / HeatMapWriter::kMaxWidth); }

// The decoded luma as grey, each pixel the mean of its factor x factor box (the picture's
// edge boxes of the samples they hold), high bit depths shifted down to 8 bits.
RgbImage luma_as_grey(const FrameView& decoded, int factor) {
    const PlaneView& luma = decoded.planes[0];
    const int width = decoded.width, height = decoded.height;
    const bool wide = decoded.bit_depth > 8;
    const int shift = std::max(0, decoded.bit_depth - 8);
    RgbImage image;
    image.width = (width + factor - 1) / factor;
    image.height = (height + factor - 1) / factor;
    image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * 3);
    std::vector<uint32_t> sums(std::size_t(image.width));
    for (int oy = 0; oy < image.height; oy++) {
        std::fill(sums.begin(), sums.end(), 0u);
        const int y0 = oy * factor, y1 = std::min(height, y0 + factor);
        for (int y = y0; y < y1; y++)
            for (int x = 0; x < width; x++)
                sums[std::size_t(x / factor)] += wide ? luma.row<const uint16_t>(y)[x] : luma.row<const uint8_t>(y)[x];
        for (int ox = 0; ox < image.width; ox++) {
            const uint32_t count = uint32_t((std::min(width, ox * factor + factor) - ox * factor) * (y1 - y0));
            const uint32_t mean = (sums[std::size_t(ox)] + count / 2) / count;
            const auto grey = uint8_t(std::min<uint32_t>(255, mean >> shift));
            uint8_t* p = image.at(ox, oy);
            p[0] = p[1] = p[2] = grey;
        }
    }
    return image;
}

// Opacity of a block's tint: visible for a single differing sample, opaque when all differ.
double tint_alpha(double fraction_differing) { return 0.25 + 0.75 * std::clamp(fraction_differing, 0.0, 1.0); }

// The output pixels [begin, end) of the luma span [begin, end) scaled down by `factor`: the
// pixels whose first sample lies in it, so that neighbouring blocks never share a pixel;
// a block narrower than a pixel keeps one.
std::pair<int, int> scaled_span(int begin, int end, int factor, int limit) {
    int b = (begin + factor - 1) / factor, e = (end + factor - 1) / factor;
    if (e <= b) b = begin / factor, e = b + 1;
    return {std::min(b, limit - 1), std::min(e, limit)};
}

void tint_differing_blocks(RgbImage& image, const FrameView& decoded, const PlaneComparison& luma, int factor) {
    static constexpr uint8_t kOutline[3] = {140, 0, 0};
    for (int by = 0; by < luma.blocks_y; by++) {
        for (int bx = 0; bx < luma.blocks_x; bx++) {
            const int32_t count = luma.differing_per_block[std::size_t(by) * std::size_t(luma.blocks_x) + std::size_t(bx)];
            if (count <= 0) continue;
            const int x0 = bx * luma.block_width, x1 = std::min(decoded.width, x0 + luma.block_width);
            const int y0 = by * luma.block_height, y1 = std::min(decoded.height, y0 + luma.block_height);
            const double alpha = tint_alpha(double(count) / double((x1 - x0) * (y1 - y0)));
            const auto [ox0, ox1] = scaled_span(x0, x1, factor, image.width);
            const auto [oy0, oy1] = scaled_span(y0, y1, factor, image.height);
            // An outline on a block of two pixels or less would hide its tint.
            const bool outlined = ox1 - ox0 >= 3 && oy1 - oy0 >= 3;
            for (int oy = oy0; oy < oy1; oy++) {
                for (int ox = ox0; ox < ox1; ox++) {
                    uint8_t* p = image.at(ox, oy);
                    if (outlined && (ox == ox0 || ox == ox1 - 1 || oy == oy0 || oy == oy1 - 1)) {
                        std::copy(kOutline, kOutline + 3, p);
                        continue;
                    }
                    p[0] = uint8_t(std::lround(p[0] * (1 - alpha) + 255 * alpha));
                    p[1] = uint8_t(std::lround(p[1] * (1 - alpha)));
                    p[2] = uint8_t(std::lround(p[2] * (1 - alpha)));
                }
            }
        }
    }
}

std::string heat_map_name(int frame_index) { return printf_string("frame_%06d.png", frame_index); }

// ---- counts and ranges ----------------------------------------------------------------

int bit_exact_count(const VerificationResult& result) {
    return int(std::count_if(result.frames.begin(), result.frames.end(),
                             [](const FrameVerification& f) { return !f.missing && f.exact; }));
}

bool is_bit_exact(const FrameVerification& f) { return !f.missing && f.exact; }

// Runs of consecutive picture numbers: "0-44, 46, 48-50".
std::string index_ranges(const std::vector<int>& indices) {
    std::string out;
    for (std::size_t i = 0; i < indices.size();) {
        std::size_t j = i;
        while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) j++;
        if (!out.empty()) out += ", ";
        out += std::to_string(indices[i]);
        if (j > i) {
            out += '-';
            out += std::to_string(indices[j]);
        }
        i = j + 1;
    }
    return out;
}

std::vector<int> bit_exact_indices(const VerificationResult& result) {
    std::vector<int> indices;
    for (const FrameVerification& f : result.frames)
        if (is_bit_exact(f)) indices.push_back(f.index);
    std::sort(indices.begin(), indices.end());
    return indices;
}

// What the diagnosis says in one phrase: the best hypothesis, as the explanation when it
// reproduces some picture exactly, else as the closest; "" without a diagnosis.
// A hypothesis that would have changed bit-exact pictures is doubtful: said with it.
std::string diagnosis_phrase(const VerificationResult& result) {
    if (result.diagnosis.empty()) return "";
    const StreamDiagnosis& best = result.diagnosis.front();
    std::string phrase;
    if (best.frames_exact > 0) {
        phrase = printf_string("most likely: %s (%s) reproduces %d/%d exactly", best.id.c_str(), best.description.c_str(),
                               best.frames_exact, best.frames_tried);
    } else {
        // How much of the difference the closest mistake explains, against the samples the
        // reference itself leaves differing on the pictures tried: a closest mistake that
        // leaves most of them explains nothing (on Debian 12's FFmpeg 5.1, which applies H.274
        // grain its own way, the closest of every known mistake left 93 %), and the line says
        // so first.
        int64_t reference_differing = 0;
        for (const FrameVerification& f : result.frames)
            if (!f.hypotheses.empty() && f.comparison) reference_differing += f.comparison->differing();
        if (reference_differing > 0 && 2 * best.differing >= reference_differing) phrase = "no known mistake explains it; ";
        phrase += printf_string("closest: %s (%s) reproduces 0/%d exactly, %lld samples still differ", best.id.c_str(),
                                best.description.c_str(), best.frames_tried, static_cast<long long>(best.differing));
        if (reference_differing > 0)
            phrase += printf_string(" (%.1f %% of the %lld the reference leaves)",
                                    100.0 * double(best.differing) / double(reference_differing),
                                    static_cast<long long>(reference_differing));
    }
    if (best.frames_contradicted > 0)
        phrase += ", but would change " + plural(best.frames_contradicted, "bit-exact picture", "bit-exact pictures");
    return phrase;
}

std::string size_and_format(const VerificationResult& result) {
    std::string s;
    if (result.width > 0 && result.height > 0) s = std::to_string(result.width) + "x" + std::to_string(result.height);
    if (!result.pix_fmt.empty()) s += (s.empty() ? "" : " ") + result.pix_fmt;
    return s;
}

// ---- text -----------------------------------------------------------------------------

void print_plane_text(std::FILE* out, std::size_t plane_index, const PlaneComparison& plane) {
    const char* name = plane_name(plane_index);
    if (plane.exact()) {
        std::fprintf(out, "  %-3s identical\n", name);
        return;
    }
    std::fprintf(out, "  %-3s %lld of %lld samples differ (%.3f %%), max |diff| %d\n", name,
                 static_cast<long long>(plane.differing), static_cast<long long>(plane.samples), plane.differing_percent(),
                 plane.max_abs_difference);
    if (plane.first.x >= 0)
        std::fprintf(out, "      first at %s x %d y %d: expected %d, decoded %d\n", name, plane.first.x, plane.first.y,
                     plane.first.expected, plane.first.decoded);
    if (!plane.differing_per_block.empty()) {
        const WorstBlock worst = worst_block(plane);
        std::fprintf(out, "      %d of %d blocks (%dx%d) differ; worst block (%d, %d) with %d differing samples\n",
                     blocks_with_differences(plane), plane.blocks_x * plane.blocks_y, plane.block_width,
                     plane.block_height, worst.bx, worst.by, worst.count);
    }
}

void print_hypotheses_text(std::FILE* out, const std::vector<HypothesisOutcome>& hypotheses) {
    if (hypotheses.empty()) return;
    std::fprintf(out, "  known mistakes, best first:\n");
    for (const HypothesisOutcome& h : hypotheses) {
        if (h.exact)
            std::fprintf(out, "    %s (%s): reproduces the decoded picture exactly\n", h.id.c_str(), h.description.c_str());
        else
            std::fprintf(out, "    %s (%s): %lld samples still differ\n", h.id.c_str(), h.description.c_str(),
                         static_cast<long long>(h.differing));
    }
}

std::string above_bit_depth_text(const SampleAboveBitDepth& a) {
    return std::to_string(a.count) + (a.count == 1 ? " decoded sample is" : " decoded samples are") +
           " above the bit depth (first: " + plane_name(a.plane) + " " + std::to_string(a.value) + " at x " +
           std::to_string(a.x) + ", y " + std::to_string(a.y) +
           "): the decoder does not clip, or its output is not in the format named";
}

void print_mismatching_frame_text(std::FILE* out, const FrameVerification& f) {
    std::fprintf(out, "picture %d: differs from the reference", f.index);
    if (f.decoded_index >= 0 && f.decoded_index != f.index) std::fprintf(out, " (decoded picture %d)", f.decoded_index);
    if (!f.grain_expected) std::fprintf(out, "; the reference adds no grain to it");
    std::fprintf(out, "\n");
    if (f.comparison) {
        for (std::size_t p = 0; p < f.comparison->planes.size(); p++) print_plane_text(out, p, f.comparison->planes[p]);
    } else if (!f.expected_md5.empty() || !f.decoded_md5.empty()) {
        std::fprintf(out, "  expected md5 %s\n  decoded md5  %s\n", f.expected_md5.c_str(), f.decoded_md5.c_str());
    }
    if (f.above_bit_depth) std::fprintf(out, "  %s\n", above_bit_depth_text(*f.above_bit_depth).c_str());
    if (!f.heat_map.empty()) std::fprintf(out, "  heat map: %s\n", f.heat_map.c_str());
    print_hypotheses_text(out, f.hypotheses);
}

void print_diagnosis_text(std::FILE* out, const VerificationResult& result) {
    if (result.diagnosis.empty()) return;
    std::size_t id_width = 2;
    for (const StreamDiagnosis& d : result.diagnosis) id_width = std::max(id_width, d.id.size());
    std::fprintf(out, "\ndiagnosis over %s, best first:\n",
                 plural(result.mismatching(), "mismatching picture", "mismatching pictures").c_str());
    std::fprintf(out, "  %-*s  %11s  %12s  %10s  %s\n", int(id_width), "id", "exact/tried", "contradicted", "differing",
                 "description");
    for (std::size_t i = 0; i < result.diagnosis.size(); i++) {
        const StreamDiagnosis& d = result.diagnosis[i];
        const std::string ratio = std::to_string(d.frames_exact) + "/" + std::to_string(d.frames_tried);
        const char* mark = i > 0 ? "" : d.frames_exact > 0 ? "   <- most likely explanation" : "   <- closest";
        std::fprintf(out, "  %-*s  %11s  %12d  %10lld  %s%s\n", int(id_width), d.id.c_str(), ratio.c_str(),
                     d.frames_contradicted, static_cast<long long>(d.differing), d.description.c_str(), mark);
    }
}

// ---- JSON -----------------------------------------------------------------------------

using Json = nlohmann::ordered_json;

Json optional_string(const std::string& s) { return s.empty() ? Json(nullptr) : Json(s); }

// Rows of the block grid: differing_per_block[by][bx].
Json block_rows(const PlaneComparison& plane) {
    Json rows = Json::array();
    if (plane.exact() || plane.blocks_x <= 0) return rows;
    for (int by = 0; by < plane.blocks_y; by++) {
        const auto begin = plane.differing_per_block.begin() + std::ptrdiff_t(by) * plane.blocks_x;
        rows.push_back(Json(std::vector<int32_t>(begin, begin + plane.blocks_x)));
    }
    return rows;
}

Json plane_json(std::size_t plane_index, const PlaneComparison& plane) {
    Json first = nullptr;
    if (plane.first.x >= 0)
        first = Json{{"x", plane.first.x}, {"y", plane.first.y}, {"expected", plane.first.expected},
                     {"decoded", plane.first.decoded}};
    return Json{{"plane", plane_name(plane_index)},
                {"samples", plane.samples},
                {"differing", plane.differing},
                {"differing_percent", plane.differing_percent()},
                {"max_abs_difference", plane.max_abs_difference},
                {"first_difference", first},
                {"block_width", plane.block_width},
                {"block_height", plane.block_height},
                {"blocks_x", plane.blocks_x},
                {"blocks_y", plane.blocks_y},
                {"blocks_differing", blocks_with_differences(plane)},
                {"differing_per_block", block_rows(plane)}};
}

Json comparison_json(const PictureComparison& comparison) {
    Json planes = Json::array();
    for (std::size_t p = 0; p < comparison.planes.size(); p++) planes.push_back(plane_json(p, comparison.planes[p]));
    return Json{{"exact", comparison.exact()},
                {"differing", comparison.differing()},
                {"squared_error", comparison.squared_error},
                {"planes", planes}};
}

Json frame_json(const FrameVerification& f) {
    Json hypotheses = Json::array();
    for (const HypothesisOutcome& h : f.hypotheses)
        hypotheses.push_back(Json{{"id", h.id},
                                  {"description", h.description},
                                  {"exact", h.exact},
                                  {"differing", h.differing},
                                  {"squared_error", h.squared_error}});
    return Json{{"index", f.index},
                {"missing", f.missing},
                {"decoded_index", f.decoded_index},
                {"grain_expected", f.grain_expected},
                {"exact", f.exact},
                {"comparison", f.comparison ? comparison_json(*f.comparison) : Json(nullptr)},
                {"expected_md5", optional_string(f.expected_md5)},
                {"decoded_md5", optional_string(f.decoded_md5)},
                {"heat_map", optional_string(f.heat_map)},
                {"above_bit_depth", f.above_bit_depth ? Json{{"count", f.above_bit_depth->count},
                                                             {"plane", f.above_bit_depth->plane},
                                                             {"x", f.above_bit_depth->x},
                                                             {"y", f.above_bit_depth->y},
                                                             {"value", f.above_bit_depth->value}}
                                                      : Json(nullptr)},
                {"hypotheses", hypotheses}};
}

Json diagnosis_json(const StreamDiagnosis& d) {
    return Json{{"id", d.id},
                {"description", d.description},
                {"frames_tried", d.frames_tried},
                {"frames_exact", d.frames_exact},
                {"frames_contradicted", d.frames_contradicted},
                {"differing", d.differing},
                {"squared_error", d.squared_error}};
}

// ---- HTML -----------------------------------------------------------------------------

std::string html_escape(const std::string& s) {
    std::string o;
    o.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '<': o += "&lt;"; break;
            case '>': o += "&gt;"; break;
            case '&': o += "&amp;"; break;
            case '"': o += "&quot;"; break;
            case '\'': o += "&#39;"; break;
            default: o += c;
        }
    }
    return o;
}

// A relative file path as a URL path: characters a URL cannot hold as they are (spaces, '#',
// '?', '%', non-ASCII bytes) percent-encoded, so that a heat map directory named like any file
// still loads.
std::string url_path(const std::string& path) {
    static const char* const hex = "0123456789ABCDEF";
    std::string o;
    for (unsigned char c : path) {
        if (std::isalnum(c) || std::strchr("/-._~", c)) {
            o += char(c);
        } else {
            o += '%';
            o += hex[c >> 4];
            o += hex[c & 15];
        }
    }
    return o;
}

const char* kHtmlStyle =
    "body{font-family:sans-serif;max-width:1100px;margin:1em auto}"
    "table{border-collapse:collapse;margin:.5em 0}td,th{padding:2px 8px;text-align:left;border-bottom:1px solid #ddd}"
    "th{background:#f4f4f4}td.n{text-align:right}.ok{color:#070}.bad{color:#b00}.verdict{font-weight:bold}"
    "img{max-width:100%;border:1px solid #ccc}";

std::string plane_counts_html(const PictureComparison& c) {
    std::string s;
    for (std::size_t p = 0; p < c.planes.size(); p++)
        s += (p ? " / " : "") + std::string(plane_name(p)) + " " + std::to_string(c.planes[p].differing);
    return s;
}

std::string first_difference_html(const PictureComparison& c) {
    for (std::size_t p = 0; p < c.planes.size(); p++) {
        const FirstDifference& d = c.planes[p].first;
        if (d.x >= 0)
            return printf_string("%s (%d, %d): %d &rarr; %d", plane_name(p), d.x, d.y, d.expected, d.decoded);
    }
    return "";
}

std::string blocks_html(const PictureComparison& c) {
    std::string s;
    for (std::size_t p = 0; p < c.planes.size(); p++) {
        const PlaneComparison& plane = c.planes[p];
        if (plane.exact() || plane.differing_per_block.empty()) continue;
        const WorstBlock w = worst_block(plane);
        s += (s.empty() ? "" : "<br>") + printf_string("%s %d/%d, worst (%d, %d): %d", plane_name(p),
                                                       blocks_with_differences(plane), plane.blocks_x * plane.blocks_y,
                                                       w.bx, w.by, w.count);
    }
    return s;
}

std::string best_hypothesis_html(const FrameVerification& f) {
    if (f.hypotheses.empty()) return "";
    const HypothesisOutcome& h = f.hypotheses.front();
    return "<span title=\"" + html_escape(h.description) + "\">" + html_escape(h.id) + "</span>" +
           (h.exact ? " (exact)" : " (" + std::to_string(h.differing) + " differ)");
}

void frame_row_html(std::ostringstream& html, const FrameVerification& f) {
    html << "<tr><td class=\"n\">" << f.index << "</td>";
    if (f.missing) {
        html << "<td class=\"bad\">missing</td><td colspan=\"7\">no decoded picture for it</td></tr>\n";
        return;
    }
    html << "<td class=\"bad\">mismatching</td><td class=\"n\">" << f.decoded_index << "</td><td>"
         << (f.grain_expected ? "yes" : "no") << "</td>";
    if (f.comparison) {
        html << "<td>" << plane_counts_html(*f.comparison) << "</td><td>" << first_difference_html(*f.comparison)
             << "</td><td>" << blocks_html(*f.comparison) << "</td>";
    } else if (!f.expected_md5.empty() || !f.decoded_md5.empty()) {
        html << "<td colspan=\"3\">md5 expected " << html_escape(f.expected_md5) << ", decoded "
             << html_escape(f.decoded_md5) << "</td>";
    } else {
        html << "<td colspan=\"3\"></td>";
    }
    html << "<td>" << best_hypothesis_html(f);
    if (f.above_bit_depth) html << "<br>" << html_escape(above_bit_depth_text(*f.above_bit_depth));
    html << "</td><td>";
    if (!f.heat_map.empty()) html << "<a href=\"#heat-" << f.index << "\">heat map</a>";
    html << "</td></tr>\n";
}

void frames_table_html(std::ostringstream& html, const VerificationResult& result) {
    html << "<h2>Pictures</h2>\n<table><tr><th>picture</th><th>status</th><th>decoded as</th><th>grain</th>"
            "<th>differing samples</th><th>first difference (expected &rarr; decoded)</th>"
            "<th>blocks differing, worst</th><th>best known mistake</th><th></th></tr>\n";
    for (const FrameVerification& f : result.frames)
        if (!is_bit_exact(f)) frame_row_html(html, f);
    const std::vector<int> exact = bit_exact_indices(result);
    if (!exact.empty())
        html << "<tr><td>" << index_ranges(exact) << "</td><td class=\"ok\">bit-exact</td><td colspan=\"7\"></td></tr>\n";
    html << "</table>\n";
    if (result.extra_decoded > 0)
        html << "<p class=\"bad\">" << plural(result.extra_decoded, "decoded picture", "decoded pictures")
             << " past the stream's end matched no picture.</p>\n";
}

void diagnosis_table_html(std::ostringstream& html, const VerificationResult& result) {
    html << "<h2>Diagnosis</h2>\n";
    if (result.diagnosis.empty()) {
        html << "<p>" << (result.mismatching() ? "No known implementation mistake was tried." : "Nothing to diagnose.")
             << "</p>\n";
        return;
    }
    html << "<p>Known implementation mistakes re-synthesized on every mismatching picture, best first.</p>\n"
            "<table><tr><th>id</th><th>description</th><th>pictures reproduced / tried</th>"
            "<th>bit-exact pictures it would change</th><th>samples still differing</th><th></th></tr>\n";
    for (std::size_t i = 0; i < result.diagnosis.size(); i++) {
        const StreamDiagnosis& d = result.diagnosis[i];
        const char* mark = i > 0 ? "" : d.frames_exact > 0 ? "most likely explanation" : "closest";
        html << "<tr><td>" << html_escape(d.id) << "</td><td>" << html_escape(d.description) << "</td><td class=\"n\">"
             << d.frames_exact << " / " << d.frames_tried << "</td><td class=\"n\">" << d.frames_contradicted
             << "</td><td class=\"n\">" << d.differing << "</td><td>"
             << mark << "</td></tr>\n";
    }
    html << "</table>\n";
}

void heat_maps_html(std::ostringstream& html, const VerificationResult& result) {
    bool any = false;
    for (const FrameVerification& f : result.frames) {
        if (f.heat_map.empty()) continue;
        if (!any)
            html << "<h2>Heat maps</h2>\n<p>The decoded luma in grey; red blocks hold samples that differ from the "
                    "reference, the more opaque the larger their share of the block.</p>\n";
        any = true;
        html << "<h3 id=\"heat-" << f.index << "\">Picture " << f.index << "</h3>\n<img src=\""
             << html_escape(url_path(f.heat_map)) << "\" alt=\"differing blocks of picture " << f.index << "\">\n";
    }
}

void summary_html(std::ostringstream& html, const VerificationResult& result) {
    html << "<p class=\"verdict " << (result.all_exact() ? "ok" : "bad") << "\">"
         << html_escape(verification_summary_line(result)) << "</p>\n<table>\n";
    const auto row = [&](const char* name, const std::string& value) {
        if (!value.empty()) html << "<tr><th>" << name << "</th><td>" << html_escape(value) << "</td></tr>\n";
    };
    row("source", result.source_name);
    row("decoded", result.decoded_name);
    row("size", size_and_format(result));
    row("reference", result.reference);
    row("model", result.model);
    row("block grid", std::to_string(result.luma_block) + "x" + std::to_string(result.luma_block) + " luma samples");
    html << "</table>\n";
}

}  // namespace

// ---- public -----------------------------------------------------------------------------

HeatMapWriter::HeatMapWriter(std::string directory) : directory_(std::move(directory)) {
    std::error_code ec;
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_))
        throw Error(ErrorCode::kIo, "cannot create the heat map directory '" + directory_ + "'" +
                                        (ec ? ": " + ec.message() : std::string()));
}

std::string HeatMapWriter::write(int frame_index, const FrameView& decoded, const PlaneComparison& luma) const {
    if (decoded.width <= 0 || decoded.height <= 0 || !decoded.planes[0].data)
        throw Error(ErrorCode::kInvalidArgument, "heat map of picture " + std::to_string(frame_index) + ": no luma plane");
    check_block_grid(decoded, luma);
    const int factor = downscale_factor(decoded.width);
    RgbImage image = luma_as_grey(decoded, factor);
    if (!luma.differing_per_block.empty()) tint_differing_blocks(image, decoded, luma, factor);
    const std::string name = heat_map_name(frame_index);
    report::write_png_rgb((fs::path(directory_) / name).string(), image.width, image.height, image.pixels.data(),
                          std::ptrdiff_t(image.width) * 3);
    return name;
}

std::string verification_summary_line(const VerificationResult& result) {
    const int frames = int(result.frames.size());
    if (frames == 0 && result.extra_decoded == 0) return "verify: no frames compared";
    if (result.all_exact() && frames > 0) return "verify: " + plural(frames, "frame", "frames") + ", all bit-exact";
    std::string line = printf_string("verify: %s, %d bit-exact, %d mismatching, %d missing",
                                     plural(frames, "frame", "frames").c_str(), bit_exact_count(result),
                                     result.mismatching(), result.missing());
    if (result.extra_decoded > 0) line += ", " + plural(result.extra_decoded, "extra decoded picture", "extra decoded pictures");
    if (result.mismatching() > 0) {
        const std::string diagnosis = diagnosis_phrase(result);
        if (!diagnosis.empty()) line += "; " + diagnosis;
    }
    return line;
}

void print_verification_text(std::FILE* out, const VerificationResult& result, int max_frames_listed) {
    std::fprintf(out, "filmgrain verify\n");
    const auto field = [&](const char* name, const std::string& value) {
        if (!value.empty()) std::fprintf(out, "  %-10s %s\n", name, value.c_str());
    };
    field("source", result.source_name);
    field("decoded", result.decoded_name);
    field("size", size_and_format(result));
    field("reference", result.reference);
    field("model", result.model);
    std::fprintf(out, "\n");

    const std::vector<int> exact = bit_exact_indices(result);
    if (exact.empty())
        std::fprintf(out, "no picture bit-exact\n");
    else
        std::fprintf(out, "%s %s: bit-exact\n", exact.size() == 1 ? "picture" : "pictures", index_ranges(exact).c_str());
    int listed = 0, unlisted = 0;
    for (const FrameVerification& f : result.frames) {
        if (is_bit_exact(f)) continue;
        if (max_frames_listed >= 0 && listed >= max_frames_listed) {
            unlisted++;
            continue;
        }
        listed++;
        if (f.missing)
            std::fprintf(out, "picture %d: missing from the decoded output\n", f.index);
        else
            print_mismatching_frame_text(out, f);
    }
    if (unlisted > 0)
        std::fprintf(out, "... and %s not listed (see the JSON or HTML report)\n",
                     plural(unlisted, "more mismatching or missing picture", "more mismatching or missing pictures").c_str());
    if (result.extra_decoded > 0)
        std::fprintf(out, "%s past the stream's end matched no picture\n",
                     plural(result.extra_decoded, "decoded picture", "decoded pictures").c_str());
    print_diagnosis_text(out, result);
}

std::string verification_json(const VerificationResult& result) {
    Json frames = Json::array();
    for (const FrameVerification& f : result.frames) frames.push_back(frame_json(f));
    Json diagnosis = Json::array();
    for (const StreamDiagnosis& d : result.diagnosis) diagnosis.push_back(diagnosis_json(d));
    const Json doc{{"model", result.model},
                   {"reference", result.reference},
                   {"source", result.source_name},
                   {"decoded", result.decoded_name},
                   {"width", result.width},
                   {"height", result.height},
                   {"pix_fmt", result.pix_fmt},
                   {"luma_block", result.luma_block},
                   {"frames", frames},
                   {"extra_decoded", result.extra_decoded},
                   {"diagnosis", diagnosis},
                   {"summary", Json{{"frames", int(result.frames.size())},
                                    {"exact", bit_exact_count(result)},
                                    {"mismatching", result.mismatching()},
                                    {"missing", result.missing()},
                                    {"all_exact", result.all_exact()}}}};
    return doc.dump(2);
}

void write_verification_html(const std::string& html_path, const VerificationResult& result) {
    std::ostringstream html;
    const std::string title = "filmgrain verify: " + (result.decoded_name.empty() ? "decoded pictures" : result.decoded_name);
    html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(title) << "</title>\n<style>"
         << kHtmlStyle << "</style></head><body>\n<h1>" << html_escape(title) << "</h1>\n";
    summary_html(html, result);
    diagnosis_table_html(html, result);
    frames_table_html(html, result);
    heat_maps_html(html, result);
    html << "</body></html>\n";

    OutputFile out(html_path);
    const std::string page = html.str();
    if (std::fwrite(page.data(), 1, page.size(), out.stream()) != page.size())
        throw Error(ErrorCode::kIo, "cannot write '" + html_path + "'");
    out.commit();
}

}  // namespace filmgrain::verify

#include "analysis/analysis_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <opencv2/imgproc.hpp>

#include "analysis/plane_image.hpp"
#include "analysis/png_file.hpp"
#include "filmgrain/error.hpp"
#include "io/output_file.hpp"

namespace filmgrain::analysis {
namespace {

std::string html_escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '<') o += "&lt;";
        else if (c == '>') o += "&gt;";
        else if (c == '&') o += "&amp;";
        else o += c;
    }
    return o;
}

// One panel per plane: observations (grey dots), the fitted curve (blue), the model (red).
cv::Mat plot_scaling(const ReportInput& in) {
    const int pw = 720, ph = 300, ml = 50, mb = 30, mt = 20;
    const double to8 = 1.0 / double(1 << (in.bit_depth - 8));
    cv::Mat canvas(ph * int(in.planes.size()), pw, CV_8UC3, cv::Scalar(255, 255, 255));
    for (std::size_t k = 0; k < in.planes.size(); k++) {
        const ReportPlane& p = in.planes[k];
        cv::Mat panel = canvas(cv::Rect(0, int(k) * ph, pw, ph));
        double ymax = 1.0;
        for (int i = 0; i < 256; i++) ymax = std::max(ymax, p.curve.level[i] * to8 * 1.3);
        for (const auto& b : p.observations) ymax = std::max(ymax, std::min(double(b.sigma) * to8, ymax * 1.5));
        auto X = [&](double i) { return int(ml + (pw - ml - 10) * i / 255.0); };
        auto Y = [&](double v) { return int(ph - mb - (ph - mb - mt) * std::min(v / ymax, 1.0)); };
        cv::rectangle(panel, cv::Point(ml, mt), cv::Point(pw - 10, ph - mb), cv::Scalar(0, 0, 0));
        for (int t = 0; t <= 255; t += 32) {
            cv::line(panel, cv::Point(X(t), ph - mb), cv::Point(X(t), ph - mb + 4), cv::Scalar(0, 0, 0));
            cv::putText(panel, std::to_string(t), cv::Point(X(t) - 8, ph - 8), cv::FONT_HERSHEY_PLAIN, 0.9, cv::Scalar(0, 0, 0));
        }
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.1f", ymax);
        cv::putText(panel, buf, cv::Point(4, mt + 10), cv::FONT_HERSHEY_PLAIN, 0.9, cv::Scalar(0, 0, 0));
        cv::putText(panel, p.name + ": grain std (8-bit units) vs intensity", cv::Point(ml + 6, mt + 14),
                    cv::FONT_HERSHEY_PLAIN, 1.0, cv::Scalar(0, 0, 0));
        const std::size_t step = std::max<std::size_t>(1, p.observations.size() / 4000);
        for (std::size_t i = 0; i < p.observations.size(); i += step)
            cv::circle(panel, cv::Point(X(p.observations[i].intensity8), Y(p.observations[i].sigma * to8)), 1,
                       cv::Scalar(160, 160, 160), cv::FILLED);
        if (p.curve.valid())
            for (int i = 1; i < 256; i++)
                cv::line(panel, cv::Point(X(i - 1), Y(p.curve.level[i - 1] * to8)), cv::Point(X(i), Y(p.curve.level[i] * to8)),
                         cv::Scalar(200, 80, 0), 1, cv::LINE_AA);
        for (const auto& iv : p.intervals) {
            cv::line(panel, cv::Point(X(iv.lower), Y(iv.level * to8)), cv::Point(X(iv.upper), Y(iv.level * to8)),
                     cv::Scalar(0, 0, 220), 2);
            cv::line(panel, cv::Point(X(iv.lower), ph - mb), cv::Point(X(iv.lower), mt), cv::Scalar(220, 220, 255));
        }
        for (std::size_t i = 0; i < p.points.size(); i++) {
            const cv::Point pt(X(p.points[i].value), Y(p.points[i].level * to8));
            cv::circle(panel, pt, 4, cv::Scalar(0, 0, 220), 2);
            if (i > 0)
                cv::line(panel, cv::Point(X(p.points[i - 1].value), Y(p.points[i - 1].level * to8)), pt,
                         cv::Scalar(0, 0, 220), 2, cv::LINE_AA);
        }
    }
    return canvas;
}

// log10 of the averaged DCT power per plane, 64x64 shown at 4x, DC at the top left.
cv::Mat plot_spectrum(const ReportInput& in) {
    std::vector<cv::Mat> tiles;
    for (const auto& p : in.planes) {
        cv::Mat tile(256 + 20, 256, CV_8UC3, cv::Scalar(255, 255, 255));
        if (!p.power.empty() && cv::norm(p.power) > 0) {
            cv::Mat lp;
            cv::log(p.power + 1e-12, lp);
            double mn, mx;
            cv::minMaxLoc(lp(cv::Rect(1, 1, lp.cols - 1, lp.rows - 1)), &mn, &mx);
            mn = std::max(mn, mx - std::log(1e4));
            cv::Mat n8;
            lp.convertTo(n8, CV_8U, 255.0 / std::max(mx - mn, 1e-9), -mn * 255.0 / std::max(mx - mn, 1e-9));
            cv::Mat big, colour;
            cv::resize(n8, big, cv::Size(256, 256), 0, 0, cv::INTER_NEAREST);
            cv::applyColorMap(big, colour, cv::COLORMAP_VIRIDIS);
            colour.copyTo(tile(cv::Rect(0, 20, 256, 256)));
        }
        cv::putText(tile, p.name + " DCT power (log)", cv::Point(4, 15), cv::FONT_HERSHEY_PLAIN, 1.0, cv::Scalar(0, 0, 0));
        tiles.push_back(tile);
    }
    cv::Mat out;
    cv::hconcat(tiles, out);
    return out;
}

cv::Mat plot_crops(const ReportInput& in) {
    const cv::Mat* imgs[3] = {&in.source, &in.denoised, &in.resynthesized};
    const char* labels[3] = {"source", "denoised", "re-synthesized"};
    std::vector<cv::Mat> tiles;
    for (int i = 0; i < 3; i++) {
        if (imgs[i]->empty()) continue;
        cv::Mat g8 = to_8bit(*imgs[i], in.bit_depth), bgr;
        cv::cvtColor(g8, bgr, cv::COLOR_GRAY2BGR);
        cv::Mat tile(bgr.rows + 20, bgr.cols + 4, CV_8UC3, cv::Scalar(255, 255, 255));
        bgr.copyTo(tile(cv::Rect(2, 20, bgr.cols, bgr.rows)));
        cv::putText(tile, labels[i], cv::Point(4, 15), cv::FONT_HERSHEY_PLAIN, 1.0, cv::Scalar(0, 0, 0));
        tiles.push_back(tile);
    }
    if (tiles.empty()) return cv::Mat(20, 20, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::Mat out;
    cv::hconcat(tiles, out);
    return out;
}

}  // namespace

void write_analysis_report(const std::string& html_path, const ReportInput& in) {
    namespace fs = std::filesystem;
    const fs::path html(html_path);
    const fs::path dir = html.has_parent_path() ? html.parent_path() : fs::path(".");
    const std::string stem = html.stem().string();
    const std::string scaling = stem + "-scaling.png", spectrum = stem + "-spectrum.png", crop = stem + "-crop.png";
    write_png_file((dir / scaling).string(), plot_scaling(in));
    write_png_file((dir / spectrum).string(), plot_spectrum(in));
    write_png_file((dir / crop).string(), plot_crops(in));
    OutputFile out(html_path);
    {
        std::ofstream f(out.write_path());
        if (!f) throw Error(ErrorCode::kIo, "cannot write '" + html_path + "'");
        f << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << html_escape(in.title)
          << "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:1em auto}"
             "pre{background:#f4f4f4;padding:.5em;overflow:auto;max-height:30em}td,th{padding:2px 8px;text-align:left}</style>"
             "</head><body>\n<h1>"
          << html_escape(in.title) << "</h1>\n<p>" << html_escape(in.input_description) << "</p>\n";
        if (!in.notes.empty()) {
            f << "<ul>\n";
            for (const auto& n : in.notes) f << "<li>" << html_escape(n) << "</li>\n";
            f << "</ul>\n";
        }
        f << "<h2>Model per component</h2>\n<table><tr><th>component</th><th>grain</th><th>model</th></tr>\n";
        for (const auto& p : in.planes)
            f << "<tr><td>" << html_escape(p.name) << "</td><td>" << (p.present ? "yes" : "no") << "</td><td>"
              << html_escape(p.summary) << "</td></tr>\n";
        f << "</table>\n<h2>Scaling function</h2>\n<p>Grey: block observations (flat blocks); blue: the fitted level "
             "curve; red: the signalled model (FGC intervals or AV1 points) as grain levels.</p>\n<img src=\""
          << scaling << "\" alt=\"scaling function\">\n<h2>Grain spectrum</h2>\n<p>Averaged 64x64 DCT power of flat grain "
                        "blocks; horizontal frequency to the right, vertical downwards.</p>\n<img src=\""
          << spectrum << "\" alt=\"grain spectrum\">\n<h2>Crop</h2>\n<img src=\"" << crop
          << "\" alt=\"source, denoised and re-synthesized crop\">\n<h2>Parameters</h2>\n<pre>"
          << html_escape(in.parameters_text) << "</pre>\n</body></html>\n";
        if (!f) throw Error(ErrorCode::kIo, "cannot write '" + html_path + "'");
    }
    out.commit();
}

}  // namespace filmgrain::analysis

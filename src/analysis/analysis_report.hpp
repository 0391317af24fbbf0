// The HTML report of an analysis: the scaling function with its observations and the
// fitted intervals / points, the grain's averaged DCT power spectrum, and a crop of the
// source, the denoised picture and the picture re-synthesized from the estimate, as PNG
// images written next to the HTML file.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "analysis/block_observations.hpp"
#include "analysis/scaling_fit.hpp"

namespace filmgrain::analysis {

struct ReportPlane {
    std::string name;  // "Y", "Cb", "Cr"
    bool present = false;
    LevelCurve curve;
    std::vector<BlockSample> observations;
    std::vector<LevelInterval> intervals;  // FGC: realized level per interval (sample units)
    std::vector<LevelPoint> points;        // AV1: scaling points as levels (sample units)
    cv::Mat power;                         // mean 64x64 DCT power (CV_64F), may be empty
    std::string summary;                   // chosen order, errors, cut-offs / lag
};

struct ReportInput {
    std::string title;
    std::string input_description;
    std::string parameters_text;  // the JSON written
    std::vector<std::string> notes;
    int bit_depth = 8;
    std::vector<ReportPlane> planes;
    // Luma crops (CV_32F sample units), any may be empty.
    cv::Mat source, denoised, resynthesized;
};

// Writes `html_path` and <stem>-scaling.png, <stem>-spectrum.png, <stem>-crop.png beside it.
// Throws Error(kIo) when a file cannot be written.
void write_analysis_report(const std::string& html_path, const ReportInput& in);

}  // namespace filmgrain::analysis

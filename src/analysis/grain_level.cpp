#include "analysis/grain_level.hpp"

#include <cmath>

#include "analysis/block_observations.hpp"
#include "analysis/plane_image.hpp"

namespace filmgrain::analysis {

double measure_grain_level(const cv::Mat& grain) {
    double ss = 0;
    int n = 0;
    for (int by = 0; by + kLevelBlock <= grain.rows; by += kLevelBlock)
        for (int bx = 0; bx + kLevelBlock <= grain.cols; bx += kLevelBlock) {
            const double s = detrended_sigma(grain(cv::Rect(bx, by, kLevelBlock, kLevelBlock)), nullptr);
            ss += s * s;
            n++;
        }
    return n ? std::sqrt(ss / n) : 0.0;
}

double measure_grain_level(const FrameView& grainy, const FrameView& clean, int p) {
    return measure_grain_level(plane_to_float(grainy, p) - plane_to_float(clean, p));
}

}  // namespace filmgrain::analysis

#include "analysis/grain_level.hpp"

#include <cmath>

#include "analysis/block_observations.hpp"
#include "analysis/plane_image.hpp"

namespace filmgrain::analysis {

double measure_grain_level(const cv::Mat& grain, int block) {
    double ss = 0;
    int n = 0;
    for (int by = 0; by + block <= grain.rows; by += block)
        for (int bx = 0; bx + block <= grain.cols; bx += block) {
            const double s = detrended_sigma(grain(cv::Rect(bx, by, block, block)), nullptr);
            ss += s * s;
            n++;
        }
    return n ? std::sqrt(ss / n) : 0.0;
}

double measure_grain_level(const FrameView& grainy, const FrameView& clean, int p, int block) {
    return measure_grain_level(plane_to_float(grainy, p) - plane_to_float(clean, p), block);
}

}  // namespace filmgrain::analysis

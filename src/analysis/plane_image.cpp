#include "analysis/plane_image.hpp"

#include <algorithm>
#include <cmath>

namespace filmgrain::analysis {

cv::Mat plane_to_float(const FrameView& frame, int p) {
    const PlaneView& pv = frame.planes[p];
    cv::Mat out(pv.height, pv.width, CV_32F);
    for (int y = 0; y < pv.height; y++) {
        float* o = out.ptr<float>(y);
        if (frame.bit_depth > 8) {
            const uint16_t* r = pv.row<uint16_t>(y);
            for (int x = 0; x < pv.width; x++) o[x] = float(r[x]);
        } else {
            const uint8_t* r = pv.row<uint8_t>(y);
            for (int x = 0; x < pv.width; x++) o[x] = float(r[x]);
        }
    }
    return out;
}

void float_to_plane(const cv::Mat& image, const FrameView& frame, int p) {
    const PlaneView& pv = frame.planes[p];
    const float maxv = float((1 << frame.bit_depth) - 1);
    for (int y = 0; y < pv.height; y++) {
        const float* in = image.ptr<float>(y);
        for (int x = 0; x < pv.width; x++) {
            const float v = std::clamp(std::nearbyint(in[x]), 0.0f, maxv);
            if (frame.bit_depth > 8)
                pv.row<uint16_t>(y)[x] = uint16_t(v);
            else
                pv.row<uint8_t>(y)[x] = uint8_t(v);
        }
    }
}

cv::Mat to_8bit(const cv::Mat& image, int bit_depth) {
    cv::Mat out;
    image.convertTo(out, CV_8U, 1.0 / double(1 << (bit_depth - 8)));
    return out;
}

}  // namespace filmgrain::analysis

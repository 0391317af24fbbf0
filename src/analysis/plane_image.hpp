// Conversions between the library's plane views and OpenCV float images, which every
// analysis stage works on (sample units of the plane's own bit depth, not normalized).
#pragma once
#include <opencv2/core.hpp>

#include "filmgrain/frame.hpp"

namespace filmgrain::analysis {

// CV_32F copy of plane p of a frame.
cv::Mat plane_to_float(const FrameView& frame, int p);

// Writes a float image (rounded, clipped to the bit depth) into plane p of a frame.
void float_to_plane(const cv::Mat& image, const FrameView& frame, int p);

// CV_8U picture of a float plane scaled to 8 bits (for edge detection and report images).
cv::Mat to_8bit(const cv::Mat& image, int bit_depth);

}  // namespace filmgrain::analysis

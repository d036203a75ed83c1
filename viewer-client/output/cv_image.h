#pragma once
// Conversions between reenact::Image (RGB order) and OpenCV matrices (BGR order).

#include <opencv2/core.hpp>

#include "common/image/image.h"

namespace reenact::viewer {

// A deep copy as CV_8UC3 in BGR order (from 3 channels) or CV_8UC1 (from 1 channel).
// Precondition: 1 or 3 channels.
cv::Mat ToBgrMat(const ImageRgb8& image);

// A deep copy of a CV_8UC3 BGR or CV_8UC1 matrix as an RGB (or grey) image.
ImageRgb8 FromBgrMat(const cv::Mat& mat);

}  // namespace reenact::viewer

#include "viewer-client/output/cv_image.h"

#include <cstring>

#include <opencv2/imgproc.hpp>

namespace reenact::viewer {

cv::Mat ToBgrMat(const ImageRgb8& image) {
  REENACT_CHECK(image.channels == 1 || image.channels == 3, "image must be grey or RGB");
  const int type = image.channels == 3 ? CV_8UC3 : CV_8UC1;
  const cv::Mat view(image.height, image.width, type, const_cast<uint8_t*>(image.data.data()));
  cv::Mat out;
  if (image.channels == 3) {
    cv::cvtColor(view, out, cv::COLOR_RGB2BGR);
  } else {
    out = view.clone();
  }
  return out;
}

ImageRgb8 FromBgrMat(const cv::Mat& mat) {
  REENACT_CHECK(mat.type() == CV_8UC3 || mat.type() == CV_8UC1, "matrix must be 8-bit BGR or grey");
  cv::Mat rgb;
  if (mat.channels() == 3) {
    cv::cvtColor(mat, rgb, cv::COLOR_BGR2RGB);
  } else {
    rgb = mat.isContinuous() ? mat : mat.clone();
  }
  ImageRgb8 out(rgb.cols, rgb.rows, rgb.channels());
  for (int y = 0; y < rgb.rows; ++y) {
    std::memcpy(&out.at(0, y), rgb.ptr(y), static_cast<size_t>(rgb.cols) * rgb.channels());
  }
  return out;
}

}  // namespace reenact::viewer

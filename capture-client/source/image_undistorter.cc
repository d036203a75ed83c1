#include "capture-client/source/image_undistorter.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace reenact::capture {

struct ImageUndistorter::Maps {
  cv::Mat fixed1, fixed2;  // fixed-point maps for the bilinear colour remap (faster)
  cv::Mat x, y;            // float maps for the nearest-neighbour depth remap (rounds)
};

ImageUndistorter::ImageUndistorter(const PinholeCamera& distorted)
    : distorted_(distorted), undistorted_(distorted), maps_(std::make_unique<Maps>()) {
  distorted.Check();
  undistorted_.distortion = Distortion{};
  const cv::Matx33d k(distorted.fx, 0, distorted.cx, 0, distorted.fy, distorted.cy, 0, 0, 1);
  const Distortion& d = distorted.distortion;
  const cv::Matx<double, 1, 5> coefficients(d.k1, d.k2, d.p1, d.p2, d.k3);
  cv::initUndistortRectifyMap(k, coefficients, cv::Matx33d::eye(), k,
                              cv::Size(distorted.width, distorted.height), CV_32FC1, maps_->x,
                              maps_->y);
  cv::convertMaps(maps_->x, maps_->y, maps_->fixed1, maps_->fixed2, CV_16SC2);
}

ImageUndistorter::~ImageUndistorter() = default;
ImageUndistorter::ImageUndistorter(ImageUndistorter&&) noexcept = default;
ImageUndistorter& ImageUndistorter::operator=(ImageUndistorter&&) noexcept = default;

ImageRgb8 ImageUndistorter::Undistort(const ImageRgb8& image) const {
  REENACT_CHECK(
      image.width == distorted_.width && image.height == distorted_.height && image.channels == 3,
      "Undistort: image must be 3-channel and of the camera's size");
  ImageRgb8 out(image.width, image.height, 3);
  const cv::Mat in(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.data.data()));
  cv::Mat dst(out.height, out.width, CV_8UC3, out.data.data());
  cv::remap(in, dst, maps_->fixed1, maps_->fixed2, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar::all(0));
  return out;
}

ImageDepthMm ImageUndistorter::UndistortDepth(const ImageDepthMm& depth) const {
  REENACT_CHECK(
      depth.width == distorted_.width && depth.height == distorted_.height && depth.channels == 1,
      "UndistortDepth: depth must be 1-channel and of the camera's size");
  ImageDepthMm out(depth.width, depth.height, 1);
  const cv::Mat in(depth.height, depth.width, CV_16UC1, const_cast<uint16_t*>(depth.data.data()));
  cv::Mat dst(out.height, out.width, CV_16UC1, out.data.data());
  cv::remap(in, dst, maps_->x, maps_->y, cv::INTER_NEAREST, cv::BORDER_CONSTANT,
            cv::Scalar::all(0));
  return out;
}

}  // namespace reenact::capture

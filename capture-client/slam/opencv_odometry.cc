#include "capture-client/slam/opencv_odometry.h"

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"

namespace reenact::capture::slam {

void OpenCvOdometryOptions::Check() const {
  REENACT_CHECK(min_depth_m >= 0 && max_depth_m > min_depth_m && std::isfinite(max_depth_m),
                "need 0 <= min_depth_m < max_depth_m");
  REENACT_CHECK(mask_dilation_px >= 0, "mask_dilation_px must be >= 0");
}

OpenCvOdometry::OpenCvOdometry(const PinholeCamera& camera, double depth_scale_m,
                               const OpenCvOdometryOptions& options)
    : camera_(camera), depth_scale_m_(depth_scale_m), options_(options) {
  camera.Check();
  options.Check();
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
  cv::Mat k = (cv::Mat_<double>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  if (!camera.distortion.IsZero()) {
    const Distortion& d = camera.distortion;
    const cv::Mat coefficients = (cv::Mat_<double>(1, 5) << d.k1, d.k2, d.p1, d.p2, d.k3);
    cv::initUndistortRectifyMap(k, coefficients, cv::Mat(), k, {camera.width, camera.height},
                                CV_32FC1, map_x_, map_y_);
  }
  cv::Mat k32;
  k.convertTo(k32, CV_32F);
  if (options.method == OdometryMethod::kRgbd) {
    odometry_ = cv::rgbd::RgbdOdometry::create(k32, static_cast<float>(options.min_depth_m),
                                               static_cast<float>(options.max_depth_m));
  } else {
    odometry_ = cv::rgbd::FastICPOdometry::create(k32);
  }
}

cv::Ptr<cv::rgbd::OdometryFrame> OpenCvOdometry::Prepare(const cv::Mat& gray,
                                                         const ImageDepthMm& depth,
                                                         const ImageGray8* person_mask) const {
  REENACT_CHECK(gray.type() == CV_8UC1 && gray.cols == camera_.width && gray.rows == camera_.height,
                "gray image must be CV_8UC1 of the camera's size");
  REENACT_CHECK(
      depth.width == camera_.width && depth.height == camera_.height && depth.channels == 1,
      "depth must be registered to the camera");
  const cv::Mat raw_depth(depth.height, depth.width, CV_16UC1,
                          const_cast<uint16_t*>(depth.data.data()));
  cv::Mat metres;
  raw_depth.convertTo(metres, CV_32F, depth_scale_m_);
  // Readings in range (FastICP has no range of its own); the rest become NaN.
  cv::Mat mask =
      (raw_depth > 0) & (metres >= options_.min_depth_m) & (metres <= options_.max_depth_m);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  metres.setTo(nan, mask == 0);
  if (person_mask != nullptr && !person_mask->empty()) {
    REENACT_CHECK(person_mask->width == camera_.width && person_mask->height == camera_.height &&
                      person_mask->channels == 1,
                  "person mask must be one channel of the camera's size");
    const cv::Mat person(person_mask->height, person_mask->width, CV_8UC1,
                         const_cast<uint8_t*>(person_mask->data.data()));
    cv::Mat grown = person > 127;
    if (options_.mask_dilation_px > 0) {
      const int k = 2 * options_.mask_dilation_px + 1;
      cv::dilate(grown, grown, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
    }
    mask.setTo(0, grown);
  }
  cv::Mat image = gray;
  if (!map_x_.empty()) {
    cv::Mat undistorted_image, undistorted_depth, undistorted_mask;
    cv::remap(gray, undistorted_image, map_x_, map_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    cv::remap(metres, undistorted_depth, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT,
              cv::Scalar(nan));
    cv::remap(mask, undistorted_mask, map_x_, map_y_, cv::INTER_NEAREST, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    image = undistorted_image;
    metres = undistorted_depth;
    mask = undistorted_mask;
  }
  return cv::rgbd::OdometryFrame::create(image.clone(), metres, mask);
}

std::optional<Eigen::Isometry3d> OpenCvOdometry::Compute(cv::Ptr<cv::rgbd::OdometryFrame>& previous,
                                                         cv::Ptr<cv::rgbd::OdometryFrame>& current,
                                                         const Eigen::Isometry3d& initial) const {
  REENACT_CHECK(previous && current, "frames must be prepared");
  cv::Mat init(4, 4, CV_64F);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) init.at<double>(r, c) = initial.matrix()(r, c);
  cv::Mat rt;
  bool ok = false;
  try {
    ok = odometry_->compute(previous, current, rt, init);
  } catch (const cv::Exception&) {
    ok = false;  // OpenCV throws on frames without enough valid pixels
  }
  if (!ok || rt.empty()) return std::nullopt;
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = rt.at<double>(r, c);
  if (!m.allFinite()) return std::nullopt;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = m.topLeftCorner<3, 3>();
  out.translation() = m.topRightCorner<3, 1>();
  return out;
}

}  // namespace reenact::capture::slam

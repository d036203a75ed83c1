#pragma once
// Frame-to-frame RGB-D odometry from OpenCV's rgbd module (opencv_contrib): the dense
// photometric RgbdOdometry (Steinbruecker, Sturm and Cremers 2011) or the point-to-plane
// FastICPOdometry (KinectFusion's ICP). The SLAM tracker falls back to it when features are
// scarce; `reenact-eval slam` runs both as baselines.
//
// OpenCV's odometries take an undistorted pinhole camera. When the camera has distortion,
// colour is undistorted bilinearly and depth with nearest-neighbour sampling onto the same
// intrinsics before use. Depth is converted to float metres; 0 (no reading) becomes NaN,
// OpenCV's "no reading". Pixels of the person mask (grown by mask_dilation_px) are left out,
// so the moving subject does not drive the estimate.
//
// Result: current_from_previous (x_current = T * x_previous, OpenCV's Rt with the previous
// frame as source), or nullopt when OpenCV reports failure (too few correspondences, or a
// motion beyond its limits of 0.15 m and 15 degrees between frames).

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/rgbd.hpp>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture::slam {

enum class OdometryMethod {
  kRgbd,     // cv::rgbd::RgbdOdometry
  kFastIcp,  // cv::rgbd::FastICPOdometry
};

struct OpenCvOdometryOptions {
  OdometryMethod method = OdometryMethod::kRgbd;
  double min_depth_m = 0.3;  // depth used, metres; 0 <= min < max
  double max_depth_m = 4.0;
  int mask_dilation_px = 15;  // >= 0

  void Check() const;
};

class OpenCvOdometry {
 public:
  // Precondition (CHECK): valid camera and options, depth_scale_m > 0.
  OpenCvOdometry(const PinholeCamera& camera, double depth_scale_m,
                 const OpenCvOdometryOptions& options = {});

  // A frame in OpenCV's form (undistorted, float depth, mask). gray: CV_8UC1 of the camera's
  // size; person_mask may be null. Preconditions (CHECK): sizes agree.
  cv::Ptr<cv::rgbd::OdometryFrame> Prepare(const cv::Mat& gray, const ImageDepthMm& depth,
                                           const ImageGray8* person_mask) const;

  // current_from_previous, starting from `initial` (identity when unknown). The frames'
  // caches (pyramids, normals) are filled on first use and kept, so a frame can serve as
  // current now and as previous next time.
  std::optional<Eigen::Isometry3d> Compute(
      cv::Ptr<cv::rgbd::OdometryFrame>& previous, cv::Ptr<cv::rgbd::OdometryFrame>& current,
      const Eigen::Isometry3d& initial = Eigen::Isometry3d::Identity()) const;

 private:
  PinholeCamera camera_;
  double depth_scale_m_;
  OpenCvOdometryOptions options_;
  cv::Mat map_x_, map_y_;  // undistortion maps (empty without distortion)
  cv::Ptr<cv::rgbd::Odometry> odometry_;
};

}  // namespace reenact::capture::slam

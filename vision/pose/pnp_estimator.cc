#include "vision/pose/pnp_estimator.h"

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <optional>

#include "common/geometry/rotation.h"

namespace reenact::vision {
namespace {

std::optional<Eigen::Isometry3d> ToPose(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat r64, t64;
  rvec.convertTo(r64, CV_64F);
  tvec.convertTo(t64, CV_64F);
  const Eigen::Vector3d omega(r64.at<double>(0), r64.at<double>(1), r64.at<double>(2));
  const Eigen::Vector3d t(t64.at<double>(0), t64.at<double>(1), t64.at<double>(2));
  if (!omega.allFinite() || !t.allFinite()) return std::nullopt;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = ExpSo3(omega);
  pose.translation() = t;
  return pose;
}

}  // namespace

std::vector<PnpEstimator::Model> PnpEstimator::Estimate(const std::vector<Sample>& samples) const {
  std::vector<Model> models;
  if (samples.size() < static_cast<size_t>(kMinSampleSize)) return models;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  object.reserve(samples.size());
  image.reserve(samples.size());
  for (const Sample& s : samples) {
    if (!s.point_in_world.allFinite() || !s.normalized.allFinite()) return models;
    object.emplace_back(s.point_in_world.x(), s.point_in_world.y(), s.point_in_world.z());
    image.emplace_back(s.normalized.x(), s.normalized.y());
  }
  const cv::Mat identity = cv::Mat::eye(3, 3, CV_64F);
  try {
    if (samples.size() == 3) {
      std::vector<cv::Mat> rvecs, tvecs;
      cv::solveP3P(object, image, identity, cv::noArray(), rvecs, tvecs, cv::SOLVEPNP_AP3P);
      for (size_t i = 0; i < rvecs.size(); ++i) {
        if (auto pose = ToPose(rvecs[i], tvecs[i])) models.push_back(*pose);
      }
    } else {
      cv::Mat rvec, tvec;
      if (cv::solvePnP(object, image, identity, cv::noArray(), rvec, tvec, false,
                       cv::SOLVEPNP_SQPNP)) {
        if (auto pose = ToPose(rvec, tvec)) models.push_back(*pose);
      }
    }
  } catch (const cv::Exception&) {
    // A degenerate configuration OpenCV refuses (e.g. coincident points): no model.
    models.clear();
  }
  return models;
}

std::vector<double> PnpEstimator::Residuals(const Model& sensor_from_world,
                                            const std::vector<Sample>& samples) const {
  std::vector<double> out;
  out.reserve(samples.size());
  for (const Sample& s : samples) {
    const Eigen::Vector3d p = sensor_from_world * s.point_in_world;
    if (!(p.z() > 1e-6)) {
      out.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    const double du = fx * (p.x() / p.z() - s.normalized.x());
    const double dv = fy * (p.y() / p.z() - s.normalized.y());
    out.push_back(std::sqrt(du * du + dv * dv));
  }
  return out;
}

}  // namespace reenact::vision

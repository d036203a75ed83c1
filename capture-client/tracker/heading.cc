#include "capture-client/tracker/heading.h"

#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

std::optional<Eigen::Vector3d> Horizontal(const Eigen::Vector3d& v, const Eigen::Vector3d& up) {
  const Eigen::Vector3d h = v - v.dot(up) * up;
  if (!(h.norm() > 1e-6)) return std::nullopt;
  return h.normalized();
}

}  // namespace

std::vector<Eigen::Vector3d> CandidateHeadings(const Eigen::Vector3d& up,
                                               const Eigen::Vector3d& toward_sensor, int count) {
  REENACT_CHECK(count >= 1, "count must be >= 1");
  std::vector<Eigen::Vector3d> out;
  if (!(up.norm() > 1e-9)) return out;
  const Eigen::Vector3d u = up.normalized();
  const auto toward = Horizontal(toward_sensor, u);
  if (!toward) return out;
  for (int k = 0; k < count; ++k) {
    const double a = 2 * std::numbers::pi * k / count;
    out.push_back(std::cos(a) * *toward + std::sin(a) * u.cross(*toward));
  }
  return out;
}

ArticulatedPose UprightPose(const ArticulatedBody& body, const Eigen::Vector3d& ground,
                            const Eigen::Vector3d& up, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d u = up.norm() > 1e-9 ? up.normalized() : Eigen::Vector3d::UnitZ();
  Eigen::Vector3d f = Horizontal(forward, u).value_or(Eigen::Vector3d::Zero());
  if (f.isZero()) f = Horizontal(Eigen::Vector3d::UnitX(), u).value_or(Eigen::Vector3d::UnitY());
  const BodyShape& sh = body.shape();
  ArticulatedPose pose;
  pose.root_rotation.col(0) = f;
  pose.root_rotation.col(1) = u.cross(f);
  pose.root_rotation.col(2) = u;
  pose.root_translation = ground + (sh.ankle_height + sh.shin + sh.thigh + sh.hip_drop) * u;
  return pose;
}

std::optional<Eigen::Vector3d> HorizontalForward(const ArticulatedPose& pose,
                                                 const Eigen::Vector3d& up) {
  return Horizontal(pose.root_rotation.col(0), up);
}

ArticulatedPose TurnedTo(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                         const Eigen::Vector3d& forward) {
  const auto from = HorizontalForward(pose, up);
  const auto to = Horizontal(forward, up);
  if (!from || !to) return pose;
  const double angle = std::atan2(up.dot(from->cross(*to)), from->dot(*to));
  ArticulatedPose out = pose;
  out.root_rotation = ExpRotation(angle * up.normalized()) * pose.root_rotation;
  return out;
}

TravelDirection::TravelDirection(int window, double min_distance_m)
    : window_(window), min_distance_m_(min_distance_m) {
  REENACT_CHECK(window >= 2, "window must be >= 2");
  REENACT_CHECK(min_distance_m > 0, "min_distance_m must be > 0");
}

void TravelDirection::Add(const Eigen::Vector3d& root) {
  path_.push_back(root);
  while (static_cast<int>(path_.size()) > window_) path_.pop_front();
}

std::optional<Eigen::Vector3d> TravelDirection::Direction(const Eigen::Vector3d& up) const {
  if (path_.size() < 2 || !(up.norm() > 1e-9)) return std::nullopt;
  const Eigen::Vector3d u = up.normalized();
  Eigen::Vector3d d = path_.back() - path_.front();
  d -= d.dot(u) * u;
  if (!(d.norm() >= min_distance_m_)) return std::nullopt;
  return d.normalized();
}

}  // namespace reenact::capture

#include "capture-client/tracker/heading.h"

#include <algorithm>
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

bool FacesAwayFrom(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                   const Eigen::Vector3d& sensor) {
  if (!(up.norm() > 1e-9)) return false;
  const auto forward = HorizontalForward(pose, up);
  const auto toward = Horizontal(sensor - pose.root_translation, up);
  return forward && toward && forward->dot(*toward) < 0;
}

ArticulatedPose TurnedBy(const ArticulatedPose& pose, const Eigen::Vector3d& up, double angle_rad) {
  ArticulatedPose out = pose;
  if (!(up.norm() > 1e-9)) return out;
  out.root_rotation = ExpRotation(angle_rad * up.normalized()) * pose.root_rotation;
  return out;
}

ArticulatedPose TurnedTo(const ArticulatedPose& pose, const Eigen::Vector3d& up,
                         const Eigen::Vector3d& forward) {
  const auto from = HorizontalForward(pose, up);
  const auto to = Horizontal(forward, up);
  if (!from || !to) return pose;
  return TurnedBy(pose, up, std::atan2(up.dot(from->cross(*to)), from->dot(*to)));
}

void TravelOptions::Check() const {
  REENACT_CHECK(window_frames >= 2 && max_window_frames >= window_frames,
                "travel window_frames must be >= 2 and max_window_frames >= window_frames");
  REENACT_CHECK(min_distance_m > 0, "travel min_distance_m must be > 0");
  REENACT_CHECK(min_half_share >= 0 && min_half_share <= 0.5, "travel min_half_share in [0, 0.5]");
}

TravelDirection::TravelDirection(const TravelOptions& options) : options_(options) {
  options.Check();
}

void TravelDirection::Add(const Eigen::Vector3d& root) {
  path_.push_back(root);
  while (static_cast<int>(path_.size()) > options_.max_window_frames) path_.pop_front();
}

std::optional<Eigen::Vector3d> TravelDirection::Direction(const Eigen::Vector3d& up) const {
  if (path_.size() < 2 || !(up.norm() > 1e-9)) return std::nullopt;
  const Eigen::Vector3d u = up.normalized();
  const auto across = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    const Eigen::Vector3d d = to - from;
    return Eigen::Vector3d(d - d.dot(u) * u);
  };
  const int last = static_cast<int>(path_.size()) - 1;
  int first = std::max(0, last + 1 - options_.window_frames);
  while (first > 0 && across(path_[first], path_[last]).norm() < options_.min_distance_m) --first;
  const Eigen::Vector3d d = across(path_[first], path_[last]);
  const double distance = d.norm();
  if (!(distance >= options_.min_distance_m)) return std::nullopt;
  const Eigen::Vector3d& middle = path_[(first + last + 1) / 2];
  const double shorter_half =
      std::min(across(path_[first], middle).norm(), across(middle, path_[last]).norm());
  if (shorter_half < options_.min_half_share * distance) return std::nullopt;
  return d / distance;
}

}  // namespace reenact::capture

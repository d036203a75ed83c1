#include "capture-client/source/timed_trajectory.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

std::optional<Eigen::Isometry3d> InterpolatePose(const std::vector<TimedPose>& samples, double t,
                                                 double max_gap_s) {
  REENACT_CHECK(std::is_sorted(samples.begin(), samples.end(),
                               [](const TimedPose& a, const TimedPose& b) {
                                 return a.timestamp_s < b.timestamp_s;
                               }),
                "pose samples must be in ascending time order");
  if (!std::isfinite(t) || samples.empty() || t < samples.front().timestamp_s ||
      t > samples.back().timestamp_s)
    return std::nullopt;
  // b: the first sample later than t (exists unless t is the last sample's time).
  const auto b =
      std::upper_bound(samples.begin(), samples.end(), t,
                       [](double time, const TimedPose& s) { return time < s.timestamp_s; });
  const auto a = std::prev(b);
  const auto first_at_a =
      std::lower_bound(samples.begin(), b, a->timestamp_s,
                       [](const TimedPose& s, double time) { return s.timestamp_s < time; });
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (a->timestamp_s == t || b == samples.end()) {
    pose.linear() = first_at_a->rotation.normalized().toRotationMatrix();
    pose.translation() = first_at_a->position;
    return pose;
  }
  const double gap = b->timestamp_s - a->timestamp_s;
  if (gap > max_gap_s) return std::nullopt;
  const double s = (t - a->timestamp_s) / gap;
  pose.translation() = (1 - s) * a->position + s * b->position;
  pose.linear() = a->rotation.normalized().slerp(s, b->rotation.normalized()).toRotationMatrix();
  return pose;
}

}  // namespace reenact::capture

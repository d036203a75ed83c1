#include "tests/eval/joint_error_table.h"

#include <algorithm>
#include <cmath>

namespace reenact::eval {
namespace {

bool Usable(const Skeleton& s, Joint j) { return s.Has(j) && s[j].allFinite(); }

}  // namespace

std::optional<Eigen::Matrix3d> BodyFrame(const Skeleton& t) {
  for (Joint j : {Joint::kNeck, Joint::kWaist, Joint::kLeftShoulder, Joint::kRightShoulder,
                  Joint::kLeftHip, Joint::kRightHip})
    if (!Usable(t, j)) return std::nullopt;
  const Eigen::Vector3d up = t[Joint::kNeck] - t[Joint::kWaist];
  if (!(up.norm() > 1e-9)) return std::nullopt;
  const Eigen::Vector3d z = up.normalized();
  Eigen::Vector3d x = (t[Joint::kRightShoulder] - t[Joint::kLeftShoulder]) +
                      (t[Joint::kRightHip] - t[Joint::kLeftHip]);
  x -= x.dot(z) * z;
  if (!(x.norm() > 1e-9)) return std::nullopt;
  x.normalize();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return r;
}

bool JointErrorTable::Add(const Skeleton& estimate, const Skeleton& truth) {
  const std::optional<Eigen::Matrix3d> frame = BodyFrame(truth);
  if (!frame) return false;
  for (int j = 0; j < kJointCount; ++j) {
    const Joint joint = static_cast<Joint>(j);
    if (!Usable(estimate, joint) || !Usable(truth, joint)) continue;
    const Eigen::Vector3d e = frame->transpose() * (estimate[joint] - truth[joint]);
    Sum& s = sums_[j];
    ++s.n;
    s.norm += e.norm();
    const Eigen::Vector3d delta = e - s.mean;
    s.mean += delta / s.n;
    s.m2 += delta.dot(e - s.mean);
  }
  return true;
}

std::array<JointErrorStats, kJointCount> JointErrorTable::Stats() const {
  std::array<JointErrorStats, kJointCount> out;
  for (int j = 0; j < kJointCount; ++j) {
    const Sum& s = sums_[j];
    JointErrorStats& o = out[j];
    o.frames = s.n;
    if (s.n == 0) continue;
    o.mean_cm = 100 * s.norm / s.n;
    o.bias_cm = 100 * s.mean;
    o.bias_norm_cm = 100 * s.mean.norm();
    o.spread_cm = 100 * std::sqrt(std::max(0.0, s.m2 / s.n));
  }
  return out;
}

}  // namespace reenact::eval

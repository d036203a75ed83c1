#include "tests/eval/calibration_aligned_error.h"

#include <Eigen/Geometry>
#include <cmath>

#include "tests/eval/joint_error_table.h"

namespace reenact::eval {
namespace {

// The limb joint's parent, or nullopt for a trunk joint: the near end of the limb part
// (upper arm, forearm, thigh, shin) whose far end j is.
std::optional<Joint> LimbParent(Joint j) {
  for (int p = Index(BodyPart::kLeftUpperArm); p < kBodyPartCount; ++p) {
    const auto [a, b] = PartJoints(static_cast<BodyPart>(p));
    if (b == j) return a;
  }
  return std::nullopt;
}

constexpr double kMinBoneM = 1e-3;
const double kUpCos = -std::cos(1e-6);  // rest . d below this: d points up the spine

// SegmentFrame with the skeleton's body frame already found.
std::optional<Eigen::Matrix3d> SegmentFrameIn(const Skeleton& s, Joint j,
                                              const Eigen::Matrix3d& body) {
  if (!s.Has(j) || !s[j].allFinite()) return std::nullopt;
  const std::optional<Joint> parent = LimbParent(j);
  if (!parent) return body;
  if (!s.Has(*parent) || !s[*parent].allFinite()) return std::nullopt;
  const Eigen::Vector3d bone = s[j] - s[*parent];
  if (!(bone.norm() >= kMinBoneM)) return std::nullopt;
  const Eigen::Vector3d rest = -body.col(2);
  const Eigen::Vector3d d = bone.normalized();
  const Eigen::Matrix3d r = rest.dot(d) < kUpCos
                                ? Eigen::AngleAxisd(M_PI, body.col(1)).toRotationMatrix()
                                : Eigen::Quaterniond::FromTwoVectors(rest, d).toRotationMatrix();
  return r * body;
}

}  // namespace

std::optional<Eigen::Matrix3d> SegmentFrame(const Skeleton& s, Joint j) {
  const std::optional<Eigen::Matrix3d> body = BodyFrame(s);
  if (!body) return std::nullopt;
  return SegmentFrameIn(s, j, *body);
}

std::optional<CalibrationAlignment> CalibrationAlignment::FromCalibrationFrame(
    const Skeleton& estimate, const Skeleton& truth) {
  const std::optional<Eigen::Matrix3d> body = BodyFrame(estimate);
  if (!body) return std::nullopt;
  CalibrationAlignment a;
  for (int i = 0; i < kJointCount; ++i) {
    const Joint j = static_cast<Joint>(i);
    const std::optional<Eigen::Matrix3d> frame = SegmentFrameIn(estimate, j, *body);
    if (!frame || !truth.Has(j) || !truth[j].allFinite()) return std::nullopt;
    a.offset_[i] = frame->transpose() * (truth[j] - estimate[j]);
  }
  return a;
}

Skeleton CalibrationAlignment::Aligned(const Skeleton& estimate) const {
  Skeleton out = estimate;
  const std::optional<Eigen::Matrix3d> body = BodyFrame(estimate);
  if (!body) return out;
  for (int i = 0; i < kJointCount; ++i)
    if (const auto frame = SegmentFrameIn(estimate, static_cast<Joint>(i), *body))
      out.position[i] = estimate.position[i] + *frame * offset_[i];
  return out;
}

}  // namespace reenact::eval

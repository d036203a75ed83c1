#include "common/model/representative_frame.h"

#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact {
namespace {

std::optional<double> AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const double nu = u.norm(), nv = v.norm();
  if (!(nu > 1e-9) || !(nv > 1e-9)) return std::nullopt;
  // atan2 of |u x v| and u.v is accurate near 0 and 180 degrees, unlike acos.
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / std::numbers::pi;
}

}  // namespace

void RepresentativeFrameOptions::Check() const {
  REENACT_CHECK(std::isfinite(lambda) && lambda >= 0, "lambda must be finite and >= 0");
}

std::optional<double> RepresentativeScore(const Skeleton& s,
                                          const RepresentativeFrameOptions& options) {
  options.Check();
  for (Joint j : {Joint::kNeck, Joint::kWaist, Joint::kLeftShoulder, Joint::kLeftHand,
                  Joint::kRightShoulder, Joint::kRightHand, Joint::kLeftHip, Joint::kRightHip,
                  Joint::kLeftKnee, Joint::kRightKnee, Joint::kLeftFoot, Joint::kRightFoot})
    if (!s.Has(j)) return std::nullopt;

  const Eigen::Vector3d torso = s[Joint::kWaist] - s[Joint::kNeck];
  double score = 0;
  for (auto [shoulder, hand] : {std::pair{Joint::kLeftShoulder, Joint::kLeftHand},
                                std::pair{Joint::kRightShoulder, Joint::kRightHand}}) {
    const Eigen::Vector3d arm = s[hand] - s[shoulder];
    const std::optional<double> theta = AngleDeg(torso, arm);
    if (!theta) return std::nullopt;
    score += *theta * std::abs(arm.x()) / arm.norm();
  }
  const Eigen::Vector3d hip_axis = s[Joint::kLeftHip] - s[Joint::kRightHip];
  if (!(hip_axis.norm() > 1e-9)) return std::nullopt;
  const bool uncrossed = (s[Joint::kLeftKnee] - s[Joint::kRightKnee]).dot(hip_axis) > 0 &&
                         (s[Joint::kLeftFoot] - s[Joint::kRightFoot]).dot(hip_axis) > 0;
  return score + (uncrossed ? options.lambda : 0.0);
}

std::optional<int> SelectRepresentativeFrame(std::span<const Skeleton> skeletons,
                                             std::span<const bool> usable,
                                             const RepresentativeFrameOptions& options) {
  REENACT_CHECK(usable.empty() || usable.size() == skeletons.size(),
                "usable must be empty or one flag per skeleton");
  std::optional<int> best;
  double best_score = 0;
  for (size_t n = 0; n < skeletons.size(); ++n) {
    if (!usable.empty() && !usable[n]) continue;
    const std::optional<double> f = RepresentativeScore(skeletons[n], options);
    if (f && (!best || *f > best_score)) {
      best = static_cast<int>(n);
      best_score = *f;
    }
  }
  return best;
}

}  // namespace reenact

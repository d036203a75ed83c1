#include "tests/eval/body_heading.h"

#include <cmath>
#include <numbers>

namespace reenact::eval {
namespace {

constexpr double kDegPerRad = 180 / std::numbers::pi;

// The forward's component across up, unit; nullopt within 1 degree of up.
std::optional<Eigen::Vector3d> OnFloor(const Eigen::Vector3d& forward, const Eigen::Vector3d& up) {
  const Eigen::Vector3d across = forward - forward.dot(up) * up;
  if (across.norm() < std::sin(1.0 / kDegPerRad)) return std::nullopt;
  return across.normalized();
}

}  // namespace

std::optional<Eigen::Vector3d> BodyForward(const Skeleton& s) {
  const Eigen::Vector3d left = s[Joint::kLeftShoulder] - s[Joint::kRightShoulder];
  const Eigen::Vector3d spine = s[Joint::kNeck] - s[Joint::kWaist];
  const Eigen::Vector3d forward = left.cross(spine);
  // Relative to the lengths: parallel lines give a cross product small against their product.
  if (forward.norm() <= 1e-6 * left.norm() * spine.norm() || forward.norm() < 1e-12)
    return std::nullopt;
  return forward.normalized();
}

std::optional<double> HeadingErrorDeg(const Skeleton& tracked, const Skeleton& truth,
                                      const Eigen::Vector3d& up) {
  if (up.norm() < 1e-12) return std::nullopt;
  const Eigen::Vector3d u = up.normalized();
  const auto a = BodyForward(tracked), b = BodyForward(truth);
  if (!a || !b) return std::nullopt;
  const auto fa = OnFloor(*a, u), fb = OnFloor(*b, u);
  if (!fa || !fb) return std::nullopt;
  return std::atan2(fa->cross(*fb).norm(), fa->dot(*fb)) * kDegPerRad;
}

}  // namespace reenact::eval

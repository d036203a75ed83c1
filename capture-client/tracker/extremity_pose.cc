#include "capture-client/tracker/extremity_pose.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace reenact::capture {
namespace {

using S = BodySegment;

int I(S s) { return static_cast<int>(s); }

bool IsArm(Limb limb) { return limb == Limb::kLeftArm || limb == Limb::kRightArm; }

double Reach(const BodyShape& shape, Limb limb) {
  return IsArm(limb) ? shape.forearm + shape.forearm_radius : shape.shin + shape.ankle_height;
}

// v made perpendicular to n (unit), unit; nullopt-like zero when (nearly) parallel.
Eigen::Vector3d Perpendicular(const Eigen::Vector3d& v, const Eigen::Vector3d& n) {
  const Eigen::Vector3d p = v - v.dot(n) * n;
  return p.norm() > 1e-6 ? Eigen::Vector3d(p.normalized()) : Eigen::Vector3d::Zero();
}

}  // namespace

Eigen::Vector3d LimbEnd(const ArticulatedBody& body, const PosedBody3& posed, Limb limb) {
  return posed.sensor_from_segment[I(LimbLower(limb))] *
         Eigen::Vector3d(0, 0, -Reach(body.shape(), limb));
}

ArticulatedPose ReachLimb(const ArticulatedBody& body, const ArticulatedPose& pose, Limb limb,
                          const Eigen::Vector3d& target, const JointLimits& limits) {
  if (!target.allFinite()) return pose;
  const S upper = LimbUpper(limb), lower = LimbLower(limb);
  const PosedBody3 posed = body.Pose(pose);
  const Eigen::Matrix3d parent = posed.sensor_from_segment[SegmentParent(upper)].linear();
  const Eigen::Vector3d joint = posed.sensor_from_segment[I(upper)].translation();
  const double a = body.offset(lower).norm(), b = Reach(body.shape(), limb);
  const Eigen::Vector3d forward = parent.col(0), down = -parent.col(2);
  const Eigen::Vector3d to = target - joint;
  const double d_raw = to.norm();
  const Eigen::Vector3d n = d_raw > 1e-9 ? Eigen::Vector3d(to / d_raw) : down;
  const double d = std::clamp(d_raw, std::abs(a - b) + 1e-3, a + b);
  // The elbow behind the arm, the knee in front of the leg.
  Eigen::Vector3d m = Perpendicular(IsArm(limb) ? -forward : forward, n);
  if (m.isZero()) m = Perpendicular(down, n);
  if (m.isZero()) m = Perpendicular(parent.col(1), n);
  const double cos_alpha = std::clamp((a * a + d * d - b * b) / (2 * a * d), -1.0, 1.0);
  const double alpha = std::acos(cos_alpha);
  const Eigen::Vector3d u = std::cos(alpha) * n + std::sin(alpha) * m;
  const Eigen::Vector3d l = ((joint + d * n) - (joint + a * u)).normalized();
  const double theta = std::acos(std::clamp(u.dot(l), -1.0, 1.0));
  // The lower bone is cos(theta) u + sin(theta) x_u (forearm) or - sin(theta) x_u (shin).
  const double sign = IsArm(limb) ? 1.0 : -1.0;
  Eigen::Vector3d x = Perpendicular(sign * (l - std::cos(theta) * u), u);
  if (x.isZero()) x = Perpendicular(-sign * m, u);
  if (x.isZero()) x = Perpendicular(forward, u);
  if (x.isZero()) x = Perpendicular(parent.col(1), u);
  const Eigen::Vector3d z = -u;
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  ArticulatedPose out = pose;
  out.local[I(upper)] = parent.transpose() * r;
  out.hinge_angle[I(lower)] = theta;
  ArticulatedBody::Clamp(&out, limits);
  return out;
}

ArticulatedPose PoseFromExtremities(const ArticulatedBody& body, const ArticulatedPose& start,
                                    const GeodesicExtremities& extremities,
                                    const JointLimits& limits, int* placed, double min_offset_m) {
  ArticulatedPose pose = start;
  int count = 0;
  const PosedBody3 posed = body.Pose(start);
  const Eigen::Vector3d left = posed.sensor_from_segment[I(S::kPelvis)].linear().col(1);
  for (const auto& [label, left_limb, right_limb] :
       {std::tuple{ExtremityLabel::kHand, Limb::kLeftArm, Limb::kRightArm},
        std::tuple{ExtremityLabel::kFoot, Limb::kLeftLeg, Limb::kRightLeg}}) {
    std::vector<const Extremity*> ex = extremities.WithLabel(label);
    if (ex.empty()) continue;
    const Eigen::Vector3d l_root = posed.sensor_from_segment[I(LimbUpper(left_limb))].translation();
    const Eigen::Vector3d r_root =
        posed.sensor_from_segment[I(LimbUpper(right_limb))].translation();
    auto reach = [&](Limb limb, const Eigen::Vector3d& target) {
      if ((LimbEnd(body, posed, limb) - target).norm() <= min_offset_m) return;
      pose = ReachLimb(body, pose, limb, target, limits);
      ++count;
    };
    if (ex.size() >= 2) {
      const Extremity* first = ex[0];
      const Extremity* second = ex[1];
      if (first->position.dot(left) < second->position.dot(left)) std::swap(first, second);
      reach(left_limb, first->position);
      reach(right_limb, second->position);
    } else {
      const Eigen::Vector3d& p = ex[0]->position;
      const bool is_left = (p - l_root).squaredNorm() <= (p - r_root).squaredNorm();
      reach(is_left ? left_limb : right_limb, p);
    }
  }
  if (placed) *placed = count;
  return pose;
}

}  // namespace reenact::capture

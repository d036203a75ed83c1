#include "synthetic/body_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace reenact::capture {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d Rx(double a) { return AngleAxisd(a, Vector3d::UnitX()).toRotationMatrix(); }
Matrix3d Ry(double a) { return AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }
Matrix3d Rz(double a) { return AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }

Eigen::Isometry3d Frame(const Matrix3d& r, const Vector3d& t) {
  Eigen::Isometry3d f = Eigen::Isometry3d::Identity();
  f.linear() = r;
  f.translation() = t;
  return f;
}

}  // namespace

BodyPart SegmentPart(Segment s) {
  switch (s) {
    case Segment::kHead:
      return BodyPart::kHead;
    case Segment::kNeck:
    case Segment::kUpperTorso:
      return BodyPart::kUpperTorso;
    case Segment::kLowerTorso:
      return BodyPart::kLowerTorso;
    case Segment::kLeftUpperArm:
      return BodyPart::kLeftUpperArm;
    case Segment::kLeftForearm:
    case Segment::kLeftHand:
      return BodyPart::kLeftForearm;
    case Segment::kRightUpperArm:
      return BodyPart::kRightUpperArm;
    case Segment::kRightForearm:
    case Segment::kRightHand:
      return BodyPart::kRightForearm;
    case Segment::kLeftThigh:
      return BodyPart::kLeftThigh;
    case Segment::kLeftShin:
    case Segment::kLeftFoot:
      return BodyPart::kLeftShin;
    case Segment::kRightThigh:
      return BodyPart::kRightThigh;
    case Segment::kRightShin:
    case Segment::kRightFoot:
      return BodyPart::kRightShin;
  }
  return BodyPart::kHead;
}

PosedBody PoseBody(const BodyPose& pose, const BodyDimensions& d) {
  PosedBody out;
  auto seg = [&](Segment s, const Matrix3d& r, const Vector3d& t) {
    out.world_from_segment[static_cast<int>(s)] = Frame(r, t);
  };
  // Body x (forward) = world -y at yaw 0: Rz(-pi/2).
  const Matrix3d body = Rz(pose.root_yaw) * Rz(-std::numbers::pi / 2);
  const Vector3d waist(pose.root_xy.x(), pose.root_xy.y(), 0.0);
  const Matrix3d lower = body * Ry(pose.spine_bend / 2) * Rz(pose.spine_twist / 2);
  const Matrix3d upper = lower * Ry(pose.spine_bend / 2) * Rz(pose.spine_twist / 2);
  const Vector3d torso = waist + lower * Vector3d(0, 0, d.lower_spine);
  const Vector3d neck = torso + upper * Vector3d(0, 0, d.upper_spine);
  const Matrix3d head_r = upper * Ry(pose.head_pitch);
  const Vector3d head = neck + head_r * Vector3d(d.head_forward, 0, d.head_rise);

  Skeleton& s = out.skeleton;
  s.Set(Joint::kHead, head);
  s.Set(Joint::kNeck, neck);
  s.Set(Joint::kTorso, torso);
  s.Set(Joint::kWaist, waist);
  seg(Segment::kHead, head_r, head);
  seg(Segment::kNeck, upper, neck);
  seg(Segment::kUpperTorso, upper, torso);
  seg(Segment::kLowerTorso, lower, waist);

  const Vector3d down(0, 0, -1);
  for (int side = 0; side < 2; ++side) {
    const bool left = side == 0;
    const double sign = left ? 1 : -1;
    const ArmPose& arm = left ? pose.left_arm : pose.right_arm;
    const Vector3d shoulder =
        neck + upper * Vector3d(0, sign * d.shoulder_half_width, -d.shoulder_drop);
    const Matrix3d upper_arm = upper * Rx(sign * arm.abduction) * Ry(-arm.flexion);
    const Vector3d elbow = shoulder + upper_arm * (d.upper_arm * down);
    const Matrix3d forearm = upper_arm * Ry(-arm.elbow);
    const Vector3d wrist = elbow + forearm * (d.forearm * down);
    const Vector3d hand = wrist + forearm * (d.wrist_to_palm * down);
    s.Set(left ? Joint::kLeftShoulder : Joint::kRightShoulder, shoulder);
    s.Set(left ? Joint::kLeftElbow : Joint::kRightElbow, elbow);
    s.Set(left ? Joint::kLeftHand : Joint::kRightHand, hand);
    seg(left ? Segment::kLeftUpperArm : Segment::kRightUpperArm, upper_arm, shoulder);
    seg(left ? Segment::kLeftForearm : Segment::kRightForearm, forearm, elbow);
    seg(left ? Segment::kLeftHand : Segment::kRightHand, forearm, wrist);

    const LegPose& leg = left ? pose.left_leg : pose.right_leg;
    const Vector3d hip = waist + body * Vector3d(0, sign * d.hip_half_width, -d.hip_drop);
    const Matrix3d thigh = body * Rx(sign * leg.abduction) * Ry(-leg.flexion);
    const Vector3d knee = hip + thigh * (d.thigh * down);
    const Matrix3d shin = thigh * Ry(leg.knee);
    const Vector3d ankle = knee + shin * (d.shin * down);
    s.Set(left ? Joint::kLeftHip : Joint::kRightHip, hip);
    s.Set(left ? Joint::kLeftKnee : Joint::kRightKnee, knee);
    s.Set(left ? Joint::kLeftFoot : Joint::kRightFoot, ankle);
    seg(left ? Segment::kLeftThigh : Segment::kRightThigh, thigh, hip);
    seg(left ? Segment::kLeftShin : Segment::kRightShin, shin, knee);
    seg(left ? Segment::kLeftFoot : Segment::kRightFoot,
        shin * Ry(leg.ankle) * Rx(sign * leg.ankle_roll), ankle);
  }

  // Stand on the floor: lift everything so that the lower ankle sits at ankle_height.
  const double lowest = std::min(s[Joint::kLeftFoot].z(), s[Joint::kRightFoot].z());
  const Vector3d lift(0, 0, d.ankle_height - lowest);
  for (int j = 0; j < kJointCount; ++j) s.position[j] += lift;
  for (auto& f : out.world_from_segment) f.translation() += lift;
  return out;
}

}  // namespace reenact::capture

#include "capture-client/tracker/articulated_body.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

using S = BodySegment;
constexpr int I(S s) { return static_cast<int>(s); }

constexpr std::array<int, kBodySegmentCount> kParent = {-1, 0, 1, 2, 2, 4, 2, 6, 0, 8, 0, 10};

Eigen::Matrix3d RotY(double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

// Sign of the hinge: elbows turn about -y (forearm forwards), knees about +y (shin backwards).
double HingeSign(S s) { return s == S::kLeftForearm || s == S::kRightForearm ? -1.0 : 1.0; }

double ConeLimit(S s, const JointLimits& l) {
  switch (s) {
    case S::kLowerSpine:
    case S::kChest:
      return l.spine_max;
    case S::kHead:
      return l.head_max;
    case S::kLeftUpperArm:
    case S::kRightUpperArm:
      return l.shoulder_max;
    case S::kLeftThigh:
    case S::kRightThigh:
      return l.hip_max;
    case S::kLeftForearm:
    case S::kRightForearm:
      return l.elbow_max;
    default:
      return l.knee_max;
  }
}

// The twist limit of segment s (radians; pi and beyond: none).
double TwistLimit(S s, const JointLimits& l) {
  switch (s) {
    case S::kLowerSpine:
    case S::kChest:
      return l.spine_twist_max;
    case S::kLeftThigh:
    case S::kRightThigh:
      return l.hip_twist_max;
    default:
      return std::numbers::pi;
  }
}

// local = swing * Rz(twist) with the twist clamped to [-limit, limit], the swing kept. A swing
// of half a turn about an axis across z leaves the twist undefined; the rotation is kept.
void ClampTwist(Eigen::Matrix3d* local, double limit) {
  const Eigen::Quaterniond q(*local);
  const double n = std::hypot(q.w(), q.z());
  if (!(n > 1e-9)) return;
  const Eigen::Quaterniond twist(q.w() / n, 0, 0, q.z() / n);
  const double angle = std::remainder(2 * std::atan2(twist.z(), twist.w()), 2 * std::numbers::pi);
  if (std::abs(angle) <= limit) return;
  *local =
      (q * twist.conjugate()).toRotationMatrix() *
      Eigen::AngleAxisd(std::copysign(limit, angle), Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// A rotation whose z axis is z (unit) and whose x axis is as near x_hint as possible; when
// x_hint is (nearly) parallel to z, fallback is used instead.
Eigen::Matrix3d FrameFromAxes(const Eigen::Vector3d& z, const Eigen::Vector3d& x_hint,
                              const Eigen::Vector3d& fallback) {
  Eigen::Vector3d x = x_hint - x_hint.dot(z) * z;
  if (x.norm() < 1e-3 * std::max(1.0, x_hint.norm())) x = fallback - fallback.dot(z) * z;
  if (x.norm() < 1e-9) x = z.unitOrthogonal();
  x.normalize();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = z.cross(x);
  r.col(2) = z;
  return r;
}

Eigen::Vector3d SafeDir(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double n = v.norm();
  return n > 1e-9 ? Eigen::Vector3d(v / n) : fallback;
}

}  // namespace

int SegmentParent(BodySegment s) { return kParent[I(s)]; }

bool IsHinge(BodySegment s) {
  return s == S::kLeftForearm || s == S::kRightForearm || s == S::kLeftShin || s == S::kRightShin;
}

BodySegment LimbUpper(Limb limb) {
  constexpr S kUpper[] = {S::kLeftUpperArm, S::kRightUpperArm, S::kLeftThigh, S::kRightThigh};
  return kUpper[static_cast<int>(limb)];
}

BodySegment LimbLower(Limb limb) {
  constexpr S kLower[] = {S::kLeftForearm, S::kRightForearm, S::kLeftShin, S::kRightShin};
  return kLower[static_cast<int>(limb)];
}

Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

BodyShape BodyShape::FromHeight(double h) {
  REENACT_CHECK(h > 0 && std::isfinite(h), "height must be positive");
  BodyShape s;
  s.ankle_height = 0.039 * h;
  s.shin = 0.246 * h;
  s.thigh = 0.245 * h;
  s.hip_drop = 0.03 * h;
  s.hip_half_width = 0.05 * h;
  s.lower_spine = 0.13 * h;
  s.upper_spine = 0.18 * h;
  s.head_rise = 0.07 * h;
  s.head_radius = 0.06 * h;
  s.shoulder_half_width = 0.105 * h;
  s.shoulder_drop = 0.052 * h;
  s.upper_arm = 0.186 * h;
  s.forearm = 0.186 * h;
  s.torso_radius = 0.057 * h;
  s.torso_half_spread = 0.04 * h;
  s.upper_arm_radius = 0.026 * h;
  s.forearm_radius = 0.022 * h;
  s.thigh_radius = 0.04 * h;
  s.shin_radius = 0.029 * h;
  s.foot_radius = 0.023 * h;
  s.foot_length = 0.07 * h;
  return s;
}

double BodyShape::StandingHeight() const {
  return ankle_height + shin + thigh + hip_drop + lower_spine + upper_spine + head_rise +
         head_radius;
}

Skeleton BodyShape::RestSkeleton() const {
  const ArticulatedBody body(*this);
  ArticulatedPose pose;
  pose.root_translation = Eigen::Vector3d(0, 0, ankle_height + shin + thigh + hip_drop);
  return body.Pose(pose).skeleton;
}

std::array<double, kBodyPartCount> BodyShape::PartLengths() const {
  return {head_rise, upper_spine, lower_spine, upper_arm, forearm, upper_arm,
          forearm,   thigh,       shin,        thigh,     shin};
}

std::array<double, kBodyPartCount> BodyShape::PartRadii() const {
  const double torso = 0.5 * ((torso_half_spread + torso_radius) + torso_radius);
  return {head_radius,      torso,          torso,        upper_arm_radius, forearm_radius,
          upper_arm_radius, forearm_radius, thigh_radius, shin_radius,      thigh_radius,
          shin_radius};
}

std::vector<BodyCapsule> BodyShape::Capsules() const {
  using V = Eigen::Vector3d;
  std::vector<BodyCapsule> c;
  c.push_back({S::kHead, V::Zero(), V(0, 0, head_rise), head_radius});
  const double chest_top = std::max(0.0, upper_spine - torso_radius);
  for (double side : {-1.0, 1.0}) {
    const double y = side * torso_half_spread;
    c.push_back({S::kChest, V(0, y, 0), V(0, y, chest_top), torso_radius});
    c.push_back({S::kLowerSpine, V(0, y, 0), V(0, y, lower_spine), torso_radius});
    c.push_back({S::kPelvis, V(0, y, -hip_drop), V(0, y, 0), torso_radius});
  }
  for (S arm : {S::kLeftUpperArm, S::kRightUpperArm})
    c.push_back({arm, V::Zero(), V(0, 0, -upper_arm), upper_arm_radius});
  for (S arm : {S::kLeftForearm, S::kRightForearm})
    c.push_back({arm, V::Zero(), V(0, 0, -forearm), forearm_radius});
  for (S leg : {S::kLeftThigh, S::kRightThigh})
    c.push_back({leg, V::Zero(), V(0, 0, -thigh), thigh_radius});
  for (S leg : {S::kLeftShin, S::kRightShin}) {
    c.push_back({leg, V::Zero(), V(0, 0, -shin), shin_radius});
    c.push_back({leg, V(0, 0, -shin),
                 V(foot_length, 0, -shin - std::max(0.0, ankle_height - foot_radius)),
                 foot_radius});
  }
  return c;
}

ArticulatedPose::ArticulatedPose() { local.fill(Eigen::Matrix3d::Identity()); }

ArticulatedBody::ArticulatedBody(const BodyShape& shape)
    : shape_(shape), capsules_(shape.Capsules()) {
  const BodyShape& s = shape;
  offset_.fill(Eigen::Vector3d::Zero());
  offset_[I(S::kChest)] = {0, 0, s.lower_spine};
  offset_[I(S::kHead)] = {0, 0, s.upper_spine};
  offset_[I(S::kLeftUpperArm)] = {0, s.shoulder_half_width, s.upper_spine - s.shoulder_drop};
  offset_[I(S::kRightUpperArm)] = {0, -s.shoulder_half_width, s.upper_spine - s.shoulder_drop};
  offset_[I(S::kLeftForearm)] = {0, 0, -s.upper_arm};
  offset_[I(S::kRightForearm)] = {0, 0, -s.upper_arm};
  offset_[I(S::kLeftThigh)] = {0, s.hip_half_width, -s.hip_drop};
  offset_[I(S::kRightThigh)] = {0, -s.hip_half_width, -s.hip_drop};
  offset_[I(S::kLeftShin)] = {0, 0, -s.thigh};
  offset_[I(S::kRightShin)] = {0, 0, -s.thigh};
}

PosedBody3 ArticulatedBody::Pose(const ArticulatedPose& pose) const {
  PosedBody3 out;
  auto& T = out.sensor_from_segment;
  T[0].linear() = pose.root_rotation;
  T[0].translation() = pose.root_translation;
  for (int s = 1; s < kBodySegmentCount; ++s) {
    const Eigen::Isometry3d& parent = T[kParent[s]];
    const Eigen::Matrix3d local = IsHinge(static_cast<S>(s))
                                      ? RotY(HingeSign(static_cast<S>(s)) * pose.hinge_angle[s])
                                      : pose.local[s];
    T[s].linear() = parent.linear() * local;
    T[s].translation() = parent * offset_[s];
  }
  Skeleton& k = out.skeleton;
  const BodyShape& sh = shape_;
  auto origin = [&](S s) -> Eigen::Vector3d { return T[I(s)].translation(); };
  k.Set(Joint::kHead, T[I(S::kHead)] * Eigen::Vector3d(0, 0, sh.head_rise));
  k.Set(Joint::kNeck, origin(S::kHead));
  k.Set(Joint::kTorso, origin(S::kChest));
  k.Set(Joint::kWaist, origin(S::kPelvis));
  k.Set(Joint::kLeftShoulder, origin(S::kLeftUpperArm));
  k.Set(Joint::kLeftElbow, origin(S::kLeftForearm));
  k.Set(Joint::kLeftHand, T[I(S::kLeftForearm)] * Eigen::Vector3d(0, 0, -sh.forearm));
  k.Set(Joint::kRightShoulder, origin(S::kRightUpperArm));
  k.Set(Joint::kRightElbow, origin(S::kRightForearm));
  k.Set(Joint::kRightHand, T[I(S::kRightForearm)] * Eigen::Vector3d(0, 0, -sh.forearm));
  k.Set(Joint::kLeftHip, origin(S::kLeftThigh));
  k.Set(Joint::kLeftKnee, origin(S::kLeftShin));
  k.Set(Joint::kLeftFoot, T[I(S::kLeftShin)] * Eigen::Vector3d(0, 0, -sh.shin));
  k.Set(Joint::kRightHip, origin(S::kRightThigh));
  k.Set(Joint::kRightKnee, origin(S::kRightShin));
  k.Set(Joint::kRightFoot, T[I(S::kRightShin)] * Eigen::Vector3d(0, 0, -sh.shin));
  return out;
}

int ArticulatedBody::ParameterIndex(BodySegment s) {
  if (s == S::kPelvis) return 3;
  int index = 6;
  for (int i = 1; i < I(s); ++i) index += IsHinge(static_cast<S>(i)) ? 1 : 3;
  return index;
}

void ArticulatedBody::Clamp(ArticulatedPose* pose, const JointLimits& limits) {
  for (int s = 1; s < kBodySegmentCount; ++s) {
    const S seg = static_cast<S>(s);
    const double limit = ConeLimit(seg, limits);
    if (IsHinge(seg)) {
      pose->hinge_angle[s] = std::clamp(pose->hinge_angle[s], 0.0, limit);
      continue;
    }
    if (const double twist = TwistLimit(seg, limits); twist < std::numbers::pi)
      ClampTwist(&pose->local[s], twist);
    Eigen::AngleAxisd aa(pose->local[s]);
    if (aa.angle() > limit) pose->local[s] = Eigen::AngleAxisd(limit, aa.axis()).toRotationMatrix();
  }
}

ArticulatedPose ArticulatedBody::Step(const ArticulatedPose& pose, const PosedBody3& posed,
                                      const Eigen::VectorXd& delta,
                                      const JointLimits& limits) const {
  REENACT_CHECK(delta.size() == kParameterCount, "step of the wrong size");
  ArticulatedPose next = pose;
  next.root_translation += delta.segment<3>(0);
  next.root_rotation = ExpRotation(delta.segment<3>(3)) * pose.root_rotation;
  Eigen::Quaterniond q(next.root_rotation);
  next.root_rotation = q.normalized().toRotationMatrix();
  for (int s = 1; s < kBodySegmentCount; ++s) {
    const S seg = static_cast<S>(s);
    const int k = ParameterIndex(seg);
    if (IsHinge(seg)) {
      next.hinge_angle[s] += delta[k];
      continue;
    }
    const Eigen::Matrix3d& parent = posed.sensor_from_segment[kParent[s]].linear();
    const Eigen::Vector3d omega_local = parent.transpose() * delta.segment<3>(k);
    Eigen::Quaterniond local(ExpRotation(omega_local) * pose.local[s]);
    next.local[s] = local.normalized().toRotationMatrix();
  }
  Clamp(&next, limits);
  return next;
}

ArticulatedPose ArticulatedBody::PoseFromSkeleton(const Skeleton& t) const {
  ArticulatedPose pose;
  // Pelvis: the hips lie at (0, +-hip_half_width, -hip_drop) from the waist, so z points from
  // the hips' middle to the waist and y along the hips; x = y cross z (forward).
  const Eigen::Vector3d spine_up =
      SafeDir(t[Joint::kNeck] - t[Joint::kWaist], Eigen::Vector3d(0, -1, 0));
  const Eigen::Vector3d hips_mid = 0.5 * (t[Joint::kLeftHip] + t[Joint::kRightHip]);
  const Eigen::Vector3d up =
      shape_.hip_drop > 1e-6 ? SafeDir(t[Joint::kWaist] - hips_mid, spine_up) : spine_up;
  const Eigen::Vector3d left =
      SafeDir(t[Joint::kLeftHip] - t[Joint::kRightHip], Eigen::Vector3d(-1, 0, 0));
  const Eigen::Matrix3d pelvis = FrameFromAxes(up, left.cross(up), Eigen::Vector3d(0, 0, -1));
  pose.root_rotation = pelvis;
  pose.root_translation = t[Joint::kWaist];
  std::array<Eigen::Matrix3d, kBodySegmentCount> world;
  world[0] = pelvis;
  auto set_ball = [&](S s, const Eigen::Matrix3d& r) {
    world[I(s)] = r;
    pose.local[I(s)] = world[kParent[I(s)]].transpose() * r;
  };
  auto fwd = [&](S s) -> Eigen::Vector3d { return world[I(s)].col(0); };
  set_ball(S::kLowerSpine, FrameFromAxes(SafeDir(t[Joint::kTorso] - t[Joint::kWaist], up),
                                         fwd(S::kPelvis), fwd(S::kPelvis)));
  const Eigen::Vector3d chest_up = SafeDir(t[Joint::kNeck] - t[Joint::kTorso], up);
  const Eigen::Vector3d shoulders = t[Joint::kLeftShoulder] - t[Joint::kRightShoulder];
  set_ball(S::kChest, FrameFromAxes(chest_up, shoulders.cross(chest_up), fwd(S::kLowerSpine)));
  set_ball(S::kHead, FrameFromAxes(SafeDir(t[Joint::kHead] - t[Joint::kNeck], chest_up),
                                   fwd(S::kChest), fwd(S::kChest)));
  struct Limb {
    S upper, lower;
    Joint a, b, c;
    double bend;  // +1: the lower segment bends towards the upper's +x (elbow), -1 (knee)
  };
  const Limb limbs[] = {
      {S::kLeftUpperArm, S::kLeftForearm, Joint::kLeftShoulder, Joint::kLeftElbow, Joint::kLeftHand,
       1},
      {S::kRightUpperArm, S::kRightForearm, Joint::kRightShoulder, Joint::kRightElbow,
       Joint::kRightHand, 1},
      {S::kLeftThigh, S::kLeftShin, Joint::kLeftHip, Joint::kLeftKnee, Joint::kLeftFoot, -1},
      {S::kRightThigh, S::kRightShin, Joint::kRightHip, Joint::kRightKnee, Joint::kRightFoot, -1},
  };
  for (const Limb& l : limbs) {
    const Eigen::Matrix3d& parent = world[kParent[I(l.upper)]];
    const Eigen::Vector3d down = SafeDir(t[l.b] - t[l.a], -parent.col(2));
    const Eigen::Vector3d lower = SafeDir(t[l.c] - t[l.b], down);
    // The segment's z axis points from its distal end to its proximal joint.
    const Eigen::Vector3d z = -down;
    set_ball(l.upper, FrameFromAxes(z, l.bend * lower, parent.col(0)));
    const double c = std::clamp(down.dot(lower), -1.0, 1.0);
    pose.hinge_angle[I(l.lower)] = std::acos(c);
    world[I(l.lower)] = world[I(l.upper)] * RotY(HingeSign(l.lower) * std::acos(c));
  }
  Clamp(&pose, JointLimits{});
  return pose;
}

}  // namespace reenact::capture

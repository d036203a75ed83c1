#include "synthetic/body_pose_from_skeleton.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kPi = std::numbers::pi;

Matrix3d Rx(double a) { return AngleAxisd(a, Vector3d::UnitX()).toRotationMatrix(); }
Matrix3d Ry(double a) { return AngleAxisd(a, Vector3d::UnitY()).toRotationMatrix(); }
Matrix3d Rz(double a) { return AngleAxisd(a, Vector3d::UnitZ()).toRotationMatrix(); }

double Wrap(double a) {
  a = std::remainder(a, 2 * kPi);
  return a <= -kPi ? a + 2 * kPi : a;
}

// a (any angle) moved into [lo, hi] (a range shorter than a full turn): a itself, or an
// equal angle a + 2 pi k, or else the bound nearest around the circle.
double ClampAngle(double a, double lo, double hi) {
  const double near_lo = lo + std::fmod(std::fmod(a - lo, 2 * kPi) + 2 * kPi, 2 * kPi);
  if (near_lo <= hi) return near_lo;
  const double past_hi = near_lo - hi, before_lo = lo + 2 * kPi - near_lo;
  return past_hi <= before_lo ? hi : lo;
}

bool Usable(const Skeleton& s, Joint j) { return s.Has(j) && s[j].allFinite(); }

// The unit direction a -> b, when both joints are usable and far enough apart.
std::optional<Vector3d> Direction(const Skeleton& s, Joint a, Joint b) {
  if (!Usable(s, a) || !Usable(s, b)) return std::nullopt;
  const Vector3d d = s[b] - s[a];
  const double n = d.norm();
  if (!(n >= kMinBoneLength)) return std::nullopt;
  return d / n;
}

using ResidualFn = std::function<VectorXd(const VectorXd&)>;

// Levenberg-Marquardt on a box: numeric (central) Jacobian; an angle at a bound whose
// gradient points out of the box stays there for the iteration (active set), the others
// take the damped step, projected into [lo, hi].
VectorXd Minimize(const ResidualFn& residual, VectorXd x, const VectorXd& lo, const VectorXd& hi,
                  int iterations) {
  x = x.cwiseMax(lo).cwiseMin(hi);
  VectorXd r = residual(x);
  double cost = r.squaredNorm();
  double mu = 1e-6;
  constexpr double kStep = 1e-7;
  for (int it = 0; it < iterations && cost > 1e-28; ++it) {
    Eigen::MatrixXd J(r.size(), x.size());
    for (int k = 0; k < x.size(); ++k) {
      VectorXd a = x, b = x;
      a[k] += kStep;
      b[k] -= kStep;
      J.col(k) = (residual(a) - residual(b)) / (2 * kStep);
    }
    const VectorXd g_all = J.transpose() * r;
    for (int k = 0; k < x.size(); ++k)
      if ((x[k] <= lo[k] && g_all[k] > 0) || (x[k] >= hi[k] && g_all[k] < 0)) J.col(k).setZero();
    const Eigen::MatrixXd H = J.transpose() * J;
    const VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 12 && !improved; ++tries) {
      Eigen::MatrixXd damped = H;
      damped.diagonal().array() += mu * (1.0 + H.diagonal().array());
      const VectorXd step = damped.ldlt().solve(-g);
      if (!step.allFinite()) break;
      const VectorXd next = (x + step).cwiseMax(lo).cwiseMin(hi);
      const VectorXd next_r = residual(next);
      const double next_cost = next_r.squaredNorm();
      if (next_cost < cost) {
        const double moved = (next - x).norm();
        x = next, r = next_r, cost = next_cost;
        mu = std::max(mu / 10, 1e-12);
        improved = true;
        if (moved < 1e-13) return x;
      } else {
        mu *= 10;
      }
    }
    if (!improved) break;
  }
  return x;
}

// Appends (fitted - target) for the bones whose target is known.
void Append(const std::optional<Vector3d>& target, const Vector3d& fitted,
            std::vector<double>* out) {
  if (!target) return;
  const Vector3d d = fitted - *target;
  out->insert(out->end(), {d.x(), d.y(), d.z()});
}

VectorXd ToVector(const std::vector<double>& v) {
  if (v.empty()) return VectorXd::Zero(1);
  return Eigen::Map<const VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

struct Chain {
  double abduction = 0, flexion = 0, hinge = 0;
};

// An arm (hinge_sign -1: the elbow is Ry(-e)) or a leg (+1: the knee is Ry(+k)) on the parent
// frame `parent` (world_from_parent), side sign s.
struct ChainModel {
  Matrix3d parent;
  double s = 1, hinge_sign = -1;
  std::optional<Vector3d> upper, lower;  // target bone directions, world
  double a_min = 0, a_max = 0, f_min = 0, f_max = 0, hinge_max = 0;  // limits

  Matrix3d Upper(double a, double f) const { return parent * Rx(s * a) * Ry(-f); }
  VectorXd Residual(const VectorXd& p) const {
    const Matrix3d r = Upper(p[0], p[1]);
    std::vector<double> out;
    Append(upper, r * Vector3d(0, 0, -1), &out);
    Append(lower, r * Ry(hinge_sign * p[2]) * Vector3d(0, 0, -1), &out);
    return ToVector(out);
  }
  // The hinge angle that puts the lower bone nearest `lower` for a given upper frame.
  double Hinge(double a, double f) const {
    if (!lower) return 0;
    const Vector3d v = Upper(a, f).transpose() * *lower;
    return ClampAngle(std::atan2(-hinge_sign * v.x(), -v.z()), 0, hinge_max);
  }
};

Chain FitChain(const ChainModel& m, int iterations) {
  if (!m.upper && !m.lower) return {};
  VectorXd lo(3), hi(3);
  lo << m.a_min, m.f_min, 0;
  hi << m.a_max, m.f_max, m.hinge_max;
  std::vector<VectorXd> starts;
  if (m.upper) {
    const Vector3d u = m.parent.transpose() * *m.upper;
    const double f1 = std::atan2(u.x(), std::hypot(u.y(), u.z()));
    const double a1 = std::atan2(m.s * u.y(), -u.z());
    for (auto [a0, f0] : {std::pair{a1, f1}, std::pair{a1 + kPi, kPi - f1}}) {
      const double a = ClampAngle(a0, m.a_min, m.a_max), f = ClampAngle(f0, m.f_min, m.f_max);
      VectorXd p(3);
      p << a, f, m.Hinge(a, f);
      starts.push_back(p);
    }
  } else {
    VectorXd p(3);
    p << 0, 0, m.Hinge(0, 0);
    starts.push_back(p);
  }
  const ResidualFn residual = [&](const VectorXd& p) { return m.Residual(p); };
  VectorXd best = starts.front();
  double best_cost = INFINITY;
  for (const VectorXd& start : starts) {
    const VectorXd p = Minimize(residual, start, lo, hi, iterations);
    const double cost = residual(p).squaredNorm();
    if (cost < best_cost - 1e-12) best = p, best_cost = cost;
  }
  return {best[0], best[1], best[2]};
}

// The rotation of the lower (first) and upper torso for a spine bend and twist (PoseBody).
std::pair<Matrix3d, Matrix3d> Torso(const Matrix3d& body, double bend, double twist) {
  const Matrix3d half = Ry(bend / 2) * Rz(twist / 2);
  const Matrix3d lower = body * half;
  return {lower, lower * half};
}

}  // namespace

void BodyPoseLimits::Check() const {
  const auto range = [](double lo, double hi) {
    return std::isfinite(lo) && std::isfinite(hi) && lo <= hi && hi - lo < 2 * kPi;
  };
  REENACT_CHECK(range(spine_bend_min, spine_bend_max),
                "spine bend range must be finite, min <= max, shorter than a turn");
  REENACT_CHECK(range(0, spine_twist_max) && range(0, head_pitch_max) && range(0, elbow_max) &&
                    range(0, knee_max) && range(0, ankle_roll_max),
                "spine_twist_max, head_pitch_max, elbow_max, knee_max and ankle_roll_max must "
                "be finite, >= 0 and less than a turn");
  REENACT_CHECK(
      range(arm_abduction_min, arm_abduction_max) && range(arm_flexion_min, arm_flexion_max),
      "arm ranges must be finite, min <= max, shorter than a turn");
  REENACT_CHECK(range(leg_flexion_min, leg_flexion_max) &&
                    range(leg_abduction_min, leg_abduction_max) && range(ankle_min, ankle_max),
                "leg ranges must be finite, min <= max, shorter than a turn");
}

void BodyPoseFromSkeletonOptions::Check() const {
  limits.Check();
  REENACT_CHECK(iterations >= 0, "iterations must be >= 0");
  REENACT_CHECK(std::isfinite(dims.head_forward) && std::isfinite(dims.head_rise) &&
                    std::hypot(dims.head_forward, dims.head_rise) > 0,
                "dims must place the head away from the neck");
}

BodyPoseFit BodyPoseFromSkeleton(const Skeleton& t, const BodyPoseFromSkeletonOptions& options) {
  options.Check();
  const BodyPoseLimits& lim = options.limits;
  const BodyDimensions& dims = options.dims;
  BodyPoseFit fit;
  BodyPose& pose = fit.pose;

  // The 13 bones.
  const auto waist_torso = Direction(t, Joint::kWaist, Joint::kTorso);
  const auto torso_neck = Direction(t, Joint::kTorso, Joint::kNeck);
  const auto waist_neck =
      waist_torso || torso_neck ? std::nullopt : Direction(t, Joint::kWaist, Joint::kNeck);
  const auto shoulders = Direction(t, Joint::kRightShoulder, Joint::kLeftShoulder);
  const auto hips = Direction(t, Joint::kRightHip, Joint::kLeftHip);
  const auto neck_head = Direction(t, Joint::kNeck, Joint::kHead);

  // 1. Yaw.
  const auto horizontal = [&](Joint a, Joint b) -> std::optional<Eigen::Vector2d> {
    if (!Usable(t, a) || !Usable(t, b)) return std::nullopt;
    const Eigen::Vector2d h = (t[b] - t[a]).head<2>();
    if (!(h.norm() >= kMinBoneLength)) return std::nullopt;
    return h;
  };
  fit.yaw_from = "none";
  if (const auto h = horizontal(Joint::kRightHip, Joint::kLeftHip)) {
    pose.root_yaw = std::atan2(h->y(), h->x());
    fit.yaw_from = "hips";
  } else if (const auto s = horizontal(Joint::kRightShoulder, Joint::kLeftShoulder)) {
    pose.root_yaw = std::atan2(s->y(), s->x());
    fit.yaw_from = "shoulders";
  }
  pose.root_yaw = Wrap(pose.root_yaw);
  const Matrix3d body = Rz(pose.root_yaw) * Rz(-kPi / 2);

  // 2. Spine.
  {
    double bend = 0, twist = 0;
    const std::optional<Vector3d> lower_dir = waist_torso ? waist_torso : waist_neck;
    if (lower_dir) {
      const Vector3d d = body.transpose() * *lower_dir;
      bend = 2 * std::atan2(d.x(), d.z());
    }
    if (shoulders && fit.yaw_from == "hips") {
      const Vector3d d = body.transpose() * *shoulders;
      twist = std::atan2(-d.x(), d.y());
    }
    const ResidualFn residual = [&](const VectorXd& p) {
      const auto [lower, upper] = Torso(body, p[0], p[1]);
      std::vector<double> out;
      Append(waist_torso, lower.col(2), &out);
      Append(torso_neck, upper.col(2), &out);
      Append(waist_neck,
             (lower.col(2) * dims.lower_spine + upper.col(2) * dims.upper_spine).normalized(),
             &out);
      Append(shoulders, upper.col(1), &out);
      return ToVector(out);
    };
    VectorXd p(2), lo(2), hi(2);
    p << ClampAngle(bend, lim.spine_bend_min, lim.spine_bend_max),
        ClampAngle(twist, -lim.spine_twist_max, lim.spine_twist_max);
    lo << lim.spine_bend_min, -lim.spine_twist_max;
    hi << lim.spine_bend_max, lim.spine_twist_max;
    p = Minimize(residual, p, lo, hi, options.iterations);
    pose.spine_bend = p[0];
    pose.spine_twist = p[1];
  }
  const Matrix3d upper = Torso(body, pose.spine_bend, pose.spine_twist).second;

  // 3. Head.
  if (neck_head) {
    const Vector3d v = upper.transpose() * *neck_head;
    pose.head_pitch =
        ClampAngle(std::atan2(v.x(), v.z()) - std::atan2(dims.head_forward, dims.head_rise),
                   -lim.head_pitch_max, lim.head_pitch_max);
  }

  // 4. Arms and legs, 5. feet.
  for (int side = 0; side < 2; ++side) {
    const bool left = side == 0;
    const double s = left ? 1 : -1;
    const ChainModel arm{upper,
                         s,
                         -1,
                         Direction(t, left ? Joint::kLeftShoulder : Joint::kRightShoulder,
                                   left ? Joint::kLeftElbow : Joint::kRightElbow),
                         Direction(t, left ? Joint::kLeftElbow : Joint::kRightElbow,
                                   left ? Joint::kLeftHand : Joint::kRightHand),
                         lim.arm_abduction_min,
                         lim.arm_abduction_max,
                         lim.arm_flexion_min,
                         lim.arm_flexion_max,
                         lim.elbow_max};
    const Chain a = FitChain(arm, options.iterations);
    ArmPose& arm_pose = left ? pose.left_arm : pose.right_arm;
    arm_pose = {a.abduction, a.flexion, a.hinge};

    const ChainModel leg{body,
                         s,
                         +1,
                         Direction(t, left ? Joint::kLeftHip : Joint::kRightHip,
                                   left ? Joint::kLeftKnee : Joint::kRightKnee),
                         Direction(t, left ? Joint::kLeftKnee : Joint::kRightKnee,
                                   left ? Joint::kLeftFoot : Joint::kRightFoot),
                         lim.leg_abduction_min,
                         lim.leg_abduction_max,
                         lim.leg_flexion_min,
                         lim.leg_flexion_max,
                         lim.knee_max};
    const Chain l = FitChain(leg, options.iterations);
    LegPose& leg_pose = left ? pose.left_leg : pose.right_leg;
    leg_pose.abduction = l.abduction;
    leg_pose.flexion = l.flexion;
    leg_pose.knee = l.hinge;
    const Matrix3d shin = leg.Upper(l.abduction, l.flexion) * Ry(l.hinge);
    leg_pose.ankle = ClampAngle(std::atan2(shin(2, 0), shin(2, 2)), lim.ankle_min, lim.ankle_max);
    const Matrix3d foot = shin * Ry(leg_pose.ankle);
    leg_pose.ankle_roll = ClampAngle(s * std::atan2(-foot(2, 1), foot(2, 2)), -lim.ankle_roll_max,
                                     lim.ankle_roll_max);
  }

  // 6. Root position.
  if (Usable(t, Joint::kWaist))
    pose.root_xy = t[Joint::kWaist].head<2>();
  else if (Usable(t, Joint::kLeftHip) && Usable(t, Joint::kRightHip))
    pose.root_xy = ((t[Joint::kLeftHip] + t[Joint::kRightHip]) / 2).head<2>();

  // The fitted body's bone directions against the target's.
  const Skeleton f = PoseBody(pose, dims).skeleton;
  double sum = 0;
  const auto add = [&](const std::optional<Vector3d>& target, Joint a, Joint b) {
    if (!target) return;
    sum += ((f[b] - f[a]).normalized() - *target).squaredNorm();
    ++fit.bones_used;
  };
  add(waist_torso, Joint::kWaist, Joint::kTorso);
  add(torso_neck, Joint::kTorso, Joint::kNeck);
  add(waist_neck, Joint::kWaist, Joint::kNeck);
  add(shoulders, Joint::kRightShoulder, Joint::kLeftShoulder);
  add(hips, Joint::kRightHip, Joint::kLeftHip);
  add(neck_head, Joint::kNeck, Joint::kHead);
  for (const auto& [a, b] :
       {std::pair{Joint::kLeftShoulder, Joint::kLeftElbow},
        std::pair{Joint::kLeftElbow, Joint::kLeftHand},
        std::pair{Joint::kRightShoulder, Joint::kRightElbow},
        std::pair{Joint::kRightElbow, Joint::kRightHand},
        std::pair{Joint::kLeftHip, Joint::kLeftKnee}, std::pair{Joint::kLeftKnee, Joint::kLeftFoot},
        std::pair{Joint::kRightHip, Joint::kRightKnee},
        std::pair{Joint::kRightKnee, Joint::kRightFoot}})
    add(Direction(t, a, b), a, b);
  fit.rms_direction_error = fit.bones_used ? std::sqrt(sum / fit.bones_used) : 0;
  return fit;
}

}  // namespace reenact::capture

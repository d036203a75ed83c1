#include "synthetic/walk_motion.h"

#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "synthetic/procedural.h"

namespace reenact::capture {
namespace {

constexpr double kPi = std::numbers::pi;
double Deg(double d) { return d * kPi / 180; }

// exp(-(d / w)^2) with d the distance from p to c on the unit circle of phases.
double Bump(double p, double c, double w) {
  double d = std::abs(Fract(p) - c);
  d = std::min(d, 1 - d);
  return std::exp(-(d / w) * (d / w));
}

void SetLeg(double p, double a, LegPose* leg) {
  leg->flexion = a * Deg(7.5 + 17.5 * std::cos(2 * kPi * p));
  leg->knee = a * Deg(15 * Bump(p, 0.15, 0.08) + 60 * Bump(p, 0.72, 0.11));
  leg->ankle = a * Deg(10 * Bump(p, 0.6, 0.08));
  leg->abduction = Deg(2);
}

void SetArm(double p, double a, ArmPose* arm) {
  const double swing = std::cos(2 * kPi * (p + 0.5));
  arm->flexion = a * Deg(15 * swing);
  arm->elbow = Deg(15) + a * Deg(10 * std::max(0.0, swing));
  arm->abduction = Deg(7);
}

// Integral of SmoothStep(0, 1, x) from 0 to x, for x in [0, 1].
double SmoothStepIntegral(double x) { return x * x * x - x * x * x * x / 2; }

}  // namespace

void CircleWalkOptions::Check() const {
  REENACT_CHECK(std::isfinite(ramp_s) && ramp_s >= 0, "ramp_s must be >= 0");
  REENACT_CHECK(std::isfinite(duration_s) && duration_s > 2 * ramp_s,
                "duration_s must exceed twice ramp_s");
  REENACT_CHECK(std::isfinite(radius_m) && radius_m > 0, "radius_m must be > 0");
  REENACT_CHECK(std::isfinite(stride_m) && stride_m > 0, "stride_m must be > 0");
}

BodyPose WalkCyclePose(double phase, double amplitude) {
  BodyPose pose;
  const double left = Fract(phase), right = Fract(phase + 0.5);
  SetLeg(left, amplitude, &pose.left_leg);
  SetLeg(right, amplitude, &pose.right_leg);
  SetArm(left, amplitude, &pose.left_arm);
  SetArm(right, amplitude, &pose.right_arm);
  pose.spine_twist = amplitude * Deg(6) * std::cos(2 * kPi * left);
  pose.spine_bend = amplitude * Deg(3);
  return pose;
}

std::vector<BodyPose> CircleWalk(const CircleWalkOptions& o, double frame_rate_hz) {
  o.Check();
  REENACT_CHECK(std::isfinite(frame_rate_hz) && frame_rate_hz > 0, "frame_rate_hz must be > 0");
  const double T = o.duration_s, r = o.ramp_s;
  const double v_max = 2 * kPi * o.radius_m / (T - r);
  // Distance walked by time t and the speed share v / v_max.
  auto distance = [&](double t) {
    if (r > 0 && t < r) return v_max * r * SmoothStepIntegral(t / r);
    if (r > 0 && t > T - r) return v_max * ((T - r) - r * SmoothStepIntegral((T - t) / r));
    return v_max * (r / 2 + (t - r));
  };
  auto share = [&](double t) {
    return r > 0 ? SmoothStep(0, r, t) * (1 - SmoothStep(T - r, T, t)) : 1.0;
  };
  const int frames = static_cast<int>(std::lround(T * frame_rate_hz));
  std::vector<BodyPose> poses;
  poses.reserve(frames);
  for (int k = 0; k < frames; ++k) {
    const double t = k / frame_rate_hz;
    const double s = distance(t);
    BodyPose pose = WalkCyclePose(s / o.stride_m, share(t));
    const double heading = s / o.radius_m;
    pose.root_yaw = heading;
    pose.root_xy =
        Eigen::Vector2d(o.radius_m * (1 - std::cos(heading)), -o.radius_m * std::sin(heading));
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace reenact::capture

#include "capture-client/synthetic/scenario.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "capture-client/synthetic/procedural.h"
#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr double kPi = std::numbers::pi;
double Deg(double d) { return d * kPi / 180; }

// Smoothly goes from a to b as t goes from t0 to t1.
double Ramp(double a, double b, double t0, double t1, double t) {
  return a + (b - a) * SmoothStep(t0, t1, t);
}

BodyPose CalibrationPose() {
  BodyPose p;
  p.left_arm.abduction = p.right_arm.abduction = Deg(88);
  p.left_leg.abduction = p.right_leg.abduction = Deg(4);
  return p;
}

BodyPose TurnAndKick(double t) {
  BodyPose p = CalibrationPose();
  // Arms come down.
  const double arms = Ramp(Deg(88), Deg(18), 0.7, 1.2, t);
  p.left_arm.abduction = p.right_arm.abduction = arms;
  p.left_arm.elbow = p.right_arm.elbow = Ramp(0, Deg(15), 0.7, 1.2, t);

  // The turn, with stepping and arm swing fading in and out.
  const double s = std::clamp((t - 1.2) / 2.8, 0.0, 1.0);
  p.root_yaw = 2 * kPi * SmoothStep(0, 1, s);
  const double envelope = std::sin(kPi * s);
  const double step = 2 * kPi * 2.5 * s;
  const double lift_left = std::max(0.0, std::sin(step)) * envelope;
  const double lift_right = std::max(0.0, -std::sin(step)) * envelope;
  p.left_leg.flexion = Deg(25) * lift_left;
  p.left_leg.knee = Deg(45) * lift_left;
  p.right_leg.flexion = Deg(25) * lift_right;
  p.right_leg.knee = Deg(45) * lift_right;
  p.left_arm.flexion = Deg(30) * std::sin(step) * envelope;
  p.right_arm.flexion = -Deg(30) * std::sin(step) * envelope;
  p.left_arm.elbow += Deg(30) * envelope;
  p.right_arm.elbow += Deg(30) * envelope;
  p.spine_twist = Deg(12) * std::sin(2 * kPi * s);

  // Front kick with the right leg.
  if (t >= 4.0 && t < 5.0) {
    const double k = t - 4.0;
    const double guard = SmoothStep(0, 0.2, k) * (1 - SmoothStep(0.8, 1.0, k));
    p.left_arm.flexion = p.right_arm.flexion = Deg(45) * guard;
    p.left_arm.elbow = p.right_arm.elbow = Deg(15) + Deg(95) * guard;
    p.left_arm.abduction = p.right_arm.abduction = Deg(18) + Deg(7) * guard;
    const double chamber = SmoothStep(0.05, 0.35, k) * (1 - SmoothStep(0.65, 0.95, k));
    const double extend = SmoothStep(0.35, 0.5, k) * (1 - SmoothStep(0.55, 0.7, k));
    p.right_leg.flexion = Deg(80) * chamber;
    p.right_leg.knee = Deg(100) * chamber * (1 - extend) + Deg(5) * extend;
    p.right_leg.ankle = Deg(30) * chamber;
    p.spine_bend = -Deg(10) * chamber;
  }

  // Arm raise.
  if (t >= 5.0) {
    const double r = t - 5.0;
    const double up = SmoothStep(0.0, 0.45, r) * (1 - SmoothStep(0.65, 1.0, r));
    p.right_arm.flexion = Deg(168) * up;
    p.right_arm.abduction = Deg(18) * (1 - up) + Deg(5) * up;
    p.right_arm.elbow = Deg(15) * (1 - up);
    p.left_arm.abduction = Deg(18) + Deg(80) * up;
    p.left_arm.elbow = Deg(15) * (1 - up);
    p.head_pitch = -Deg(10) * up;
  }
  return p;
}

Eigen::Isometry3d DefaultSensor() {
  return LookAt(Eigen::Vector3d(0.0, -3.0, 1.3), Eigen::Vector3d(0.0, 0.0, 0.95));
}

}  // namespace

std::vector<std::string> SyntheticScenarioNames() { return {"turn-and-kick", "calibration"}; }

Expected<Scenario> MakeScenario(std::string_view name) {
  Scenario s;
  s.name = std::string(name);
  s.frame_rate_hz = 30;
  s.world_from_sensor = DefaultSensor();
  if (name == "turn-and-kick") {
    for (int i = 0; i < 180; ++i) s.poses.push_back(TurnAndKick(i / s.frame_rate_hz));
  } else if (name == "calibration") {
    s.poses.assign(30, CalibrationPose());
  } else {
    std::string known;
    for (const std::string& n : SyntheticScenarioNames()) known += (known.empty() ? "" : ", ") + n;
    return MakeError("not_found", "unknown synthetic scenario '" + std::string(name) +
                                      "'; known scenarios: " + known);
  }
  return s;
}

Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  REENACT_CHECK(eye.allFinite() && target.allFinite(), "LookAt needs finite points");
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d side = z.cross(Eigen::Vector3d::UnitZ());
  REENACT_CHECK(side.norm() > 1e-6, "LookAt needs a view direction that is not vertical");
  const Eigen::Vector3d x = side.normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  world_from_camera.linear().col(0) = x;
  world_from_camera.linear().col(1) = y;
  world_from_camera.linear().col(2) = z;
  world_from_camera.translation() = eye;
  return world_from_camera;
}

}  // namespace reenact::capture

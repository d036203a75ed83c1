#include "synthetic/scenario.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "common/error/check.h"
#include "synthetic/bvh_motion.h"
#include "synthetic/handheld_trajectory.h"
#include "synthetic/procedural.h"
#include "synthetic/room.h"
#include "synthetic/sensor_placement.h"
#include "synthetic/walk_motion.h"

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

// A full turn in place to the left over s in [0, 1] (smooth start and stop), `steps` steps
// and the arms swinging by +-swing_rad (added to their flexion, the elbows bending by as
// much), all fading in and out; the legs and the spine's twist are set.
void TurnInPlace(double s, double steps, double swing_rad, BodyPose* p) {
  p->root_yaw = 2 * kPi * SmoothStep(0, 1, s);
  const double envelope = std::sin(kPi * s);
  const double step = 2 * kPi * steps * s;
  const double lift_left = std::max(0.0, std::sin(step)) * envelope;
  const double lift_right = std::max(0.0, -std::sin(step)) * envelope;
  p->left_leg.flexion = Deg(25) * lift_left;
  p->left_leg.knee = Deg(45) * lift_left;
  p->right_leg.flexion = Deg(25) * lift_right;
  p->right_leg.knee = Deg(45) * lift_right;
  p->left_arm.flexion += swing_rad * std::sin(step) * envelope;
  p->right_arm.flexion += -swing_rad * std::sin(step) * envelope;
  p->left_arm.elbow += swing_rad * envelope;
  p->right_arm.elbow += swing_rad * envelope;
  p->spine_twist = Deg(12) * std::sin(2 * kPi * s);
}

BodyPose TurnAndKick(double t) {
  BodyPose p = CalibrationPose();
  // Arms come down.
  const double arms = Ramp(Deg(88), Deg(18), 0.7, 1.2, t);
  p.left_arm.abduction = p.right_arm.abduction = arms;
  p.left_arm.elbow = p.right_arm.elbow = Ramp(0, Deg(15), 0.7, 1.2, t);

  // The turn, with stepping and arm swing fading in and out.
  const double s = std::clamp((t - 1.2) / 2.8, 0.0, 1.0);
  TurnInPlace(s, 2.5, Deg(30), &p);

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

// raise-and-crouch (see scenario.h). The legs' angles of the squat at depth c in [0, 1];
// the ankle dorsiflexes by the shin's forward tilt so the foot stays flat (heel down).
BodyPose RaiseAndCrouch(double t) {
  BodyPose p = CalibrationPose();
  // Arms come down to the sides.
  const double down = SmoothStep(0.7, 1.2, t);
  // Both arms raised forward to horizontal, then overhead, back to forward for the squat,
  // and down to the sides after rising.
  const double forward = SmoothStep(1.2, 1.9, t) * (1 - SmoothStep(5.2, 5.9, t));
  const double overhead = SmoothStep(1.9, 2.6, t) * (1 - SmoothStep(2.9, 3.4, t));
  for (ArmPose* arm : {&p.left_arm, &p.right_arm}) {
    arm->abduction = Deg(88) + (Deg(18) - Deg(88)) * down - Deg(12) * forward;
    arm->flexion = Deg(90) * forward + Deg(78) * overhead;
    arm->elbow = Deg(15) * down * (1 - forward);
  }
  p.head_pitch = -Deg(12) * overhead;

  // The squat: down 3.3-4.4 s, held to 4.8 s, up by 5.6 s.
  const double c = SmoothStep(3.3, 4.4, t) * (1 - SmoothStep(4.8, 5.6, t));
  // The legs bend in a plane tilted out by the abduction, so the ankle's sideways offset
  // from the hip is sin(abduction) times the leg's vertical reach in that plane; the
  // abduction grows as the reach shrinks to keep that offset, i.e. the feet where they stand.
  const BodyDimensions d;
  const double stand_abduction = p.left_leg.abduction;
  const double flexion = Deg(105) * c, knee = Deg(135) * c;
  const double reach = d.thigh * std::cos(flexion) + d.shin * std::cos(knee - flexion);
  const double abduction =
      std::asin(std::min(1.0, std::sin(stand_abduction) * (d.thigh + d.shin) / reach));
  for (LegPose* leg : {&p.left_leg, &p.right_leg}) {
    leg->flexion = flexion;
    leg->knee = knee;
    leg->abduction = abduction;
    leg->ankle = flexion - knee;   // sole flat: shin tilt + ankle = 0,
    leg->ankle_roll = -abduction;  // and no sideways tilt
  }
  p.spine_bend = Deg(50) * c;
  p.head_pitch -= Deg(25) * c;  // keeps looking ahead while the trunk leans forward
  return p;
}

// upper-body-turn (see scenario.h): the subject's place and the sensor in front of it.
constexpr double kCloseUpSpotY = 1.0;       // the waist at world (0, 1)
constexpr double kCloseUpDistanceM = 0.91;  // sensor to the body's vertical axis
constexpr double kCloseUpHeightM = 1.25;    // sensor height, looking level

BodyPose UpperBodyTurn(double t) {
  BodyPose p;
  p.root_xy = Eigen::Vector2d(0, kCloseUpSpotY);
  p.left_leg.abduction = p.right_leg.abduction = Deg(4);
  // Arms relaxed at the sides, the elbows a little bent.
  for (ArmPose* arm : {&p.left_arm, &p.right_arm}) {
    arm->abduction = Deg(10);
    arm->elbow = Deg(20);
  }
  // A wave with the right hand: raised in front of the shoulder, waved side to side, lowered.
  const double up = SmoothStep(0.3, 0.7, t) * (1 - SmoothStep(1.3, 1.7, t));
  const double strokes = SmoothStep(0.6, 0.8, t) * (1 - SmoothStep(1.2, 1.4, t));
  p.right_arm.abduction += Deg(40) * up + Deg(12) * std::sin(2 * kPi * 2.5 * (t - 0.7)) * strokes;
  p.right_arm.elbow += Deg(120) * up;

  // The turn, with stepping and arm swing fading in and out (as turn-and-kick's).
  const double s = std::clamp((t - 1.7) / 3.6, 0.0, 1.0);
  TurnInPlace(s, 3, Deg(25), &p);

  // Both forearms come up forward (hands in front of the waist), held, and lowered.
  const double reach = SmoothStep(5.3, 5.8, t) * (1 - SmoothStep(6.1, 6.5, t));
  for (ArmPose* arm : {&p.left_arm, &p.right_arm}) {
    arm->flexion += Deg(5) * reach;
    arm->elbow += Deg(45) * reach;
  }
  return p;
}

// Moves each pose's waist so that the mid-point of the ankles stays where it stands in
// `standing`: PoseBody keeps the lower ankle at its height above the floor, but bending the
// legs moves the ankles forward of the hips, which would slide the feet along the floor.
void PlantFeet(const BodyPose& standing, std::vector<BodyPose>* poses) {
  auto mid_ankles = [](const BodyPose& p) {
    const Skeleton s = PoseBody(p).skeleton;
    return Eigen::Vector2d(((s[Joint::kLeftFoot] + s[Joint::kRightFoot]) / 2).head<2>());
  };
  const Eigen::Vector2d target = mid_ankles(standing);
  for (BodyPose& p : *poses) p.root_xy += target - mid_ankles(p);
}

// 0-0.7 s the calibration pose, 0.7-1.2 s the arms come down to the walk's first pose,
// then the circle walk.
std::vector<BodyPose> WalkHandheldPoses(double rate) {
  CircleWalkOptions walk;
  walk.duration_s = 6.3;
  const std::vector<BodyPose> circle = CircleWalk(walk, rate);
  const BodyPose from = CalibrationPose(), to = circle.front();
  std::vector<BodyPose> poses;
  for (int k = 0; k < static_cast<int>(std::lround(1.2 * rate)); ++k) {
    const double t = k / rate;
    BodyPose p = to;
    for (auto [arm, a, b] : {std::tuple{&p.left_arm, &from.left_arm, &to.left_arm},
                             std::tuple{&p.right_arm, &from.right_arm, &to.right_arm}}) {
      arm->abduction = Ramp(a->abduction, b->abduction, 0.7, 1.2, t);
      arm->elbow = Ramp(a->elbow, b->elbow, 0.7, 1.2, t);
    }
    for (auto [leg, a, b] : {std::tuple{&p.left_leg, &from.left_leg, &to.left_leg},
                             std::tuple{&p.right_leg, &from.right_leg, &to.right_leg}})
      leg->abduction = Ramp(a->abduction, b->abduction, 0.7, 1.2, t);
    poses.push_back(p);
  }
  poses.insert(poses.end(), circle.begin(), circle.end());
  return poses;
}

Eigen::Isometry3d DefaultSensor() {
  return LookAt(Eigen::Vector3d(0.0, -3.0, 1.3), Eigen::Vector3d(0.0, 0.0, 0.95));
}

}  // namespace

int Scenario::frame_count() const {
  if (!poses.empty()) return static_cast<int>(poses.size());
  if (!target_skeletons.empty()) return static_cast<int>(target_skeletons.size());
  if (model_animation) return model_animation_frames;
  return 0;
}

std::vector<std::string> SyntheticScenarioNames() {
  return {"turn-and-kick", "raise-and-crouch", "upper-body-turn", "walk-handheld",
          "calibration",   "model-walk",       "bvh:FILE"};
}

Expected<Scenario> MakeScenario(std::string_view name, uint64_t seed) {
  Scenario s;
  s.name = std::string(name);
  s.frame_rate_hz = 30;
  if (name.starts_with("bvh:")) {
    auto fail = [&](const Error& e) {
      return MakeError(e.code, "scenario '" + s.name + "': " + e.message);
    };
    const std::string path(name.substr(4));
    if (path.empty()) return fail(MakeError("invalid_argument", "bvh: needs a file path"));
    BvhMotionOptions options;
    options.frame_rate_hz = s.frame_rate_hz;
    Expected<BvhMotion> motion = LoadBvhMotion(path, options);
    if (!motion.ok()) return fail(motion.error());
    s.target_skeletons = std::move(motion->skeletons);
    Expected<Eigen::Isometry3d> sensor =
        PlaceStaticSensor(s.target_skeletons, PinholeCamera::KinectLike(), *SharedRoom());
    if (!sensor.ok())
      return fail(MakeError(sensor.error().code, path + ": " + sensor.error().message));
    s.world_from_sensor.assign(s.frame_count(), *sensor);
    return s;
  }
  if (name == "walk-handheld") {
    s.poses = WalkHandheldPoses(s.frame_rate_hz);
    std::vector<Eigen::Vector3d> target;
    for (const BodyPose& p : s.poses) target.emplace_back(p.root_xy.x(), p.root_xy.y(), 0.9);
    const std::vector<Eigen::Vector3d> path =
        OperatorArc(OperatorArcOptions{}, s.frame_count(), s.frame_rate_hz);
    HandheldOptions handheld;
    handheld.seed = seed;
    s.world_from_sensor = HandheldSensorPoses(path, target, s.frame_rate_hz, handheld);
    return s;
  }
  if (name == "turn-and-kick") {
    for (int i = 0; i < 180; ++i) s.poses.push_back(TurnAndKick(i / s.frame_rate_hz));
  } else if (name == "raise-and-crouch") {
    for (int i = 0; i < 180; ++i) s.poses.push_back(RaiseAndCrouch(i / s.frame_rate_hz));
    PlantFeet(CalibrationPose(), &s.poses);
  } else if (name == "upper-body-turn") {
    for (int i = 0; i < 195; ++i) s.poses.push_back(UpperBodyTurn(i / s.frame_rate_hz));
    const Eigen::Vector3d target(0, kCloseUpSpotY, kCloseUpHeightM);
    s.world_from_sensor.assign(s.frame_count(),
                               LookAt(target - Eigen::Vector3d(0, kCloseUpDistanceM, 0), target));
    return s;
  } else if (name == "calibration") {
    s.poses.assign(30, CalibrationPose());
  } else if (name == "model-walk") {
    s.model_animation = true;
    s.model_animation_frames = 120;
  } else {
    std::string known;
    for (const std::string& n : SyntheticScenarioNames()) known += (known.empty() ? "" : ", ") + n;
    return MakeError("not_found", "unknown synthetic scenario '" + std::string(name) +
                                      "'; known scenarios: " + known);
  }
  s.world_from_sensor.assign(s.frame_count(), DefaultSensor());
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

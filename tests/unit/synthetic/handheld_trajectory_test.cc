#include "synthetic/handheld_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "synthetic/sensor_placement.h"

namespace reenact::capture {
namespace {

constexpr double kRate = 30;

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180 / std::numbers::pi;
}

void ExpectRotation(const Eigen::Matrix3d& r) {
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1, 1e-12);
}

// A straight 2 m walk along x at 1.4 m, aiming at a point 3 m ahead in y.
std::vector<Eigen::Vector3d> Line(int n) {
  std::vector<Eigen::Vector3d> p;
  for (int k = 0; k < n; ++k) p.emplace_back(2.0 * k / (n - 1), 0, 1.4);
  return p;
}
std::vector<Eigen::Vector3d> Ahead(const std::vector<Eigen::Vector3d>& path) {
  std::vector<Eigen::Vector3d> t;
  for (const auto& p : path) t.push_back(p + Eigen::Vector3d(0, 3, -0.5));
  return t;
}

TEST(HandheldTrajectory, WithoutShakeOrBobTheSensorAimsExactlyAtTheTarget) {
  const auto path = Line(31), target = Ahead(path);
  HandheldOptions still;
  still.bob_amplitude_m = still.shake_translation_m = still.shake_rotation_deg = 0;
  const auto poses = HandheldSensorPoses(path, target, kRate, still);
  ASSERT_EQ(poses.size(), path.size());
  for (size_t k = 0; k < poses.size(); ++k) {
    ExpectRotation(poses[k].linear());
    EXPECT_LT((poses[k].translation() - path[k]).norm(), 1e-12);
    // The target lies on the optical axis (camera x = y = 0), in front.
    const Eigen::Vector3d t = poses[k].inverse() * target[k];
    EXPECT_NEAR(t.x(), 0, 1e-9);
    EXPECT_NEAR(t.y(), 0, 1e-9);
    EXPECT_GT(t.z(), 0);
  }
}

TEST(HandheldTrajectory, ShakeStaysWithinItsBoundsAndIsPresent) {
  const auto path = Line(121), target = Ahead(path);
  HandheldOptions still;
  still.bob_amplitude_m = still.shake_translation_m = still.shake_rotation_deg = 0;
  HandheldOptions shaky;
  shaky.bob_amplitude_m = 0;  // translation shake only, per axis <= 3 mm
  const auto a = HandheldSensorPoses(path, target, kRate, still);
  const auto b = HandheldSensorPoses(path, target, kRate, shaky);
  double largest_offset = 0, largest_angle = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    ExpectRotation(b[k].linear());
    const Eigen::Vector3d d = b[k].translation() - a[k].translation();
    EXPECT_LE(d.cwiseAbs().maxCoeff(), shaky.shake_translation_m + 1e-12);
    largest_offset = std::max(largest_offset, d.norm());
    // Three axis angles of at most 0.3 degrees each, plus the change of aim the 3 mm move
    // causes at 3 m (0.06 degrees): well under 1 degree.
    const double angle = AngleDeg(a[k].linear(), b[k].linear());
    EXPECT_LT(angle, 1.0);
    largest_angle = std::max(largest_angle, angle);
  }
  EXPECT_GT(largest_offset, 0.001);
  EXPECT_GT(largest_angle, 0.05);
}

TEST(HandheldTrajectory, BobFollowsTheOperatorsSteps) {
  // Walking at constant speed: the bob is the full sinusoid at the step frequency.
  const auto path = Line(61), target = Ahead(path);
  HandheldOptions bob;
  bob.shake_translation_m = bob.shake_rotation_deg = 0;
  const auto poses = HandheldSensorPoses(path, target, kRate, bob);
  for (size_t k = 1; k + 1 < poses.size(); ++k) {
    const double t = k / kRate;
    EXPECT_NEAR(poses[k].translation().z() - 1.4,
                bob.bob_amplitude_m * std::sin(2 * std::numbers::pi * bob.step_frequency_hz * t),
                1e-12);
  }
  // Standing still: no bob.
  const std::vector<Eigen::Vector3d> still(20, Eigen::Vector3d(0, 0, 1.4));
  for (const auto& p : HandheldSensorPoses(still, Ahead(still), kRate, bob))
    EXPECT_NEAR(p.translation().z(), 1.4, 1e-15);
}

TEST(HandheldTrajectory, DeterministicPerSeed) {
  const auto path = Line(40), target = Ahead(path);
  HandheldOptions one, two;
  two.seed = 2;
  const auto a = HandheldSensorPoses(path, target, kRate, one);
  const auto b = HandheldSensorPoses(path, target, kRate, one);
  const auto c = HandheldSensorPoses(path, target, kRate, two);
  bool differs = false;
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].matrix(), b[k].matrix());
    differs |= (a[k].matrix() - c[k].matrix()).norm() > 1e-6;
  }
  EXPECT_TRUE(differs);
}

TEST(HandheldTrajectory, DegenerateInputThrows) {
  const auto path = Line(5);
  EXPECT_THROW(HandheldSensorPoses({}, {}, kRate), CheckError);
  EXPECT_THROW(HandheldSensorPoses(path, Ahead(Line(4)), kRate), CheckError);
  EXPECT_THROW(HandheldSensorPoses(path, Ahead(path), 0), CheckError);
  // Looking straight down: the view direction is vertical.
  std::vector<Eigen::Vector3d> below = path;
  for (auto& p : below) p.z() = 0;
  HandheldOptions still;
  still.bob_amplitude_m = still.shake_translation_m = still.shake_rotation_deg = 0;
  EXPECT_THROW(HandheldSensorPoses(path, below, kRate, still), CheckError);
  HandheldOptions bad;
  bad.shake_rotation_deg = -1;
  EXPECT_THROW(HandheldSensorPoses(path, Ahead(path), kRate, bad), CheckError);
}

TEST(HandheldTrajectory, OperatorArcFollowsItsDefinition) {
  OperatorArcOptions o;
  const auto path = OperatorArc(o, 211, kRate);
  ASSERT_EQ(path.size(), 211u);
  auto azimuth = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d d = p.head<2>() - o.centre;
    return std::atan2(d.x(), -d.y()) * 180 / std::numbers::pi;
  };
  EXPECT_NEAR(azimuth(path.front()), o.start_azimuth_deg, 1e-9);
  EXPECT_NEAR(azimuth(path.back()), o.end_azimuth_deg, 1e-9);
  EXPECT_NEAR(azimuth(path[105]), (o.start_azimuth_deg + o.end_azimuth_deg) / 2, 1e-9);
  for (const auto& p : path) {
    const double r = (p.head<2>() - o.centre).norm();
    EXPECT_LE(r, o.radius_m + o.radius_wobble_m + 1e-12);
    EXPECT_GE(r, o.radius_m - o.radius_wobble_m - 1e-12);
    EXPECT_LE(p.z(), o.height_m + o.height_drift_m + 1e-12);
    EXPECT_GE(p.z(), o.height_m - o.height_drift_m - 1e-12);
  }
  EXPECT_THROW(OperatorArc(o, 0, kRate), CheckError);
}

// --- the walk-handheld scenario ---

const Scenario& WalkHandheld() {
  static const Scenario s = MakeScenario("walk-handheld").value();
  return s;
}

TEST(WalkHandheld, HasOnePosePerFrameForSubjectAndSensor) {
  const Scenario& s = WalkHandheld();
  EXPECT_EQ(s.frame_count(), 225);  // 7.5 s at 30 fps
  EXPECT_EQ(s.poses.size(), 225u);
  EXPECT_EQ(s.world_from_sensor.size(), 225u);
  EXPECT_TRUE(s.target_skeletons.empty());
  for (const auto& pose : s.world_from_sensor) ExpectRotation(pose.linear());
}

TEST(WalkHandheld, TheSubjectStaysInViewOnEveryFrame) {
  // Every joint, grown by 15 cm of body, inside the 640x480 image with 8 px to spare, at
  // least 1 m in front of the sensor and not hidden behind furniture.
  const Scenario& s = WalkHandheld();
  const RoomModel& room = *SharedRoom();
  const PinholeCamera camera = PinholeCamera::KinectLike();
  for (int k = 0; k < s.frame_count(); ++k)
    EXPECT_TRUE(SensorSeesSkeleton(PoseBody(s.poses[k]).skeleton, camera, s.world_from_sensor[k],
                                   room, StaticSensorOptions{}))
        << "frame " << k;
}

TEST(WalkHandheld, TheSensorMovesLikeAHandHeldCamera) {
  // Bounds of a camera carried by a walking person: height 1.2-1.6 m; speed under 1.5 m/s
  // (a walk); acceleration under 5 m/s^2 (half of g; the bob gives 1.5, the shake 0.3);
  // turning under 90 deg/s. The sensor stays inside the room, off the furniture.
  const Scenario& s = WalkHandheld();
  const RoomModel& room = *SharedRoom();
  const double dt = 1 / s.frame_rate_hz;
  double travelled = 0;
  for (int k = 0; k < s.frame_count(); ++k) {
    const Eigen::Vector3d p = s.world_from_sensor[k].translation();
    EXPECT_GE(p.z(), 1.2);
    EXPECT_LE(p.z(), 1.6);
    EXPECT_TRUE(((p - room.room_min).array() > 0.3).all() &&
                ((room.room_max - p).array() > 0.3).all())
        << p.transpose();
    for (const Box& box : room.furniture)
      EXPECT_FALSE((p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all());
    if (k == 0) continue;
    const Eigen::Vector3d v = (p - s.world_from_sensor[k - 1].translation()) / dt;
    travelled += v.norm() * dt;
    EXPECT_LT(v.norm(), 1.5) << k;
    EXPECT_LT(AngleDeg(s.world_from_sensor[k - 1].linear(), s.world_from_sensor[k].linear()) / dt,
              90)
        << k;
    if (k + 1 < s.frame_count()) {
      const Eigen::Vector3d a = (s.world_from_sensor[k + 1].translation() - 2 * p +
                                 s.world_from_sensor[k - 1].translation()) /
                                (dt * dt);
      EXPECT_LT(a.norm(), 5.0) << k;
    }
  }
  // The operator really walks: the arc of 45 degrees at about 3.2 m is about 2.5 m long.
  EXPECT_GT(travelled, 2.2);
}

TEST(WalkHandheld, IsDeterministicAndTheSeedOnlyShakes) {
  const Scenario& a = WalkHandheld();
  const Scenario b = MakeScenario("walk-handheld").value();
  const Scenario c = MakeScenario("walk-handheld", 7).value();
  for (int k = 0; k < a.frame_count(); ++k) {
    EXPECT_EQ(a.world_from_sensor[k].matrix(), b.world_from_sensor[k].matrix());
    // Two shakes of at most 3 mm per axis each.
    EXPECT_LE((a.world_from_sensor[k].translation() - c.world_from_sensor[k].translation())
                  .cwiseAbs()
                  .maxCoeff(),
              0.006 + 1e-12);
    EXPECT_LT(AngleDeg(a.world_from_sensor[k].linear(), c.world_from_sensor[k].linear()), 2.0);
    EXPECT_EQ(PoseBody(a.poses[k]).skeleton.position, PoseBody(c.poses[k]).skeleton.position);
  }
}

}  // namespace
}  // namespace reenact::capture

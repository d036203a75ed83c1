// The raise-and-crouch scenario, checked from its construction: a squat lowers the waist with
// the feet planted and flat, the knees bent past a right angle, the body balanced over the
// feet and always in view of the sensor.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "synthetic/body_model.h"
#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "synthetic/sensor_placement.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

using Eigen::Vector3d;

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

double Degrees(double rad) { return rad * 180 / std::numbers::pi; }

// The bend of the knee: the angle between the thigh (hip -> knee) and the shin (knee ->
// ankle) directions; 0 for a straight leg.
double KneeBend(const Skeleton& s, Joint hip, Joint knee, Joint foot) {
  const Vector3d thigh = (s[knee] - s[hip]).normalized(), shin = (s[foot] - s[knee]).normalized();
  return Degrees(std::acos(std::clamp(thigh.dot(shin), -1.0, 1.0)));
}

Scenario Make() {
  Expected<Scenario> s = MakeScenario("raise-and-crouch");
  EXPECT_TRUE(s.ok()) << s.error().message;
  return std::move(s).value();
}

// The frame with the lowest waist.
int BottomFrame(const std::vector<Skeleton>& skeletons) {
  int bottom = 0;
  for (int k = 0; k < static_cast<int>(skeletons.size()); ++k)
    if (skeletons[k][Joint::kWaist].z() < skeletons[bottom][Joint::kWaist].z()) bottom = k;
  return bottom;
}

std::vector<Skeleton> ProceduralSkeletons(const Scenario& s) {
  std::vector<Skeleton> out;
  for (const BodyPose& p : s.poses) out.push_back(PoseBody(p).skeleton);
  return out;
}

TEST(BodyModel, AnkleRollTurnsTheFootAboutItsLongAxis) {
  BodyPose p;
  p.left_leg.abduction = p.right_leg.abduction = 0.3;
  const PosedBody tilted = PoseBody(p);
  p.left_leg.ankle_roll = p.right_leg.ankle_roll = -0.3;
  const PosedBody flat = PoseBody(p);
  for (Segment foot : {Segment::kLeftFoot, Segment::kRightFoot}) {
    const int f = static_cast<int>(foot);
    // Abduction alone tilts the sole by the abduction; the opposite roll levels it, about
    // the foot's long axis (which the roll leaves as it was) and not moving the ankle.
    EXPECT_NEAR(tilted.world_from_segment[f].linear().col(2).z(), std::cos(0.3), 1e-12);
    EXPECT_NEAR(flat.world_from_segment[f].linear().col(2).z(), 1, 1e-12);
    EXPECT_TRUE(flat.world_from_segment[f].linear().col(0).isApprox(
        tilted.world_from_segment[f].linear().col(0), 1e-12));
    EXPECT_TRUE(flat.world_from_segment[f].translation().isApprox(
        tilted.world_from_segment[f].translation(), 1e-12));
  }
}

TEST(RaiseAndCrouch, IsListedAndLastsSixSecondsAtThirtyHertz) {
  const auto names = SyntheticScenarioNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "raise-and-crouch"), names.end());
  const Scenario s = Make();
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, 30);
  EXPECT_EQ(s.frame_count(), 180);
  EXPECT_EQ(s.world_from_sensor.size(), s.poses.size());
  for (const auto& pose : s.world_from_sensor)
    EXPECT_EQ(pose.matrix(), s.world_from_sensor.front().matrix());
}

TEST(RaiseAndCrouch, StartsInTheCalibrationPose) {
  const Scenario s = Make();
  const Skeleton first = PoseBody(s.poses.front()).skeleton;
  // Arms out: each hand about level with its shoulder and far out to the side.
  for (auto [shoulder, hand] : {std::pair{Joint::kLeftShoulder, Joint::kLeftHand},
                                std::pair{Joint::kRightShoulder, Joint::kRightHand}}) {
    EXPECT_NEAR(first[hand].z(), first[shoulder].z(), 0.05);
    EXPECT_GT(std::abs(first[hand].x() - first[shoulder].x()), 0.55);
  }
}

TEST(RaiseAndCrouch, RaisesBothArmsForwardThenOverhead) {
  const Scenario s = Make();
  const std::vector<Skeleton> sk = ProceduralSkeletons(s);
  // At 1.9 s both arms point forward (world -y) at shoulder height; at 2.75 s overhead.
  const Skeleton& forward = sk[57];
  const Skeleton& overhead = sk[82];
  for (auto [shoulder, hand] : {std::pair{Joint::kLeftShoulder, Joint::kLeftHand},
                                std::pair{Joint::kRightShoulder, Joint::kRightHand}}) {
    EXPECT_NEAR(forward[hand].z(), forward[shoulder].z(), 0.05);
    EXPECT_LT(forward[hand].y() - forward[shoulder].y(), -0.55);
    EXPECT_GT(overhead[hand].z(), overhead[Joint::kHead].z() + 0.3);
  }
}

TEST(RaiseAndCrouch, SquatsDeepWithTheFeetPlantedAndFlat) {
  const Scenario s = Make();
  const std::vector<Skeleton> sk = ProceduralSkeletons(s);
  const int bottom = BottomFrame(sk);
  const Skeleton& stand = sk.front();
  const Skeleton& low = sk[bottom];
  EXPECT_LT(low[Joint::kWaist].z(), stand[Joint::kWaist].z() - 0.3);
  EXPECT_GT(KneeBend(low, Joint::kLeftHip, Joint::kLeftKnee, Joint::kLeftFoot), 90);
  EXPECT_GT(KneeBend(low, Joint::kRightHip, Joint::kRightKnee, Joint::kRightFoot), 90);
  // And rises again: the last frame stands as the first.
  EXPECT_NEAR(sk.back()[Joint::kWaist].z(), stand[Joint::kWaist].z(), 1e-3);

  for (int k = 0; k < s.frame_count(); ++k) {
    const PosedBody body = PoseBody(s.poses[k]);
    for (auto [foot, segment] : {std::pair{Joint::kLeftFoot, Segment::kLeftFoot},
                                 std::pair{Joint::kRightFoot, Segment::kRightFoot}}) {
      // Ankles within 2 cm of where they stand, in height and along the floor.
      EXPECT_NEAR(body.skeleton[foot].z(), stand[foot].z(), 0.02) << k;
      EXPECT_LT((body.skeleton[foot] - stand[foot]).head<2>().norm(), 0.02) << k;
      // Heel down and the sole flat: the foot's up axis (segment z) stays vertical.
      const Vector3d up = body.world_from_segment[static_cast<int>(segment)].linear().col(2);
      EXPECT_GT(up.z(), 1 - 1e-9) << k;
    }
  }
}

TEST(RaiseAndCrouch, TheTrunkLeansForwardAndTheBodyStaysBalancedOverTheFeet) {
  const Scenario s = Make();
  const std::vector<Skeleton> sk = ProceduralSkeletons(s);
  const Skeleton& b = sk[BottomFrame(sk)];
  // Facing world -y: forward is -y. The neck ahead of the waist (trunk leaning forward).
  EXPECT_LT(b[Joint::kNeck].y(), b[Joint::kWaist].y() - 0.15);
  // Centre of mass from segment mass fractions (Winter, Biomechanics and Motor Control of
  // Human Movement, table 4.1), each at its segment's mid-point (trunk: waist to neck; head;
  // feet at the ankle), compared with the support: the feet reach from about 7 cm behind
  // the ankle (heel) to 20 cm ahead of it (toe), body_mesh.cc's foot capsule.
  auto mid = [&](Joint a, Joint c) { return Vector3d((b[a] + b[c]) / 2); };
  Vector3d com = 0.081 * b[Joint::kHead] + 0.497 * mid(Joint::kWaist, Joint::kNeck);
  for (int side = 0; side < 2; ++side) {
    const bool l = side == 0;
    com += 0.028 * mid(l ? Joint::kLeftShoulder : Joint::kRightShoulder,
                       l ? Joint::kLeftElbow : Joint::kRightElbow);
    com += 0.022 * mid(l ? Joint::kLeftElbow : Joint::kRightElbow,
                       l ? Joint::kLeftHand : Joint::kRightHand);
    com += 0.100 *
           mid(l ? Joint::kLeftHip : Joint::kRightHip, l ? Joint::kLeftKnee : Joint::kRightKnee);
    com += 0.0465 *
           mid(l ? Joint::kLeftKnee : Joint::kRightKnee, l ? Joint::kLeftFoot : Joint::kRightFoot);
    com += 0.0145 * b[l ? Joint::kLeftFoot : Joint::kRightFoot];
  }
  const double ankle_y = (b[Joint::kLeftFoot].y() + b[Joint::kRightFoot].y()) / 2;
  const double ahead_of_ankle = ankle_y - com.y();  // forward is -y
  EXPECT_GT(ahead_of_ankle, -0.07);
  EXPECT_LT(ahead_of_ankle, 0.20);
}

TEST(RaiseAndCrouch, TheWholeBodyStaysInTheSensorImage) {
  const Scenario s = Make();
  const std::vector<Skeleton> sk = ProceduralSkeletons(s);
  const PinholeCamera camera = PinholeCamera::KinectLike();
  // Every joint grown by 15 cm of flesh projects 8 px inside the image, in front of the
  // sensor, unoccluded by furniture (sensor_placement.h).
  for (int k = 0; k < s.frame_count(); ++k)
    EXPECT_TRUE(SensorSeesSkeleton(sk[k], camera, s.world_from_sensor[k], *SharedRoom(),
                                   StaticSensorOptions{}))
        << k;
}

TEST(RaiseAndCrouch, PlaysOnTheProceduralBodyWithTheSubjectInsideTheImage) {
  const auto scene = SyntheticScene::Create("raise-and-crouch");
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  std::vector<Skeleton> sk;
  for (int k = 0; k < scene->frame_count(); ++k) sk.push_back(scene->skeleton_in_world(k));
  for (int k : {0, 80, BottomFrame(sk)}) {
    const SyntheticView v = scene->RenderSensor(k, {.draw_room = false});
    int subject = 0, on_border = 0;
    for (int y = 0; y < v.mask.height; ++y)
      for (int x = 0; x < v.mask.width; ++x) {
        if (v.mask.at(x, y) == 0) continue;
        ++subject;
        on_border += x == 0 || y == 0 || x == v.mask.width - 1 || y == v.mask.height - 1;
      }
    EXPECT_GT(subject, 5000) << k;
    EXPECT_EQ(on_border, 0) << k;
  }
}

TEST(RaiseAndCrouch, PlaysOnTheSkinnedCesiumMan) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  const auto scene = SyntheticScene::Create("raise-and-crouch", 1, {.gltf_path = kCesiumMan});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  ASSERT_EQ(scene->frame_count(), 180);
  std::vector<Skeleton> sk;
  for (int k = 0; k < scene->frame_count(); ++k) sk.push_back(scene->skeleton_in_world(k));
  const int bottom = BottomFrame(sk);
  // The skin follows the bone directions with its own (shorter, 1.51 m body) legs: its hip
  // to ankle distance shrinks by more than half, far more than 0.3 m of waist drop.
  EXPECT_LT(sk[bottom][Joint::kWaist].z(), sk.front()[Joint::kWaist].z() - 0.3);
  EXPECT_GT(KneeBend(sk[bottom], Joint::kLeftHip, Joint::kLeftKnee, Joint::kLeftFoot), 90);
  const PinholeCamera camera = scene->sensor_camera();
  for (int k = 0; k < scene->frame_count(); ++k)
    EXPECT_TRUE(SensorSeesSkeleton(sk[k], camera, scene->world_from_sensor(k), *SharedRoom(),
                                   StaticSensorOptions{}))
        << k;
  const SyntheticView v = scene->RenderSensor(bottom, {.draw_room = false});
  int subject = 0;
  for (uint8_t m : v.mask.data) subject += m != 0;
  EXPECT_GT(subject, 5000);
}

}  // namespace
}  // namespace reenact::capture

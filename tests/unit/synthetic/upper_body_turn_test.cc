// The upper-body-turn scenario, checked from its construction: a close-up from 0.8 m that
// shows the head and the trunk to the hips, never the knees, the feet or the floor; the
// subject starts relaxed (not in the calibration pose) and turns a full circle, on both
// bodies, always beyond the sensor's minimum range.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "synthetic/body_model.h"
#include "synthetic/scenario.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

double Degrees(double rad) { return rad * 180 / std::numbers::pi; }

const SyntheticScene& Procedural() {
  static const SyntheticScene scene = SyntheticScene::Create("upper-body-turn").value();
  return scene;
}

// The scene on CesiumMan, or nullptr where the model is absent.
const SyntheticScene* Skinned() {
  static const std::optional<SyntheticScene> scene = []() -> std::optional<SyntheticScene> {
    if (!std::filesystem::exists(kCesiumMan)) return std::nullopt;
    SyntheticBodySpec body;
    body.gltf_path = kCesiumMan;
    auto s = SyntheticScene::Create("upper-body-turn", 1, body);
    EXPECT_TRUE(s.ok()) << s.error().message;
    if (!s.ok()) return std::nullopt;
    return std::move(s).value();
  }();
  return scene ? &*scene : nullptr;
}

// The sensor image's pixel where a world point projects, if it lies in front of the sensor
// and inside the image.
bool InImage(const SyntheticScene& scene, int frame, const Eigen::Vector3d& world) {
  const PinholeCamera& c = scene.sensor_camera();
  const auto uv = c.Project(scene.world_from_sensor(frame).inverse() * world, 0.05);
  return uv && uv->x() >= 0 && uv->y() >= 0 && uv->x() < c.width && uv->y() < c.height;
}

void ExpectUpperBodyInViewOnly(const SyntheticScene& scene, int step) {
  for (int f = 0; f < scene.frame_count(); f += step) {
    const Skeleton s = scene.skeleton_in_world(f);
    for (Joint j :
         {Joint::kHead, Joint::kNeck, Joint::kLeftShoulder, Joint::kRightShoulder, Joint::kTorso})
      EXPECT_TRUE(InImage(scene, f, s[j])) << JointName(j) << " frame " << f;
    for (Joint j : {Joint::kLeftKnee, Joint::kRightKnee, Joint::kLeftFoot, Joint::kRightFoot})
      EXPECT_FALSE(InImage(scene, f, s[j])) << JointName(j) << " frame " << f;
  }
}

// Renders every step-th frame without noise: every pixel off the subject sees the room
// above the floor (its depth, unprojected, lies more than 5 cm above the floor: a wall or
// furniture), and every pixel on the subject has a reading (nothing of it is nearer than the
// 0.4 m minimum range, where the reading would be 0).
void ExpectNoFloorAndTheSubjectInRange(const SyntheticScene& scene, int step) {
  const PinholeCamera& c = scene.sensor_camera();
  for (int f = 0; f < scene.frame_count(); f += step) {
    const SyntheticView view = scene.RenderSensor(f);
    const Eigen::Isometry3d world_from_sensor = scene.world_from_sensor(f);
    int floor = 0, subject_without_reading = 0;
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const double z = view.depth.at(x, y) / 1000.0;
        if (view.mask.at(x, y)) {
          subject_without_reading += z == 0;
          continue;
        }
        const Eigen::Vector3d p = world_from_sensor * c.Unproject(Eigen::Vector2d(x, y), z);
        floor += z == 0 || p.z() < 0.05;
      }
    EXPECT_EQ(floor, 0) << "frame " << f;
    EXPECT_EQ(subject_without_reading, 0) << "frame " << f;
  }
}

// The heading turned from the first frame to the last, degrees, counter-clockwise seen from
// above (to the subject's left), summed frame by frame: the hips' left-right line's angle
// about world z.
double AccumulatedTurnDeg(const SyntheticScene& scene) {
  auto angle = [&](int f) {
    const Skeleton s = scene.skeleton_in_world(f);
    const Eigen::Vector3d left = s[Joint::kLeftHip] - s[Joint::kRightHip];
    return std::atan2(left.y(), left.x());
  };
  double total = 0;
  for (int f = 1; f < scene.frame_count(); ++f) {
    const double d = std::remainder(angle(f) - angle(f - 1), 2 * std::numbers::pi);
    EXPECT_LT(std::abs(Degrees(d)), 30) << "frame " << f;  // the sum is unambiguous
    total += d;
  }
  return Degrees(total);
}

// The first frame: arms relaxed at the sides, not held out as in the calibration pose (where
// the hands are level with the shoulders).
void ExpectArmsDown(const Skeleton& first) {
  for (auto [shoulder, hand] : {std::pair{Joint::kLeftShoulder, Joint::kLeftHand},
                                std::pair{Joint::kRightShoulder, Joint::kRightHand}})
    EXPECT_LT(first[hand].z(), first[shoulder].z() - 0.3) << JointName(hand);
}

TEST(UpperBodyTurn, IsListedAndLastsSixAndAHalfSecondsAtThirtyHertz) {
  const auto names = SyntheticScenarioNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "upper-body-turn"), names.end());
  const Expected<Scenario> s = MakeScenario("upper-body-turn");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_DOUBLE_EQ(s->frame_rate_hz, 30);
  EXPECT_EQ(s->frame_count(), 195);
  EXPECT_EQ(s->poses.size(), s->world_from_sensor.size());
  for (const auto& pose : s->world_from_sensor)
    EXPECT_EQ(pose.matrix(), s->world_from_sensor.front().matrix());
}

TEST(UpperBodyTurn, TheSensorLooksLevelAtTheChestFromAbout80Centimetres) {
  const SyntheticScene& scene = Procedural();
  const Eigen::Isometry3d sensor = scene.world_from_sensor(0);
  const Skeleton s = scene.skeleton_in_world(0);
  // Between the trunk's middle and the shoulders, the optical axis horizontal.
  EXPECT_GT(sensor.translation().z(), s[Joint::kTorso].z());
  EXPECT_LT(sensor.translation().z(), s[Joint::kLeftShoulder].z());
  EXPECT_NEAR(sensor.linear().col(2).z(), 0, 1e-12);
  // The chest's surface, seen at the torso joint's pixel, 0.75-0.85 m away.
  const PinholeCamera& c = scene.sensor_camera();
  const auto uv = c.Project(sensor.inverse() * s[Joint::kTorso], 0.05);
  ASSERT_TRUE(uv);
  const SyntheticView view = scene.RenderSensor(0);
  const int x = static_cast<int>(uv->x()), y = static_cast<int>(uv->y());
  ASSERT_EQ(view.mask.at(x, y), 255);
  EXPECT_GT(view.depth.at(x, y), 750);
  EXPECT_LT(view.depth.at(x, y), 850);
}

TEST(UpperBodyTurn, ProceduralShowsTheUpperBodyAndNeverTheKneesOrFeet) {
  ExpectUpperBodyInViewOnly(Procedural(), 1);
}

TEST(UpperBodyTurn, SkinnedShowsTheUpperBodyAndNeverTheKneesOrFeet) {
  if (!Skinned()) GTEST_SKIP() << kCesiumMan << " not present";
  ExpectUpperBodyInViewOnly(*Skinned(), 1);
}

TEST(UpperBodyTurn, ProceduralShowsNoFloorAndStaysBeyondTheMinimumRange) {
  ExpectNoFloorAndTheSubjectInRange(Procedural(), 2);
}

TEST(UpperBodyTurn, SkinnedShowsNoFloorAndStaysBeyondTheMinimumRange) {
  if (!Skinned()) GTEST_SKIP() << kCesiumMan << " not present";
  ExpectNoFloorAndTheSubjectInRange(*Skinned(), 3);
}

TEST(UpperBodyTurn, TurnsAFullCircleToTheLeft) {
  // Procedural: the hips turn with root_yaw, 0 to 2 pi.
  EXPECT_NEAR(AccumulatedTurnDeg(Procedural()), 360, 1e-6);
  // CesiumMan retargeted from the procedural skeleton by bone directions.
  if (!Skinned()) GTEST_SKIP() << kCesiumMan << " not present";
  EXPECT_NEAR(AccumulatedTurnDeg(*Skinned()), 360, 5);
}

TEST(UpperBodyTurn, StartsWithTheArmsDownNotInTheCalibrationPose) {
  ExpectArmsDown(Procedural().skeleton_in_world(0));
  if (!Skinned()) GTEST_SKIP() << kCesiumMan << " not present";
  ExpectArmsDown(Skinned()->skeleton_in_world(0));
}

}  // namespace
}  // namespace reenact::capture

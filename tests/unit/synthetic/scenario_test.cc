#include "synthetic/scenario.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "synthetic/room.h"
#include "synthetic/sensor_placement.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

namespace fs = std::filesystem;

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string Mocap(const std::string& name) {
  return (fs::path(REENACT_SHARED_DATA_DIR) / "mocap" / name).string();
}

TEST(Scenario, FrameCountComesFromTheMotion) {
  Scenario s;
  EXPECT_EQ(s.frame_count(), 0);
  s.model_animation = true;
  s.model_animation_frames = 12;
  EXPECT_EQ(s.frame_count(), 12);
  s.target_skeletons.resize(5);
  EXPECT_EQ(s.frame_count(), 5);
  s.poses.resize(3);
  EXPECT_EQ(s.frame_count(), 3);
}

TEST(Scenario, ProceduralScenariosHaveOneSensorPosePerFrame) {
  for (const char* name : {"turn-and-kick", "calibration", "walk-handheld"}) {
    const auto s = MakeScenario(name);
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_GT(s->frame_count(), 0) << name;
    EXPECT_EQ(static_cast<int>(s->world_from_sensor.size()), s->frame_count()) << name;
    EXPECT_EQ(static_cast<int>(s->poses.size()), s->frame_count()) << name;
  }
  // The static ones: all poses equal.
  const auto t = MakeScenario("turn-and-kick");
  for (const auto& pose : t->world_from_sensor)
    EXPECT_EQ(pose.matrix(), t->world_from_sensor.front().matrix());
}

TEST(Scenario, NamesListTheNewScenarios) {
  const auto names = SyntheticScenarioNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "walk-handheld"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "bvh:FILE"), names.end());
  EXPECT_EQ(SyntheticScene::ScenarioNames(), names);
}

TEST(BvhScenario, CmuWalkStaysInViewOfAStaticSensor) {
  const std::string path = Mocap("cmu-131_01-walk.bvh");
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  const auto s = MakeScenario("bvh:" + path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(s->poses.empty());
  ASSERT_GT(s->frame_count(), 200);
  EXPECT_EQ(s->target_skeletons.size(), s->world_from_sensor.size());
  EXPECT_DOUBLE_EQ(s->frame_rate_hz, 30);
  const RoomModel& room = *SharedRoom();
  const PinholeCamera camera = PinholeCamera::KinectLike();
  for (int k = 0; k < s->frame_count(); ++k) {
    EXPECT_EQ(s->world_from_sensor[k].matrix(), s->world_from_sensor[0].matrix());
    EXPECT_TRUE(SensorSeesSkeleton(s->target_skeletons[k], camera, s->world_from_sensor[k], room,
                                   StaticSensorOptions{}))
        << k;
  }
  // The walk runs about 2.5 m towards world -y, past where the preferred sensor (3 m in front
  // of the start) would stand, so the sensor stands elsewhere, at 1.3 m.
  EXPECT_NEAR(s->world_from_sensor[0].translation().z(), 1.3, 1e-12);
  EXPECT_GT((s->world_from_sensor[0].translation() - Eigen::Vector3d(0, -3, 1.3)).norm(), 0.5);
}

TEST(BvhScenario, MissingFileNamesThePath) {
  const auto s = MakeScenario("bvh:/nonexistent/dance.bvh");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "not_found");
  EXPECT_TRUE(Contains(s.error().message, "/nonexistent/dance.bvh")) << s.error().message;
}

TEST(BvhScenario, EmptyPathIsAnError) {
  const auto s = MakeScenario("bvh:");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "invalid_argument");
}

TEST(BvhScenario, MalformedFileNamesThePathAndLine) {
  std::string pattern = (fs::temp_directory_path() / "reenact_bvh_XXXXXX").string();
  const fs::path dir = mkdtemp(pattern.data());
  const fs::path file = dir / "broken.bvh";
  std::ofstream(file) << "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition "
                         "Yposition Zposition\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n1 2 3\n";
  const auto s = MakeScenario("bvh:" + file.string());
  fs::remove_all(dir);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "corrupt");
  EXPECT_TRUE(Contains(s.error().message, file.string() + ":")) << s.error().message;
  EXPECT_TRUE(Contains(s.error().message, "truncated")) << s.error().message;
}

TEST(BvhScenario, TheProceduralBodyPlaysIt) {
  // Retargeted by bone directions (body_pose_from_skeleton.h; its tests check the motion).
  const std::string path = Mocap("cmu-131_02-walk.bvh");
  if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
  const auto scene = SyntheticScene::Create("bvh:" + path);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->frame_count(), MakeScenario("bvh:" + path)->frame_count());
  EXPECT_TRUE(scene->skeleton_in_world(scene->frame_count() - 1).Complete());
}

}  // namespace
}  // namespace reenact::capture

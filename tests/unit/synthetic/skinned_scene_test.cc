// The synthetic scene with a skinned glTF body (SyntheticBodySpec).

#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "common/error/check.h"
#include "synthetic/synthetic_scene.h"
#include "tests/support/temp_dir.h"
#include "tests/unit/synthetic/gltf_test_rig.h"

namespace reenact::capture {
namespace {

using reenact::test_support::TempDir;

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

#define REQUIRE_CESIUM_MAN() \
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent"

SyntheticBodySpec CesiumMan() {
  SyntheticBodySpec b;
  b.gltf_path = kCesiumMan;
  return b;
}

// The subject is in view: a mask of a plausible size that does not touch the image border,
// and nearly every ground-truth joint projects onto it (within 2 pixels: joints lie inside
// the body; a hand or foot joint may sit behind another part but still on the silhouette).
void ExpectSubjectInView(const SyntheticScene& scene, int frame) {
  const SyntheticView v = scene.RenderSensor(frame);
  const PinholeCamera& c = scene.sensor_camera();
  int count = 0;
  bool border = false;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      if (v.mask.at(x, y) != 255) continue;
      ++count;
      border |= x == 0 || y == 0 || x == c.width - 1 || y == c.height - 1;
      EXPECT_NE(v.part_labels.at(x, y), kBackgroundLabel);
    }
  EXPECT_GT(count, 5000) << "frame " << frame;
  EXPECT_FALSE(border) << "frame " << frame;
  const Skeleton s = scene.skeleton_in_world(frame);
  ASSERT_TRUE(s.Complete());
  const Eigen::Isometry3d sensor_from_world = scene.world_from_sensor(frame).inverse();
  int on_mask = 0;
  for (int j = 0; j < kJointCount; ++j) {
    const std::optional<Eigen::Vector2d> px = c.Project(sensor_from_world * s.position[j]);
    ASSERT_TRUE(px.has_value());
    const int u = static_cast<int>(std::lround(px->x())),
              w = static_cast<int>(std::lround(px->y()));
    bool hit = false;
    for (int dy = -2; dy <= 2 && !hit; ++dy)
      for (int dx = -2; dx <= 2 && !hit; ++dx)
        hit = v.mask.Contains(u + dx, w + dy) && v.mask.at(u + dx, w + dy) == 255;
    on_mask += hit;
  }
  EXPECT_GE(on_mask, 15) << "frame " << frame;
}

TEST(SkinnedScene, CesiumManTurnsAndKicksInView) {
  REQUIRE_CESIUM_MAN();
  const Expected<SyntheticScene> scene = SyntheticScene::Create("turn-and-kick", 1, CesiumMan());
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->frame_count(), 180);
  EXPECT_TRUE(scene->body().skinned());
  for (int f = 0; f < scene->frame_count(); f += 15) ExpectSubjectInView(*scene, f);
}

TEST(SkinnedScene, CesiumManWalksItsOwnAnimationInView) {
  REQUIRE_CESIUM_MAN();
  const Expected<SyntheticScene> scene = SyntheticScene::Create("model-walk", 1, CesiumMan());
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->frame_count(), 120);
  for (int f = 0; f < scene->frame_count(); f += 10) ExpectSubjectInView(*scene, f);
  // It walks: the feet move relative to each other.
  const Skeleton a = scene->skeleton_in_world(0), b = scene->skeleton_in_world(15);
  EXPECT_GT(
      ((a[Joint::kLeftFoot] - a[Joint::kRightFoot]) - (b[Joint::kLeftFoot] - b[Joint::kRightFoot]))
          .norm(),
      0.1);
}

TEST(SkinnedScene, BoneLengthsStayTheSkinsOverTheClip) {
  REQUIRE_CESIUM_MAN();
  // Retargeting turns whole skin bones, so every part between joints on one rigid chain
  // keeps its length; the torso halves span the spine joints between the waist and the neck
  // (CesiumMan has two), whose bend changes them by millimetres. The model's own walk also
  // turns the wrists and the head joint (which carry the derived hand and head centres), so
  // there only the single-bone parts keep their length.
  const std::vector<BodyPart> single_bone = {BodyPart::kLeftUpperArm, BodyPart::kRightUpperArm,
                                             BodyPart::kLeftThigh,    BodyPart::kRightThigh,
                                             BodyPart::kLeftShin,     BodyPart::kRightShin};
  for (const char* name : {"turn-and-kick", "model-walk"}) {
    const SyntheticScene scene = SyntheticScene::Create(name, 1, CesiumMan()).value();
    const Skeleton first = scene.skeleton_in_world(0);
    for (int f = 1; f < scene.frame_count(); f += 7) {
      const Skeleton s = scene.skeleton_in_world(f);
      for (int p = 0; p < kBodyPartCount; ++p) {
        const BodyPart part = static_cast<BodyPart>(p);
        const auto [a, b] = PartJoints(part);
        const double change = std::abs((s[a] - s[b]).norm() - (first[a] - first[b]).norm());
        const bool torso = part == BodyPart::kUpperTorso || part == BodyPart::kLowerTorso;
        const bool rigid =
            std::string(name) == "turn-and-kick"
                ? !torso
                : std::find(single_bone.begin(), single_bone.end(), part) != single_bone.end();
        if (rigid) {
          EXPECT_LT(change, 1e-6) << name << " frame " << f << " " << PartName(part);
        } else if (torso) {
          EXPECT_LT(change, 0.01) << name << " frame " << f << " " << PartName(part);
        }
      }
    }
  }
}

TEST(SkinnedScene, TheProceduralBodyRefusesTheModelsAnimation) {
  const Expected<SyntheticScene> scene = SyntheticScene::Create("model-walk");
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, "unsupported");
  EXPECT_NE(scene.error().message.find("needs a skinned body"), std::string::npos);
}

TEST(SkinnedScene, AModelWithoutAnimationCannotPlayModelWalk) {
  TempDir dir;
  test::TestRig rig;
  rig.json.erase("animations");
  rig.WriteGlb(dir.path() / "still.glb");
  SyntheticBodySpec body;
  body.gltf_path = (dir.path() / "still.glb").string();
  const Expected<SyntheticScene> walk = SyntheticScene::Create("model-walk", 1, body);
  ASSERT_FALSE(walk.ok());
  EXPECT_EQ(walk.error().code, "unsupported");
  EXPECT_NE(walk.error().message.find("has none"), std::string::npos) << walk.error().message;
  // The same body plays procedural scenarios.
  EXPECT_TRUE(SyntheticScene::Create("calibration", 1, body).ok());
}

TEST(SkinnedScene, AMissingBodyFileIsNotFound) {
  SyntheticBodySpec body;
  body.gltf_path = "/nonexistent/body.glb";
  const Expected<SyntheticScene> scene = SyntheticScene::Create("turn-and-kick", 1, body);
  ASSERT_FALSE(scene.ok());
  EXPECT_EQ(scene.error().code, "not_found");
  EXPECT_NE(scene.error().message.find("/nonexistent/body.glb"), std::string::npos);
}

}  // namespace
}  // namespace reenact::capture

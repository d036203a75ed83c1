// The subject's lighting (SyntheticBodySpec::ambient): lit by the scene's directional light or
// lit flat, on the procedural and the skinned body.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "synthetic/room.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

TEST(SubjectLighting, LambertShadeIsOneEverywhereWhenFlat) {
  const Eigen::Vector3d l = SceneLightDirection();
  EXPECT_DOUBLE_EQ(LambertShade(l), 1.0);
  EXPECT_DOUBLE_EQ(LambertShade(-l), kSceneAmbient);
  for (const Eigen::Vector3d& n :
       {l, Eigen::Vector3d(-l), Eigen::Vector3d(Eigen::Vector3d::UnitX())})
    EXPECT_DOUBLE_EQ(LambertShade(n, 1.0), 1.0);
}

// Lit by the scene, every subject pixel's colour is albedo * shade with shade <= 1, so it is
// never brighter than lit flat (albedo * 1; up to one level of rounding), and surfaces facing
// away from the light (shade = ambient 0.5) are clearly darker. Geometry is the same.
void ExpectFlatIsTheUnshadedAlbedo(const SyntheticBodySpec& body) {
  SyntheticBodySpec flat_body = body;
  flat_body.ambient = 1.0;
  const Expected<SyntheticScene> lit = SyntheticScene::Create("turn-and-kick", 1, body);
  const Expected<SyntheticScene> flat = SyntheticScene::Create("turn-and-kick", 1, flat_body);
  ASSERT_TRUE(lit.ok()) << lit.error().message;
  ASSERT_TRUE(flat.ok()) << flat.error().message;
  for (int frame : {0, 90}) {
    const SyntheticView a = lit->RenderSensor(frame, {.draw_room = false});
    const SyntheticView b = flat->RenderSensor(frame, {.draw_room = false});
    EXPECT_EQ(a.mask.data, b.mask.data);
    EXPECT_EQ(a.depth.data, b.depth.data);
    int subject = 0, darker = 0;
    for (int y = 0; y < a.mask.height; ++y)
      for (int x = 0; x < a.mask.width; ++x) {
        if (a.mask.at(x, y) == 0) continue;
        ++subject;
        bool much_darker = true;
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(a.color.at(x, y, k), b.color.at(x, y, k) + 1) << x << "," << y;
          much_darker = much_darker && a.color.at(x, y, k) + 1 <= 0.6 * b.color.at(x, y, k) + 2;
        }
        darker += much_darker;
      }
    EXPECT_GT(subject, 1000) << frame;
    EXPECT_GT(darker, subject / 50) << frame;  // the sides and back away from the light
  }
}

TEST(SubjectLighting, FlatLightShowsTheProceduralBodysAlbedo) { ExpectFlatIsTheUnshadedAlbedo({}); }

TEST(SubjectLighting, FlatLightShowsTheSkinnedBodysAlbedo) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  SyntheticBodySpec body;
  body.gltf_path = kCesiumMan;
  ExpectFlatIsTheUnshadedAlbedo(body);
}

TEST(SubjectLighting, AmbientOutsideZeroToOneIsRefused) {
  for (double ambient : {-0.1, 1.5, std::nan("")}) {
    SyntheticBodySpec body;
    body.ambient = ambient;
    const Expected<SyntheticScene> scene = SyntheticScene::Create("turn-and-kick", 1, body);
    ASSERT_FALSE(scene.ok()) << ambient;
    EXPECT_EQ(scene.error().code, "invalid_argument");
    EXPECT_NE(scene.error().message.find("ambient"), std::string::npos);
  }
}

}  // namespace
}  // namespace reenact::capture

// Relighting in the reenactment (issue 9): the subject light is fitted at load from a clip
// recorded through the real capture path, and Build hands the renderers the light as the
// viewer sees it and as every candidate's stored frame saw it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "synthetic/room.h"
#include "tests/unit/viewer-client/recorded_synthetic_clip.h"
#include "viewer-client/play/texturing_presets.h"
#include "viewer-client/play/viewer_camera.h"

namespace reenact::viewer {
namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// The first 3 s of the synthetic "turn-and-kick" scenario (the procedural body turns through
// more than a quarter turn), recorded and read back, the subject lit with ambient share
// `ambient`.
Reenactment RecordedClip(double ambient) {
  capture::SyntheticBodySpec body;
  body.ambient = ambient;
  return testing::RecordedSyntheticClip("turn-and-kick", 90, body);
}

const Reenactment& LitClip() {
  static const Reenactment clip = RecordedClip(capture::kSceneAmbient);
  return clip;
}

TEST(ReenactmentRelight, TheScenesLightIsFittedAtLoad) {
  const SubjectLightFit& fit = LitClip().subject_light();
  ASSERT_TRUE(fit.found) << fit.reason;
  // Truth by construction (subject_light.h): Lambert with ambient share k = 0.5 towards l is
  // L = l (1 - k) / k, strength 1. The world's up is +z (the floor is z = 0). The subject is
  // upright and turns about the vertical, so the horizontal part of L is what the fit measures
  // well (subject_light.h, observability). Its bounds: the stored colours are JPEG-coded, the
  // labels come from the rough cylinder model (pixels of the hands and feet go to the forearms
  // and shins), and the procedural body's patterns vary within a bin; 10 degrees and 20 % hold
  // the horizontal part to the light's side of the subject and its contrast to a fifth.
  const Eigen::Vector3d truth =
      capture::SceneLightDirection() * ((1 - capture::kSceneAmbient) / capture::kSceneAmbient);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d fit_across = fit.light - fit.light.dot(up) * up;
  const Eigen::Vector3d true_across = truth - truth.dot(up) * up;
  EXPECT_LT(AngleDeg(fit_across, true_across), 10.0);
  EXPECT_NEAR(fit_across.norm(), true_across.norm(), 0.2 * true_across.norm());
  EXPECT_GT(fit.light.dot(up), 0.0);  // the light is above
  EXPECT_GT(fit.gain, 0.2);

  // With a light, every stored crop carries its depth normals for relighting.
  const StoredTexture t = LitClip().Texture(30);
  ASSERT_FALSE(t.depth_m.empty());
  const Image<float> expected = DepthNormalMap(t.depth_m, t.part_labels, t.camera);
  EXPECT_EQ(t.normals.channels, 3);
  EXPECT_EQ(t.normals.data, expected.data);
  EXPECT_TRUE(
      std::any_of(t.normals.data.begin(), t.normals.data.end(), [](float v) { return v != 0; }));
}

TEST(ReenactmentRelight, AFlatLitSubjectHasNoLight) {
  const Reenactment clip = RecordedClip(1.0);
  const SubjectLightFit& fit = clip.subject_light();
  EXPECT_FALSE(fit.found);
  EXPECT_EQ(fit.light, Eigen::Vector3d::Zero());
  EXPECT_FALSE(fit.reason.empty());
  EXPECT_TRUE(clip.Texture(30).normals.empty());  // nothing to relight with
}

// Build with relighting: the frame's light is L seen from the viewer, and each candidate's
// stored_light gives, for any viewer-frame normal n, the shading the stored frame's surface
// had there: n . stored_light = (R n) . L_stored, R the rotation of stored_from_viewer
// (texturing.h), L_stored the light in that frame's sensor frame.
TEST(ReenactmentRelight, BuildGivesEveryCandidateTheLightItsFrameSaw) {
  const Reenactment& clip = LitClip();
  ASSERT_TRUE(clip.subject_light().found);
  const Eigen::Vector3d light = clip.subject_light().light;
  TexturingOptions relit = TexturingPreset("relit").value();
  const PinholeCamera camera = ScaledViewerCamera(clip.manifest().color_camera, 320, 240);
  OrbitCameraOptions orbit;
  orbit.angle_deg = 120;
  const auto view = OrbitViewFor(clip, orbit);
  ASSERT_TRUE(view.has_value());
  const int k = 45;
  const auto texture_of = [](int n) { return n; };
  const ReenactedFrame frame = clip.BuildPosed(k, clip.frame(k).skeleton_in_world, camera,
                                               view->viewer_from_world, texture_of, relit);
  EXPECT_LT((frame.draw.subject_light - view->viewer_from_world.linear() * light).norm(), 1e-12);

  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 1);
  int candidates = 0;
  for (const CylinderDraw& c : frame.draw.cylinders)
    for (const TextureCandidate& t : c.candidates) {
      ++candidates;
      const Eigen::Matrix3d sr = t.stored_from_viewer.topLeftCorner<3, 3>();
      const Eigen::Matrix3d r = sr / sr.col(0).norm();
      const Eigen::Vector3d light_in_stored =
          clip.frame(t.texture).world_from_sensor.linear().transpose() * light;
      for (int i = 0; i < 5; ++i) {
        const Eigen::Vector3d n = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
        EXPECT_NEAR(n.dot(t.stored_light), (r * n).dot(light_in_stored), 1e-9);
      }
    }
  EXPECT_GT(candidates, 20);

  // Without relighting (or where no light was found) both stay zero: the factor is 1.
  relit.relight = false;
  const ReenactedFrame plain = clip.BuildPosed(k, clip.frame(k).skeleton_in_world, camera,
                                               view->viewer_from_world, texture_of, relit);
  EXPECT_EQ(plain.draw.subject_light, Eigen::Vector3d::Zero());
  for (const CylinderDraw& c : plain.draw.cylinders)
    for (const TextureCandidate& t : c.candidates)
      EXPECT_EQ(t.stored_light, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace reenact::viewer

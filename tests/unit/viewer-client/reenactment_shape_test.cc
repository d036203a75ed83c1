// Reenactment with the profiled body shape (issue 9, a closer shape): the clip's cross-sections
// are fitted at load from its stored silhouettes and drawn, with the torso's width direction,
// only by BodyShape::kProfiled.

#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/common/shaped_cylinder_raycast.h"
#include "tests/unit/common/test_skeletons.h"
#include "viewer-client/play/reenactment.h"

namespace reenact::viewer {
namespace {

double Deg(double d) { return d * M_PI / 180; }

// The subject's true shape: an elliptic upper torso (1.3 x 0.7 of the cylinder's radius at
// every ring), every other part the plain cylinder.
PartShapes TruthShapes() {
  PartShapes truth{};
  truth[Index(BodyPart::kUpperTorso)].width.fill(1.3);
  truth[Index(BodyPart::kUpperTorso)].depth.fill(0.7);
  return truth;
}

// A static sensor at the world origin; the subject (arms out, so the arms do not touch the
// torso) turning on the spot in 15-degree steps, 2.5 m away; every frame's mask and depth
// ray-cast from the true shape, the crop the whole image.
Reenactment TurningClip() {
  proto::ClipManifest manifest;
  manifest.color_camera = PinholeCamera::KinectLike();
  manifest.depth_camera = manifest.color_camera;
  manifest.radius_ratio = DefaultRadiusRatios();
  std::vector<proto::ClipFrame> frames;
  for (int d = 0; d < 360; d += 15) {
    proto::ClipFrame f;
    f.skeleton_in_world = testing::StandingPerson(2.5, Deg(d), true);
    testing::RayCastShapedCylinders(
        PoseCylinders(f.skeleton_in_world, manifest.radius_ratio, {}, TruthShapes()),
        manifest.color_camera, f.depth, f.mask);
    f.color = ImageRgb8(manifest.color_camera.width, manifest.color_camera.height, 3, 100);
    f.timestamp_s = frames.size() / 30.0;
    frames.push_back(std::move(f));
  }
  manifest.frame_count = static_cast<int64_t>(frames.size());
  return Reenactment(manifest, std::move(frames));
}

const CylinderDraw& Part(const ReenactedFrame& f, BodyPart p) {
  for (size_t i = 0; i < f.cylinder_parts.size(); ++i)
    if (f.cylinder_parts[i] == p) return f.draw.cylinders[i];
  throw std::runtime_error("part not drawn");
}

TEST(ReenactmentShape, TheClipsCrossSectionsAreFittedAtLoadAndDrawnOnlyWhenProfiled) {
  const Reenactment r = TurningClip();
  // The fit sees the torso from every side. Bound: cross_section_fit_test's elliptic torso
  // (12 headings at 2.5 m) holds 0.1 on every ring; the torso's radius is about 22 px here, so
  // half a pixel of edge error is 0.02 of a ratio, the rest is the rings' end insets and the
  // shoulders' overlap.
  const PartShape& torso = r.part_shapes()[Index(BodyPart::kUpperTorso)];
  for (int k = 1; k < kShapeRings - 1; ++k) {
    EXPECT_NEAR(torso.width[k], 1.3, 0.1) << k;
    EXPECT_NEAR(torso.depth[k], 0.7, 0.1) << k;
  }
  // A plain part stays close to the plain cylinder (its silhouette is one).
  const PartShape& thigh = r.part_shapes()[Index(BodyPart::kLeftThigh)];
  for (int k = 1; k < kShapeRings - 1; ++k) EXPECT_NEAR(thigh.width[k], 1.0, 0.1) << k;

  const Skeleton viewer = testing::StandingPerson(2.5, Deg(40), true);
  const auto identity = [](int n) { return n; };
  TexturingOptions texturing{.shape = BodyShape::kProfiled};
  const ReenactedFrame profiled = r.BuildPosed(0, viewer, PinholeCamera::KinectLike(),
                                               Eigen::Isometry3d::Identity(), identity, texturing);
  const CylinderDraw& drawn = Part(profiled, BodyPart::kUpperTorso);
  EXPECT_EQ(drawn.shape.width, torso.width);
  EXPECT_EQ(drawn.shape.depth, torso.depth);
  ASSERT_TRUE(drawn.width_direction);
  // Across the shoulders, orthogonal to the torso's axis.
  const Eigen::Vector3d across = viewer[Joint::kLeftShoulder] - viewer[Joint::kRightShoulder];
  EXPECT_GT(drawn.width_direction->dot(across.normalized()), 0.99);
  EXPECT_NEAR(drawn.width_direction->dot((drawn.b - drawn.a).normalized()), 0.0, 1e-9);

  for (BodyShape shape : {BodyShape::kCylinders, BodyShape::kExtended}) {
    texturing.shape = shape;
    const ReenactedFrame plain = r.BuildPosed(0, viewer, PinholeCamera::KinectLike(),
                                              Eigen::Isometry3d::Identity(), identity, texturing);
    for (const CylinderDraw& c : plain.draw.cylinders) {
      EXPECT_TRUE(c.shape.IsCylinder());
      EXPECT_FALSE(c.width_direction);
    }
  }
}

}  // namespace
}  // namespace reenact::viewer

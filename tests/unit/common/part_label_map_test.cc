#include "common/texture/part_label_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error/check.h"
#include "common/texture/visibility_maps.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

// Principal point off the pixel grid, to catch half-pixel errors.
PinholeCamera Camera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

using Cylinders = std::array<std::optional<Cylinder>, kBodyPartCount>;
constexpr BodyPart kArm = BodyPart::kLeftUpperArm;
constexpr BodyPart kTorso = BodyPart::kLowerTorso;

// Distance of pixel (x, y)'s ray to the infinite line through `on_axis` along the unit axis,
// and the ray's depth at its closest approach: the analytic silhouette of a long cylinder.
double RayToAxisDistance(const PinholeCamera& cam, int x, int y, const Eigen::Vector3d& on_axis,
                         const Eigen::Vector3d& axis) {
  const Eigen::Vector3d d =
      Eigen::Vector3d((x - cam.cx) / cam.fx, (y - cam.cy) / cam.fy, 1.0).normalized();
  const Eigen::Vector3d n = d.cross(axis);
  return std::abs(on_axis.dot(n)) / n.norm();  // skew-line distance (the ray starts at 0)
}

TEST(PartLabelMap, PixelsInsideAProjectedCylinderGetItsPartAndBackgroundStaysNone) {
  // Arm: horizontal, at depth 2, from x = -0.3 to 0.1, radius 0.1.
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{-0.3, 0, 2}, {0.1, 0, 2}, 0.1};
  const PinholeCamera cam = Camera();
  ImageGray8 mask(cam.width, cam.height, 1, 255);
  for (int x = 0; x < cam.width; ++x) mask.at(x, 3) = 0;  // one background row
  const ImageLabel8 labels = RenderPartLabelMap(cylinders, cam, mask);
  ASSERT_EQ(labels.width, cam.width);
  ASSERT_EQ(labels.height, cam.height);
  int inside = 0;
  // Columns 55..85 see the side, not the caps, at any depth between 1.9 and 2.1 m.
  for (int y = 0; y < cam.height; ++y)
    for (int x = 55; x <= 85; ++x) {
      if (y == 3) {
        EXPECT_EQ(labels.at(x, y), kBackgroundLabel);
        continue;
      }
      const double distance =
          RayToAxisDistance(cam, x, y, Eigen::Vector3d(0, 0, 2), Eigen::Vector3d::UnitX());
      if (distance < 0.1 * 0.995) {
        ++inside;
        EXPECT_EQ(labels.at(x, y), PartLabel(kArm)) << x << ", " << y;
      }
    }
  EXPECT_GT(inside, 31 * 15);  // about 20 rows of 31 columns
  // Subject pixels off the only cylinder fall back to it; background rows stay none.
  EXPECT_EQ(labels.at(5, 110), PartLabel(kArm));
  EXPECT_EQ(labels.at(150, 3), kBackgroundLabel);
}

TEST(PartLabelMap, WhereTwoCylindersOverlapTheNearerWinsWhateverThePartOrder) {
  // A vertical torso at depth 1.5 in front of the horizontal arm at depth 2, and the same
  // two swapped in depth.
  for (bool torso_in_front : {true, false}) {
    const double torso_z = torso_in_front ? 1.5 : 2.5;
    Cylinders cylinders;
    cylinders[Index(kArm)] = Cylinder{{-0.5, 0, 2}, {0.5, 0, 2}, 0.08};
    cylinders[Index(kTorso)] = Cylinder{{0, -0.4, torso_z}, {0, 0.4, torso_z}, 0.1};
    const PinholeCamera cam = Camera();
    const ImageGray8 mask(cam.width, cam.height, 1, 255);
    const ImageLabel8 labels = RenderPartLabelMap(cylinders, cam, mask);
    int both = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const double to_arm =
            RayToAxisDistance(cam, x, y, Eigen::Vector3d(0, 0, 2), Eigen::Vector3d::UnitX());
        const double to_torso =
            RayToAxisDistance(cam, x, y, Eigen::Vector3d(0, 0, torso_z), Eigen::Vector3d::UnitY());
        // Near the image centre, far from every cap.
        if (std::abs(x - cam.cx) > 30 || std::abs(y - cam.cy) > 30) continue;
        const bool in_arm = to_arm < 0.08 * 0.995, in_torso = to_torso < 0.1 * 0.995;
        if (in_arm && in_torso) {
          ++both;
          EXPECT_EQ(labels.at(x, y), PartLabel(torso_in_front ? kTorso : kArm)) << x << ", " << y;
        } else if (in_arm && to_torso > 0.1 * 1.005) {
          EXPECT_EQ(labels.at(x, y), PartLabel(kArm)) << x << ", " << y;
        } else if (in_torso && to_arm > 0.08 * 1.005) {
          EXPECT_EQ(labels.at(x, y), PartLabel(kTorso)) << x << ", " << y;
        }
      }
    EXPECT_GT(both, 50);
  }
}

TEST(PartLabelMap, UncoveredSubjectPixelsTakeTheNearestProjectedCapsule) {
  Cylinders cylinders;
  // Arm: u from about 50 to 90 at v = 60.7, 10 px thick; torso: u = 105.3, v 35.7..85.7,
  // 5 px thick. Both at depth 2.
  cylinders[Index(kArm)] = Cylinder{{-0.3, 0, 2}, {0.1, 0, 2}, 0.1};
  cylinders[Index(kTorso)] = Cylinder{{0.25, -0.25, 2}, {0.25, 0.25, 2}, 0.05};
  const PinholeCamera cam = Camera();
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  EXPECT_EQ(labels.at(10, 60), PartLabel(kArm));     // 40 px left of the arm's end
  EXPECT_EQ(labels.at(70, 100), PartLabel(kArm));    // below the arm, far from the torso
  EXPECT_EQ(labels.at(105, 10), PartLabel(kTorso));  // above the torso
  EXPECT_EQ(labels.at(150, 60), PartLabel(kTorso));  // right of the torso
  // Between them: |pixel - axis| - projected radius decides: at u = 95.3 the arm's end
  // (u 90.3, radius 10 px) is 5 - 10 = -5 px away, the torso (u 105.3, radius 5) 10 - 5 = 5.
  EXPECT_EQ(labels.at(95, 61), PartLabel(kArm));
}

TEST(PartLabelMap, NoSkeletonGivesBackgroundEverywhere) {
  const PinholeCamera cam = Camera();
  const ImageGray8 mask(cam.width, cam.height, 1, 255);
  const ImageLabel8 labels = PartLabelMapOfFrame(Skeleton(), DefaultRadiusRatios(), cam, mask);
  for (uint8_t l : labels.data) ASSERT_EQ(l, kBackgroundLabel);
}

TEST(PartLabelMap, CylindersBehindTheCameraLabelNothing) {
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{-0.3, 0, -2}, {0.3, 0, -2}, 0.1};
  const PinholeCamera cam = Camera();
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  for (uint8_t l : labels.data) ASSERT_EQ(l, kBackgroundLabel);
}

TEST(PartLabelMap, ACylinderThroughTheCameraPlaneLabelsOnlyItsFrontPart) {
  // Along the optical axis from z = -1 to z = 3, off-centre: the ray hits only at z > 0; the
  // fallback clips the axis at kLabelMapNearZ, so no NaN and every subject pixel is labelled.
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0.3, 0, -1}, {0.3, 0, 3}, 0.1};
  const PinholeCamera cam = Camera();
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  for (uint8_t l : labels.data) ASSERT_EQ(l, PartLabel(kArm));
}

TEST(PartLabelMap, AZeroLengthCylinderLabelsNothing) {
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0, 0, 2}, {0, 0, 2}, 0.1};
  const PinholeCamera cam = Camera();
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  for (uint8_t l : labels.data) ASSERT_EQ(l, kBackgroundLabel);
}

TEST(PartLabelMap, APosedPersonLabelsTheTorsoAtTheWaistAndAHandOnTheForearm) {
  const Skeleton person = testing::StandingPerson(2.5, 0, /*arms_out=*/true);
  const PinholeCamera cam = PinholeCamera{320, 240, 250, 250, 160, 120, {}};
  const ImageLabel8 labels = PartLabelMapOfFrame(person, DefaultRadiusRatios(), cam,
                                                 ImageGray8(cam.width, cam.height, 1, 255));
  const auto label_at = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d uv(cam.fx * p.x() / p.z() + cam.cx, cam.fy * p.y() / p.z() + cam.cy);
    return labels.at(static_cast<int>(std::lround(uv.x())), static_cast<int>(std::lround(uv.y())));
  };
  const Eigen::Vector3d mid_torso = 0.5 * (person[Joint::kTorso] + person[Joint::kWaist]);
  EXPECT_EQ(label_at(mid_torso), PartLabel(BodyPart::kLowerTorso));
  const Eigen::Vector3d mid_forearm = 0.5 * (person[Joint::kLeftElbow] + person[Joint::kLeftHand]);
  EXPECT_EQ(label_at(mid_forearm), PartLabel(BodyPart::kLeftForearm));
}

TEST(PartLabelMap, RejectsAMaskOfAnotherSize) {
  const PinholeCamera cam = Camera();
  EXPECT_THROW(RenderPartLabelMap(Cylinders{}, cam, ImageGray8(cam.width - 1, cam.height, 1, 255)),
               CheckError);
}

TEST(PartLabelMap, RejectsANonFiniteCylinder) {
  Cylinders cylinders;
  cylinders[0] = Cylinder{{0, std::nan(""), 2}, {0, 0, 2}, 0.1};
  const PinholeCamera cam = Camera();
  EXPECT_THROW(RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255)),
               CheckError);
}

TEST(VisibilityMaps, DepthIsScaledToMetresAndZeroStaysNoReading) {
  ImageDepthMm depth(3, 1, 1, 0);
  depth.at(1, 0) = 1500;
  depth.at(2, 0) = 65535;
  const Image<float> m = DepthInMetres(depth, 0.001);
  EXPECT_EQ(m.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(m.at(1, 0), 1.5f);
  EXPECT_FLOAT_EQ(m.at(2, 0), 65.535f);
  EXPECT_TRUE(DepthInMetres(ImageDepthMm(), 0.001).empty());
}

TEST(VisibilityMaps, RejectsABadScaleAndADepthOfAnotherSize) {
  EXPECT_THROW(DepthInMetres(ImageDepthMm(2, 2, 1, 0), 0.0), CheckError);
  EXPECT_THROW(DepthInMetres(ImageDepthMm(2, 2, 1, 0), std::nan("")), CheckError);
  const PinholeCamera cam = Camera();
  EXPECT_THROW(MakeVisibilityMaps(Skeleton(), DefaultRadiusRatios(), cam,
                                  ImageGray8(cam.width, cam.height, 1, 255),
                                  ImageDepthMm(4, 4, 1, 0), 0.001),
               CheckError);
}

}  // namespace
}  // namespace reenact

#include "common/texture/part_coverage.h"

#include <gtest/gtest.h>

#include "common/error/check.h"
#include "common/render/texturing.h"
#include "common/texture/part_label_map.h"
#include "common/texture/visibility_maps.h"
#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/shaped_cylinder_raycast.h"

namespace reenact {
namespace {

using Cylinders = std::array<std::optional<Cylinder>, kBodyPartCount>;
constexpr BodyPart kArm = BodyPart::kLeftUpperArm;
constexpr BodyPart kForearm = BodyPart::kRightForearm;

// Fine enough that the facing half's outermost cells (82.5 degrees from the facing side of a
// 10 cm cylinder 2 m away: 1.1 px inside the 100 px silhouette edge) round to pixels inside it.
PinholeCamera Camera() { return PinholeCamera{640, 640, 2000, 2000, 320.3, 319.6, {}}; }

// A frame of `cylinders` as a sensor sees it: exact ray-cast depth and mask, and the part
// labels the renderers test against.
struct Frame {
  ImageGray8 mask;
  Image<float> depth_m;
  ImageLabel8 labels;
};
Frame See(const Cylinders& cylinders, const PinholeCamera& camera, bool shaped = false) {
  Frame f;
  ImageDepthMm depth;
  if (shaped) {
    testing::RayCastShapedCylinders(cylinders, camera, depth, f.mask);
  } else {
    testing::RayCastCylinders(cylinders, camera, depth, f.mask);
  }
  f.depth_m = DepthInMetres(depth, 0.001);
  f.labels = RenderPartLabelMap(cylinders, camera, f.mask);
  return f;
}

PartCoverage Cell(int angle, int height) {
  return PartCoverage{1} << (angle * kCoverageHeights + height);
}

// The cells of the heights in [first, last], at every angle.
PartCoverage Heights(int first, int last) {
  PartCoverage out = 0;
  for (int i = 0; i < kCoverageAngles; ++i)
    for (int j = first; j <= last; ++j) out |= Cell(i, j);
  return out;
}

TEST(PartCoverage, AnUnoccludedCylinderCoversItsWholeFacingHalf) {
  // Upright arm 2 m ahead, a (y = -0.25) above b (y = 0.25): every cell of the facing half,
  // out to 82.5 degrees, is on the visible side (the silhouette lies at 87 degrees).
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0, -0.25, 2}, {0, 0.25, 2}, 0.1};
  const PinholeCamera camera = Camera();
  const Frame f = See(cylinders, camera);
  const PartCoverages coverage =
      CoverageOfFrame(cylinders, camera, f.mask, f.labels, f.depth_m, kDefaultDepthToleranceM);
  EXPECT_EQ(coverage[Index(kArm)], kFullCoverage);
  EXPECT_EQ(CoveredCells(coverage[Index(kArm)]), kCoverageAngles * kCoverageHeights);
  for (int p = 0; p < kBodyPartCount; ++p)
    if (p != Index(kArm)) {
      EXPECT_EQ(coverage[p], 0u) << "unposed part " << p;
    }
}

TEST(PartCoverage, APartInFrontHidesTheCellsBehindIt) {
  // A horizontal forearm 0.5 m in front of the arm at y = 0.15, radius 0.08, spans image
  // rows y/z in [0.047, 0.154] (tangent rays from the camera). The arm's cells at heights
  // t = 0.7, 0.9 (y = 0.1, 0.2: y/z 0.05-0.053 and 0.1-0.105) fall inside it, those at
  // t = 0.1, 0.3, 0.5 (y/z <= 0) outside.
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0, -0.25, 2}, {0, 0.25, 2}, 0.1};
  cylinders[Index(kForearm)] = Cylinder{{-0.5, 0.15, 1.5}, {0.5, 0.15, 1.5}, 0.08};
  const PinholeCamera camera = Camera();
  const Frame f = See(cylinders, camera);
  const PartCoverages coverage =
      CoverageOfFrame(cylinders, camera, f.mask, f.labels, f.depth_m, kDefaultDepthToleranceM);
  EXPECT_EQ(coverage[Index(kArm)], Heights(0, 2));
}

TEST(PartCoverage, StoredDepthDisagreeingWithTheSurfaceCoversNothing) {
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0, -0.25, 2}, {0, 0.25, 2}, 0.1};
  const PinholeCamera camera = Camera();
  Frame f = See(cylinders, camera);
  // The sensor saw something 10 cm behind the model's surface (beyond the 6 cm tolerance).
  for (float& d : f.depth_m.data)
    if (d > 0) d += 0.10f;
  EXPECT_EQ(CoverageOfFrame(cylinders, camera, f.mask, f.labels, f.depth_m,
                            kDefaultDepthToleranceM)[Index(kArm)],
            0u);
  // No reading at all: the depth test passes, as in the renderers.
  for (float& d : f.depth_m.data) d = 0;
  EXPECT_EQ(CoverageOfFrame(cylinders, camera, f.mask, f.labels, f.depth_m,
                            kDefaultDepthToleranceM)[Index(kArm)],
            kFullCoverage);
}

TEST(PartCoverage, CellsLieOnTheShapedSurface) {
  // An elliptic part, 15 cm wide across the view and 6 cm deep along it (so its whole facing
  // half faces the camera). Its cells sit on the ellipse, so they pass a 1 cm depth test
  // against the exact ray-cast surface; on the 10 cm circle they would lie up to 4 cm off it.
  Cylinder c{{0, -0.25, 2}, {0, 0.25, 2}, 0.1};
  c.shape.width = {1.5, 1.5, 1.5, 1.5, 1.5};
  c.shape.depth = {0.6, 0.6, 0.6, 0.6, 0.6};
  c.width_direction = Eigen::Vector3d::UnitX();
  Cylinders cylinders;
  cylinders[Index(kArm)] = c;
  const PinholeCamera camera = Camera();
  const Frame f = See(cylinders, camera, /*shaped=*/true);
  EXPECT_EQ(CoverageOfFrame(cylinders, camera, f.mask, f.labels, f.depth_m, 0.01)[Index(kArm)],
            kFullCoverage);
  Cylinders circular = cylinders;
  circular[Index(kArm)]->shape = PartShape{};
  circular[Index(kArm)]->width_direction.reset();
  EXPECT_NE(CoverageOfFrame(circular, camera, f.mask, f.labels, f.depth_m, 0.01)[Index(kArm)],
            kFullCoverage);
}

TEST(PartCoverage, APartBehindTheCameraOrOfZeroLengthCoversNothing) {
  const PinholeCamera camera = Camera();
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{0, -0.25, -2}, {0, 0.25, -2}, 0.1};
  cylinders[Index(kForearm)] = Cylinder{{0, 0, 2}, {0, 0, 2}, 0.1};
  const ImageGray8 mask(camera.width, camera.height, 1, 255);
  const ImageLabel8 labels(camera.width, camera.height, 1,
                           static_cast<uint8_t>(PartLabel(kForearm)));
  const PartCoverages coverage = CoverageOfFrame(cylinders, camera, mask, labels, {}, 0.06);
  EXPECT_EQ(coverage[Index(kArm)], 0u);
  EXPECT_EQ(coverage[Index(kForearm)], 0u);
}

TEST(PartCoverage, MapsOfAnotherSizeOrABadToleranceAreABug) {
  const PinholeCamera camera = Camera();
  const Cylinders none;
  const ImageGray8 mask(camera.width, camera.height, 1, 255);
  const ImageLabel8 labels(camera.width, camera.height, 1, 0);
  const ImageLabel8 small(10, 10, 1, 0);
  EXPECT_THROW(CoverageOfFrame(none, camera, mask, small, {}, 0.06), CheckError);
  EXPECT_THROW(CoverageOfFrame(none, camera, small, labels, {}, 0.06), CheckError);
  EXPECT_THROW(CoverageOfFrame(none, camera, mask, labels, Image<float>(10, 10, 1, 0.0f), 0.06),
               CheckError);
  EXPECT_THROW(CoverageOfFrame(none, camera, mask, labels, {}, -1), CheckError);
  EXPECT_THROW(CoverageOfFrame(none, camera, mask, labels, {}, std::nan("")), CheckError);
}

}  // namespace
}  // namespace reenact

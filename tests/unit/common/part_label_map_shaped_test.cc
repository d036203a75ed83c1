// Part-label maps of shaped parts (cylinder_model.h's PartShape): the labels follow the shaped
// surface's analytic silhouette, the capsule fallback follows the rings, and the shapes are
// carried from the skeleton through PartLabelMapOfFrame and MakeVisibilityMaps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error/check.h"
#include "common/texture/part_label_map.h"
#include "common/texture/visibility_maps.h"
#include "tests/unit/common/test_part_shapes.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::Cone;
using testing::Uniform;

PinholeCamera Camera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

using Cylinders = std::array<std::optional<Cylinder>, kBodyPartCount>;
constexpr BodyPart kTorso = BodyPart::kLowerTorso;
constexpr BodyPart kArm = BodyPart::kLeftUpperArm;
constexpr BodyPart kWall = BodyPart::kRightThigh;  // a wide plain part behind everything

Eigen::Vector3d Ray(const PinholeCamera& cam, double u, double v) {
  return Eigen::Vector3d((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
}

// Whether the analytic surface is hit at the pixel centre and at the 8 points 2 px away:
// 1 all, 0 none, -1 mixed (a border pixel, not checked).
template <typename Hit>
int Status(const PinholeCamera& cam, int x, int y, Hit hit) {
  int hits = 0;
  for (int dy = -2; dy <= 2; dy += 2)
    for (int dx = -2; dx <= 2; dx += 2) hits += hit(Ray(cam, x + dx, y + dy));
  return hits == 9 ? 1 : hits == 0 ? 0 : -1;
}

// A vertical elliptic torso (axis along y at depth 2, semi-axes A = 1.5 r across the view and
// B = 0.6 r along it when the width runs along x; swapped when it runs along z) in front of a
// wide plain "wall" part: pixels whose rays hit the exact elliptic prism are the torso's,
// pixels whose rays miss it the wall's.
TEST(PartLabelMapShaped, EllipticTorsoLabelsItsAnalyticSilhouette) {
  const PinholeCamera cam = Camera();
  const double r = 0.1, d = 2.0, y0 = -0.3, y1 = 0.3;
  for (bool width_along_x : {true, false}) {
    const double across = (width_along_x ? 1.5 : 0.6) * r, along = (width_along_x ? 0.6 : 1.5) * r;
    Cylinders cylinders;
    cylinders[Index(kTorso)] =
        Cylinder{{0, y0, d},
                 {0, y1, d},
                 r,
                 Uniform(1.5, 0.6),
                 width_along_x ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ()};
    cylinders[Index(kWall)] = Cylinder{{-2, 0, 4}, {2, 0, 4}, 1.5};
    const ImageLabel8 labels =
        RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
    // The ray t (dx, dy, 1) meets the prism where (t dx / A)^2 + ((t - d) / B)^2 <= 1 with
    // y0 <= t dy <= y1 (the caps face up and down, edge-on: never the nearest in these rows).
    const auto hit = [&](const Eigen::Vector3d& ray) {
      const double qa = ray.x() * ray.x() / (across * across) + 1 / (along * along);
      const double qb = -2 * d / (along * along), qc = d * d / (along * along) - 1;
      const double disc = qb * qb - 4 * qa * qc;
      if (disc < 0) return false;
      const double t = (-qb - std::sqrt(disc)) / (2 * qa);
      return t * ray.y() >= y0 && t * ray.y() <= y1;
    };
    int inside = 0, outside = 0;
    for (int y = 40; y <= 80; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const int status = Status(cam, x, y, hit);
        if (status == 1) {
          ++inside;
          ASSERT_EQ(labels.at(x, y), PartLabel(kTorso)) << x << ", " << y;
        } else if (status == 0) {
          ++outside;
          ASSERT_EQ(labels.at(x, y), PartLabel(kWall)) << x << ", " << y;
        }
      }
    const double half_width = cam.fx * across / std::sqrt(d * d - along * along);
    EXPECT_GT(inside, 41 * (2 * half_width - 6)) << width_along_x;
    EXPECT_GT(outside, 41 * (cam.width - 2 * half_width - 10)) << width_along_x;
  }
}

// A cone frustum across the view (axis along x at depth 2, radius 0.1 -> 0.2 m) in front of the
// wall: labels follow the exact ray-cone intersection, closed by its two caps.
TEST(PartLabelMapShaped, ConeLabelsItsAnalyticSilhouette) {
  const PinholeCamera cam = Camera();
  const double r = 0.1, d = 2.0, x0 = -0.3, x1 = 0.3;
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{x0, 0, d}, {x1, 0, d}, r, Cone(1, 2)};
  cylinders[Index(kWall)] = Cylinder{{-2, 0, 4}, {2, 0, 4}, 1.5};
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  // Radius R(x) = r (1 + (x - x0) / (x1 - x0)) = s (x - apex), s = r / (x1 - x0).
  const double s = r / (x1 - x0), apex = x0 - (x1 - x0);
  const auto hit = [&](const Eigen::Vector3d& ray) {
    // Side: (t dy)^2 + (t - d)^2 = s^2 (t dx - apex)^2, x0 <= t dx <= x1.
    const double qa = ray.y() * ray.y() + 1 - s * s * ray.x() * ray.x();
    const double qb = -2 * d + 2 * s * s * apex * ray.x();
    const double qc = d * d - s * s * apex * apex;
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0)
      for (double t : {(-qb - std::sqrt(disc)) / (2 * qa), (-qb + std::sqrt(disc)) / (2 * qa)})
        if (t > 0 && t * ray.x() >= x0 && t * ray.x() <= x1) return true;
    // Caps: the planes x = x0 and x = x1.
    for (double x : {x0, x1}) {
      const double t = x / ray.x(), radius = s * (x - apex);
      const double dy = t * ray.y(), dz = t - d;
      if (t > 0 && dy * dy + dz * dz <= radius * radius) return true;
    }
    return false;
  };
  int inside = 0, outside = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const int status = Status(cam, x, y, hit);
      if (status == 1) {
        ++inside;
        ASSERT_EQ(labels.at(x, y), PartLabel(kArm)) << x << ", " << y;
      } else if (status == 0) {
        ++outside;
        ASSERT_EQ(labels.at(x, y), PartLabel(kWall)) << x << ", " << y;
      }
    }
  // About the trapezoid 60 px long and 20 -> 40 px high.
  EXPECT_GT(inside, 1200);
  EXPECT_GT(outside, 15000);
}

// Subject pixels no part covers take the nearest projected capsule, whose radius follows the
// rings: beside the cone's thick end (radius 15 px) a pixel 19 px off its axis is 4 px from the
// cone and 10 px from a thin part 34 px off the axis; beside the thin end (5 px), 14 px.
TEST(PartLabelMapShaped, CapsuleFallbackFollowsTheRings) {
  const PinholeCamera cam = Camera();
  const double d = 2.0;
  Cylinders cylinders;
  cylinders[Index(kArm)] = Cylinder{{-0.3, 0, d}, {0.3, 0, d}, 0.05, Cone(1, 3)};
  const double below = 34 * d / cam.fy;  // 34 px below the cone's axis
  cylinders[Index(kTorso)] = Cylinder{{-0.3, below, d}, {0.3, below, d}, 0.05};
  const ImageLabel8 labels =
      RenderPartLabelMap(cylinders, cam, ImageGray8(cam.width, cam.height, 1, 255));
  const int v = static_cast<int>(std::lround(cam.cy + 19));
  const int thin = static_cast<int>(std::lround(cam.cx - 0.27 * cam.fx / d));
  const int thick = static_cast<int>(std::lround(cam.cx + 0.27 * cam.fx / d));
  EXPECT_EQ(labels.at(thick, v), PartLabel(kArm));
  EXPECT_EQ(labels.at(thin, v), PartLabel(kTorso));
}

// Degenerate placements: a shaped part crossing the camera plane is clipped at kLabelMapNearZ
// (every subject pixel still gets its label, no failure); one reaching past the image border
// labels its visible part.
TEST(PartLabelMapShaped, ShapedPartsThroughTheCameraPlaneOrPastTheBorderLabelTheirVisiblePart) {
  const PinholeCamera cam = Camera();
  const ImageGray8 mask(cam.width, cam.height, 1, 255);
  Cylinders through;
  through[Index(kArm)] = Cylinder{{0.3, 0, -1}, {0.3, 0, 3}, 0.1, Cone(1, 2)};
  for (uint8_t l : RenderPartLabelMap(through, cam, mask).data) ASSERT_EQ(l, PartLabel(kArm));

  Cylinders past;  // axis from u = -19.7 to u = 80.3 at row 60.7, 11 px thick either side
  past[Index(kArm)] = Cylinder{{-1, 0, 2}, {0, 0, 2}, 0.1, Uniform(1.1, 1.1)};
  past[Index(kWall)] = Cylinder{{-2, 0, 4}, {2, 0, 4}, 1.5};
  const ImageLabel8 labels = RenderPartLabelMap(past, cam, mask);
  for (int x : {0, 20, 40, 70}) {
    EXPECT_EQ(labels.at(x, 61), PartLabel(kArm)) << x;
    EXPECT_EQ(labels.at(x, 61 + 15), PartLabel(kWall)) << x;
  }
  EXPECT_EQ(labels.at(100, 61), PartLabel(kWall));
}

TEST(PartLabelMapShaped, ShapesAreCarriedFromTheSkeleton) {
  const Skeleton person = testing::StandingPerson(2.5, 0.3, /*arms_out=*/true);
  const PinholeCamera cam = PinholeCamera{320, 240, 250, 250, 160, 120, {}};
  const ImageGray8 mask(cam.width, cam.height, 1, 255);
  PartShapes shapes{};
  shapes[Index(BodyPart::kUpperTorso)] = Uniform(1.6, 0.7);
  shapes[Index(BodyPart::kLowerTorso)] = Uniform(1.5, 0.7);
  shapes[Index(BodyPart::kLeftThigh)] = Cone(1.3, 0.8);
  const RadiusRatios ratios = DefaultRadiusRatios();
  const ImageLabel8 expected =
      RenderPartLabelMap(PoseCylinders(person, ratios, {}, shapes), cam, mask);
  const ImageLabel8 plain = PartLabelMapOfFrame(person, ratios, cam, mask);
  const ImageLabel8 labels = PartLabelMapOfFrame(person, ratios, cam, mask, {}, shapes);
  EXPECT_EQ(labels.data, expected.data);
  int differ = 0;
  for (size_t i = 0; i < labels.data.size(); ++i) differ += labels.data[i] != plain.data[i];
  EXPECT_GT(differ, 100);  // the wider torso claims pixels the plain one left to the arms
  const VisibilityMaps maps =
      MakeVisibilityMaps(person, ratios, cam, mask, ImageDepthMm(), 0.001, {}, shapes);
  EXPECT_EQ(maps.part_labels.data, expected.data);
}

TEST(PartLabelMapShaped, RejectsBadShapesAndWidthDirections) {
  const PinholeCamera cam = Camera();
  const ImageGray8 mask(cam.width, cam.height, 1, 255);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    Cylinders cylinders;
    cylinders[Index(kArm)] = Cylinder{{-0.3, 0, 2}, {0.3, 0, 2}, 0.1, Uniform(1, 1)};
    cylinders[Index(kArm)]->shape.width[1] = bad;
    EXPECT_THROW(RenderPartLabelMap(cylinders, cam, mask), CheckError) << bad;
  }
  Cylinders cylinders;
  cylinders[Index(kTorso)] =
      Cylinder{{0, -0.3, 2},
               {0, 0.3, 2},
               0.1,
               Uniform(1.5, 0.6),
               Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 0)};
  EXPECT_THROW(RenderPartLabelMap(cylinders, cam, mask), CheckError);
}

}  // namespace
}  // namespace reenact

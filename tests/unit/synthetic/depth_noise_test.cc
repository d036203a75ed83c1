// Projector shadow holes (depth_noise.h), checked against 3D ray casting of scenes built
// here: a box in front of a wall, a flat wall, a slanted wall.

#include "synthetic/depth_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>

#include "common/error/check.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

using Eigen::Vector3d;

constexpr double kBaseline = 0.075;

PinholeCamera Camera() { return PinholeCamera::KinectLike(); }

// The unit ray through the centre of pixel (x, y), camera frame (z forward).
Vector3d Ray(const PinholeCamera& c, int x, int y) {
  return Vector3d((x - c.cx) / c.fx, (y - c.cy) / c.fy, 1.0);
}

// A fronto-parallel rectangle at depth z covering camera-frame x in [x0, x1], y in [y0, y1],
// in front of a fronto-parallel wall at depth wall_z.
struct BoxScene {
  double z = 1.5, x0 = -0.2, x1 = 0.1, y0 = -0.15, y1 = 0.2, wall_z = 3.0;

  bool BoxHit(const Vector3d& ray) const {
    const Vector3d p = ray * z;
    return p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1;
  }
  // Depth per pixel centre, millimetres.
  ImageDepthMm Render(const PinholeCamera& c) const {
    ImageDepthMm d(c.width, c.height, 1, 0);
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x)
        d.at(x, y) = static_cast<uint16_t>(std::lround((BoxHit(Ray(c, x, y)) ? z : wall_z) * 1000));
    return d;
  }
  // True when the segment from the projector at (b, 0, 0) to the wall point seen at (x, y)
  // crosses the rectangle.
  bool WallPointShadowed(const PinholeCamera& c, int x, int y) const {
    const Vector3d p = Ray(c, x, y) * wall_z, projector(kBaseline, 0, 0);
    const Vector3d at_box = projector + (p - projector) * (z / wall_z);
    return at_box.x() >= x0 && at_box.x() <= x1 && at_box.y() >= y0 && at_box.y() <= y1;
  }
};

TEST(ProjectorShadow, BoxInFrontOfAWallCastsAStripOfPredictedWidthOnTheFarSide) {
  const PinholeCamera c = Camera();
  const BoxScene scene;
  ImageDepthMm depth = scene.Render(c);
  const ImageDepthMm clean = depth;
  ApplyProjectorShadow(&depth, c);
  // Predicted width: f b (1/z_near - 1/z_far) = 517.3 * 0.075 * (1/1.5 - 1/3) = 12.9 px.
  const double width_px = c.fx * kBaseline * (1 / scene.z - 1 / scene.wall_z);
  int rows_with_strip = 0;
  for (int y = 0; y < c.height; ++y) {
    int first_box = -1, last_box = -1;
    for (int x = 0; x < c.width; ++x)
      if (clean.at(x, y) == 1500) {
        if (first_box < 0) first_box = x;
        last_box = x;
      }
    int holes = 0, holes_left_adjacent = 0;
    for (int x = 0; x < c.width; ++x) {
      // Every wall point that ray casting finds shadowed is a hole, except possibly in the
      // strip's outermost column.
      if (depth.at(x, y) != 0 && clean.at(x, y) != 1500 && scene.WallPointShadowed(c, x, y)) {
        EXPECT_FALSE(scene.WallPointShadowed(c, x - 1, y)) << x << "," << y;
      }
      if (depth.at(x, y) != 0) continue;
      ++holes;
      // The foreground itself keeps every reading.
      ASSERT_NE(clean.at(x, y), 1500) << x << "," << y;
      // Agrees with 3D ray casting except possibly in the strip's outermost column.
      if (!scene.WallPointShadowed(c, x, y)) {
        EXPECT_TRUE(scene.WallPointShadowed(c, x + 1, y)) << x << "," << y;
      }
      if (first_box >= 0 && x < first_box && x >= first_box - width_px - 1) ++holes_left_adjacent;
    }
    if (first_box < 0) {
      EXPECT_EQ(holes, 0) << "row " << y << " has no foreground";
      continue;
    }
    ++rows_with_strip;
    // All holes form one strip just left of the box (the side away from the projector),
    // ending at the box, of the predicted width; none right of the box.
    EXPECT_EQ(holes, holes_left_adjacent) << y;
    EXPECT_NEAR(holes, width_px, 1.0) << y;
    EXPECT_EQ(depth.at(first_box - 1, y), 0) << y;
    for (int x = last_box + 1; x < c.width; ++x) EXPECT_NE(depth.at(x, y), 0) << x << "," << y;
  }
  EXPECT_GT(rows_with_strip, 50);
}

TEST(ProjectorShadow, TheStripWidensAsTheBoxComesNearer) {
  const PinholeCamera c = Camera();
  for (double z : {0.8, 1.2, 2.0, 2.8}) {
    BoxScene scene;
    scene.z = z;
    ImageDepthMm depth = scene.Render(c);
    ApplyProjectorShadow(&depth, c);
    const int y = static_cast<int>(c.cy);  // a row through the box
    int holes = 0;
    for (int x = 0; x < c.width; ++x) holes += depth.at(x, y) == 0;
    EXPECT_NEAR(holes, c.fx * kBaseline * (1 / z - 1 / scene.wall_z), 1.0) << z;
  }
}

TEST(ProjectorShadow, FlatAndSlantedWallsLitByTheProjectorHaveNoHoles) {
  const PinholeCamera c = Camera();
  // Planes n . X = 1 (camera frame); the projector lies on their camera side, so it lights
  // every point of them that the camera sees.
  for (const Vector3d& n : {Vector3d(0, 0, 1.0 / 3), Vector3d(0.25, 0, 0.3),
                            Vector3d(-0.25, 0, 0.3), Vector3d(0, 0.3, 0.3)}) {
    ImageDepthMm depth(c.width, c.height, 1, 0);
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x) {
        const double t = 1 / n.dot(Ray(c, x, y));  // depth of the hit
        if (t > 0.4 && t < 8) depth.at(x, y) = static_cast<uint16_t>(std::lround(t * 1000));
      }
    const ImageDepthMm clean = depth;
    ApplyProjectorShadow(&depth, c);
    EXPECT_EQ(depth.data, clean.data) << n.transpose();
  }
}

TEST(ProjectorShadow, MissingReadingsNeitherCastShadowsNorChange) {
  const PinholeCamera c = Camera();
  BoxScene scene;
  ImageDepthMm depth = scene.Render(c);
  for (uint16_t& d : depth.data)
    if (d == 1500) d = 0;  // the box gave no reading
  const ImageDepthMm clean = depth;
  ApplyProjectorShadow(&depth, c);
  EXPECT_EQ(depth.data, clean.data);
}

TEST(ProjectorShadow, DepthNoiseAddsTheHolesWhenOnAndNotWhenOff) {
  const PinholeCamera c = Camera();
  const ImageDepthMm clean = BoxScene{}.Render(c);
  ImageDepthMm with = clean, without = clean, shadowed = clean;
  ApplyProjectorShadow(&shadowed, c);
  DepthNoiseOptions on;
  on.shadow_holes = true;
  ApplyDepthNoise(&with, c, 7, on);
  ApplyDepthNoise(&without, c, 7);  // off by default
  int holes = 0;
  for (size_t i = 0; i < clean.data.size(); ++i) {
    EXPECT_EQ(with.data[i] == 0, shadowed.data[i] == 0) << i;
    EXPECT_NE(without.data[i], 0) << i;
    holes += with.data[i] == 0;
  }
  EXPECT_GT(holes, 500);
}

TEST(ProjectorShadow, TheSyntheticSubjectCastsHolesOnItsLeftOnly) {
  const SyntheticScene scene = SyntheticScene::Create("calibration").value();
  SyntheticRenderOptions options;
  options.depth_noise = true;
  options.noise.shadow_holes = true;
  options.noise.sigma_scale = 0;
  options.noise.quantise = false;
  const SyntheticView clean = scene.RenderSensor(0), view = scene.RenderSensor(0, options);
  // The subject stands about 3 m from the sensor, 2-4 m in front of the back wall: its
  // shadow on the wall is f b (1/3 - 1/6) ~ 6 px wide or more, left of the silhouette.
  int rows = 0, rows_with_left_hole = 0;
  for (int y = 0; y < clean.mask.height; ++y) {
    int first = -1, last = -1;
    for (int x = 0; x < clean.mask.width; ++x) {
      if (clean.mask.at(x, y) == 0) continue;
      ASSERT_EQ(view.depth.at(x, y), clean.depth.at(x, y)) << x << "," << y;
      if (first < 0) first = x;
      last = x;
    }
    if (first < 4 || last > clean.mask.width - 4 || clean.depth.at(first - 1, y) == 0) continue;
    ++rows;
    rows_with_left_hole += view.depth.at(first - 1, y) == 0;
    for (int x = last + 1; x <= last + 3; ++x) EXPECT_NE(view.depth.at(x, y), 0) << x << "," << y;
  }
  ASSERT_GT(rows, 200);
  // Every row where background lies behind the silhouette's left edge (the floor right at
  // the feet excepted: it is barely behind them).
  EXPECT_GT(rows_with_left_hole, 0.8 * rows);
}

TEST(ProjectorShadow, BadInputsAreRefused) {
  const PinholeCamera c = Camera();
  ImageDepthMm depth(c.width, c.height, 1, 3000);
  EXPECT_THROW(ApplyProjectorShadow(nullptr, c), CheckError);
  ImageDepthMm small(10, 10, 1, 3000);
  EXPECT_THROW(ApplyProjectorShadow(&small, c), CheckError);
  PinholeCamera no_focal = c;
  no_focal.fx = 0;
  EXPECT_THROW(ApplyProjectorShadow(&depth, no_focal), CheckError);
  no_focal.fx = std::nan("");
  EXPECT_THROW(ApplyDepthNoise(&depth, no_focal, 1), CheckError);
  for (double b : {0.0, -0.075, 2.0, std::nan("")}) {
    DepthNoiseOptions o;
    o.projector_baseline_m = b;
    EXPECT_THROW(o.Check(), CheckError) << b;
    EXPECT_THROW(ApplyProjectorShadow(&depth, c, o), CheckError) << b;
  }
  DepthNoiseOptions o;
  o.shadow_margin_px = -1;
  EXPECT_THROW(o.Check(), CheckError);
  // The image is untouched by the refused calls.
  for (uint16_t d : depth.data) ASSERT_EQ(d, 3000);
}

}  // namespace
}  // namespace reenact::capture

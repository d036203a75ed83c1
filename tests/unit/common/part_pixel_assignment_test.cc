#include "common/model/part_pixel_assignment.h"

#include <gtest/gtest.h>

namespace reenact {
namespace {

// Two vertical axes in the image, 40 pixels apart: part 0 at x = 100, part 1 at x = 140, both
// from y = 100 to y = 200.
ProjectedPartAxes TwoAxes() {
  ProjectedPartAxes axes;
  for (int p = 0; p < 2; ++p) {
    ProjectedPartAxis axis;
    axis.a = Eigen::Vector2d(100 + 40 * p, 100);
    axis.b = Eigen::Vector2d(100 + 40 * p, 200);
    axis.length_px = 100;
    axis.dir = Eigen::Vector2d(0, 1);
    axis.normal = Eigen::Vector2d(-1, 0);
    axes[p] = axis;
  }
  return axes;
}

TEST(ProjectPartAxis, ProjectsTheSegmentAndRejectsDegenerateOnes) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const auto axis = ProjectPartAxis({0, -0.5, 2}, {0, 0.5, 2}, cam);
  ASSERT_TRUE(axis);
  EXPECT_NEAR(axis->length_px, cam.fy * 1.0 / 2, 1e-9);
  EXPECT_NEAR(axis->dir.y(), 1, 1e-12);
  EXPECT_NEAR(axis->normal.dot(axis->dir), 0, 1e-12);
  EXPECT_NEAR(axis->normal.norm(), 1, 1e-12);
  EXPECT_FALSE(ProjectPartAxis({0, 0, 2}, {0, 0, -1}, cam));     // an end behind
  EXPECT_FALSE(ProjectPartAxis({0, 0, 2}, {0.001, 0, 2}, cam));  // 0.26 px long
  EXPECT_FALSE(ProjectPartAxis({0, 0, 2}, {0, 0, 3}, cam));      // along the ray
}

TEST(AssignPixelToPart, NearestAxisAcrossWithinTheSegment) {
  const ProjectedPartAxes axes = TwoAxes();
  const auto left = AssignPixelToPart({110, 150}, axes);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->part, 0);
  EXPECT_NEAR(left->t, 0.5, 1e-12);
  EXPECT_NEAR(left->offset_px, -10, 1e-12);  // normal points to -x
  EXPECT_EQ(AssignPixelToPart({135, 120}, axes)->part, 1);
  EXPECT_EQ(AssignPixelToPart({120, 150}, axes)->part, 0);  // a tie goes to the lower index
  EXPECT_FALSE(AssignPixelToPart({110, 99}, axes));         // above both segments
  EXPECT_FALSE(AssignPixelToPart({110, 201}, axes));        // below both
}

TEST(AssignPixelToPart, DistanceInUnitsOfEachPartsRadius) {
  // Part 0 is 30 pixels thick, part 1 5: a pixel 25 pixels from part 0's axis and 15 from
  // part 1's is inside part 0 (25 / 30) and far outside part 1 (15 / 5).
  ProjectedPartAxes axes = TwoAxes();
  axes[0]->distance_unit_a = axes[0]->distance_unit_b = 30;
  axes[1]->distance_unit_a = axes[1]->distance_unit_b = 5;
  EXPECT_EQ(AssignPixelToPart({125, 150}, axes)->part, 0);
  // Units linear in t: part 1 grows to 50 at its b end.
  axes[1]->distance_unit_b = 50;
  EXPECT_EQ(AssignPixelToPart({125, 190}, axes)->part, 1);  // 25 / 30 vs 15 / 45.5
}

TEST(AssignPixelToPart, EndBandsKeepPixelsPastTheEnd) {
  ProjectedPartAxes axes = TwoAxes();
  axes[1]->end_band_a_px = 4;
  const auto past = AssignPixelToPart({138, 97}, axes);
  ASSERT_TRUE(past);
  EXPECT_EQ(past->part, 1);
  EXPECT_EQ(past->t, 0);
  EXPECT_NEAR(past->offset_px, 2, 1e-12);
  EXPECT_FALSE(AssignPixelToPart({138, 95}, axes));  // past the band
}

TEST(AssignPixelToPart, DepthPicksThePartWhoseSurfaceIsThere) {
  // Part 0 (a torso) at 2.5 m with radius 0.2 m, 40 pixels; part 1 (a forearm) crossing in
  // front at 2.1 m, radius 0.05 m, 10 pixels, its axis 10 pixels to the side. A pixel on
  // part 0's axis and part 1's rim: by the image alone it is part 0's (0 vs 1 radius); with a
  // reading of 2.1 m it lies on part 1's surface (distance 0) and a radius off part 0's (whose
  // axis is 2 radii behind it).
  ProjectedPartAxes axes = TwoAxes();
  axes[0]->distance_unit_a = axes[0]->distance_unit_b = 40;
  axes[0]->depth_a_m = axes[0]->depth_b_m = 2.5;
  axes[0]->radius_m = 0.2;
  axes[1]->a = Eigen::Vector2d(110, 100);
  axes[1]->b = Eigen::Vector2d(110, 200);
  axes[1]->distance_unit_a = axes[1]->distance_unit_b = 10;
  axes[1]->depth_a_m = axes[1]->depth_b_m = 2.1;
  axes[1]->radius_m = 0.05;
  EXPECT_EQ(AssignPixelToPart({100, 150}, axes)->part, 0);       // no reading: the image
  EXPECT_EQ(AssignPixelToPart({100, 150}, axes, 2.1)->part, 1);  // on part 1's rim
  EXPECT_EQ(AssignPixelToPart({100, 150}, axes, 2.3)->part, 0);  // on part 0's front
}

}  // namespace
}  // namespace reenact

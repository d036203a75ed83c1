// Person detection without a skeleton on ray-cast depth (a floor, a wall, upright cylinders
// of a person's size): defined results for all-zero depth, no floor, no person, one person
// and two blobs.
#include "capture-client/tracker/person_detector.h"

#include <gtest/gtest.h>

#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/tracker_test_scenes.h"

namespace reenact::capture {
namespace {

using tracker_test::Cylinder;
using tracker_test::RayScene;
using tracker_test::RenderDepth;

const PinholeCamera kCamera = PinholeCamera::KinectLike();

int MaskPixels(const PersonBlob& b) {
  int n = 0;
  for (uint8_t m : b.mask.data) n += m != 0;
  return n;
}

TEST(PersonDetector, AllZeroDepthIsNoDepthWithAnEmptyMask) {
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(ImageDepthMm(kCamera.width, kCamera.height, 1, 0));
  EXPECT_EQ(blob.status, DetectStatus::kNoDepth);
  EXPECT_TRUE(blob.points.empty());
  EXPECT_EQ(MaskPixels(blob), 0);
  EXPECT_EQ(blob.mask.width, kCamera.width / 2);  // grid of 2 px
}

TEST(PersonDetector, AWallWithoutFloorIsNoFloor) {
  RayScene scene;
  scene.floor = false;
  scene.wall_z = 3;
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(scene, kCamera));
  EXPECT_EQ(blob.status, DetectStatus::kNoFloor);
  EXPECT_TRUE(blob.points.empty());
}

TEST(PersonDetector, AnEmptyRoomIsNoPerson) {
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(RayScene{}, kCamera));
  EXPECT_EQ(blob.status, DetectStatus::kNoPerson);
  ASSERT_TRUE(blob.floor_in_sensor);
  // The floor y = 1.3 (sensor frame), normal up (-y): within the fit's 1 cm tolerance.
  EXPECT_GT(-blob.floor_in_sensor->normal.y(), 0.999);
  EXPECT_NEAR(blob.floor_in_sensor->SignedDistance(Eigen::Vector3d::Zero()), 1.3, 0.01);
  EXPECT_EQ(blob.plausible_regions, 0);  // the wall is far too wide
}

TEST(PersonDetector, FindsOnePersonWithItsHeightAndPlace) {
  RayScene scene;
  scene.people = {Cylinder{0.3, 3.0, 0.18, 1.7}};
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(scene, kCamera));
  ASSERT_EQ(blob.status, DetectStatus::kOk);
  EXPECT_EQ(blob.plausible_regions, 1);
  // Top: the cylinder's 1.7 m, up to the millimetre depth steps and the grid (2 px = 9 mm
  // at 3 m).
  EXPECT_NEAR(blob.top_height_m, 1.7, 0.02);
  // Bottom: the floor clearance (8 mm + 5 mm/m^2 z^2 |n.p|/z, 2.5 cm here) cuts the foot.
  EXPECT_LT(blob.bottom_height_m, 0.05);
  // The visible front lies up to one radius before the axis.
  EXPECT_NEAR(blob.centroid.x(), 0.3, 0.03);
  EXPECT_NEAR(blob.centroid.z(), 3.0 - 0.14, 0.05);
  for (const Eigen::Vector3d& p : blob.points) ASSERT_TRUE(p.allFinite());
  EXPECT_EQ(static_cast<int>(blob.points.size()), MaskPixels(blob));
}

TEST(PersonDetector, TwoBlobsGiveTheLargerOrTheOneNearThePreviousCentroid) {
  RayScene scene;
  const Cylinder adult{-0.8, 3.0, 0.18, 1.75}, child{0.9, 3.5, 0.13, 1.2};
  scene.people = {adult, child};
  const ImageDepthMm depth = RenderDepth(scene, kCamera);
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob first = detector.Detect(depth);
  ASSERT_EQ(first.status, DetectStatus::kOk);
  EXPECT_EQ(first.plausible_regions, 2);
  EXPECT_NEAR(first.centroid.x(), adult.x, 0.05);  // the larger blob
  const PersonBlob tracked =
      detector.Detect(depth, std::nullopt, std::nullopt, Eigen::Vector3d(child.x, 0.6, child.z));
  ASSERT_EQ(tracked.status, DetectStatus::kOk);
  EXPECT_NEAR(tracked.centroid.x(), child.x, 0.05);  // the one tracked before
  // A previous centroid far from both: no person (the tracked one is gone).
  const PersonBlob gone =
      detector.Detect(depth, std::nullopt, std::nullopt, Eigen::Vector3d(3, 0.5, 5));
  EXPECT_EQ(gone.status, DetectStatus::kNoPerson);
}

TEST(PersonDetector, AHandBehindTheHeadJoinsThePersonOnlyWhileTracking) {
  // A person 1.7 m tall at 3 m (front at 2.82 m) and a "hand" 10 cm thick held up behind its
  // head, from 1.5 to 2.0 m above the floor at 3.5 m (front at 3.45 m): from the sensor, 1.3 m
  // high, the part above 1.79 m shows above the head, 0.55-0.63 m deeper than the head's
  // edge. That gap lies between merge_step_m (0.4) and tracking_merge_step_m (0.8).
  RayScene scene;
  scene.people = {Cylinder{0, 3.0, 0.18, 1.7}, Cylinder{0.1, 3.5, 0.05, 2.0, 1.5}};
  const ImageDepthMm depth = RenderDepth(scene, kCamera);
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob found = detector.Detect(depth);
  ASSERT_EQ(found.status, DetectStatus::kOk);
  for (const Eigen::Vector3d& p : found.points) ASSERT_LT(p.z(), 3.0);  // the person alone
  EXPECT_NEAR(found.top_height_m, 1.7, 0.02);
  const PersonBlob tracked = detector.Detect(depth, std::nullopt, std::nullopt, found.centroid);
  ASSERT_EQ(tracked.status, DetectStatus::kOk);
  int hand = 0;
  for (const Eigen::Vector3d& p : tracked.points) {
    if (p.z() < 3.0) continue;
    ++hand;
    EXPECT_NEAR(p.x(), 0.1, 0.05 + 0.01);  // its radius and the 2 px grid
    EXPECT_GT(1.3 - p.y(), 1.79 - 0.02);   // the part above the head
  }
  EXPECT_GT(hand, 20);  // 10 x 21 cm at 3.45 m: about 7 x 15 grid pixels
  EXPECT_NEAR(tracked.top_height_m, 2.0, 0.02);
  EXPECT_EQ(tracked.points.size(), found.points.size() + hand);
  // With the acquisition's gap while tracking, the hand stays apart.
  PersonDetectOptions narrow;
  narrow.tracking_merge_step_m = narrow.merge_step_m;
  PersonDetector narrow_detector(kCamera, 0.001, narrow);
  const PersonBlob apart =
      narrow_detector.Detect(depth, std::nullopt, std::nullopt, found.centroid);
  ASSERT_EQ(apart.status, DetectStatus::kOk);
  EXPECT_EQ(apart.points.size(), found.points.size());
}

TEST(PersonDetector, ObjectsOfTheWrongSizeAreNoPerson) {
  RayScene scene;
  scene.people = {Cylinder{0, 3.0, 0.18, 0.4},    // too low (a box)
                  Cylinder{1.2, 3.0, 0.5, 1.7}};  // too wide at the top (a cabinet)
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(scene, kCamera));
  EXPECT_EQ(blob.status, DetectStatus::kNoPerson);
}

TEST(PersonDetector, ADepthImageOfTheWrongSizeIsABug) {
  PersonDetector detector(kCamera, 0.001);
  EXPECT_THROW(detector.Detect(ImageDepthMm(10, 10, 1, 0)), CheckError);
  PersonDetectOptions bad;
  bad.grid_step_px = 0;
  EXPECT_THROW(PersonDetector(kCamera, 0.001, bad), CheckError);
  PersonDetectOptions negative_gap;
  negative_gap.tracking_merge_step_m = -0.1;
  EXPECT_THROW(PersonDetector(kCamera, 0.001, negative_gap), CheckError);
}

}  // namespace
}  // namespace reenact::capture

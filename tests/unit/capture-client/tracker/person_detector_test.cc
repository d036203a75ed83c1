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

TEST(PersonDetector, AWallWithoutFloorIsNoPerson) {
  RayScene scene;
  scene.floor = false;
  scene.wall_z = 3;
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(scene, kCamera));
  EXPECT_EQ(blob.status, DetectStatus::kNoPerson);  // 4.9 m wide at its top: no head
  EXPECT_TRUE(blob.points.empty());
}

// Without a floor in view (the background removed, as utd-mhad's Kinect SDK export has it).
// The image's lower edge is at y / z = (480 - 255.3) / 516.5 = 0.435 below the axis: a person
// at 4 m shows its feet (the floor y = 1.3 is at 0.33), one at 1.4 m is cut at 0.61 m (0.69 m
// above the floor). Heights: along the image's up, -y (a level sensor).
RayScene WithoutFloor(std::vector<Cylinder> people) {
  RayScene scene;
  scene.floor = false;
  scene.wall_z = 0;
  scene.people = std::move(people);
  return scene;
}

double FloorY(const PersonBlob& blob) {  // where the blob's floor crosses the axis x = z = 0
  return blob.floor_in_sensor->offset / blob.floor_in_sensor->normal.y();
}

TEST(PersonDetector, WithoutAFloorAPersonStandsOnItsFeet) {
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob =
      detector.Detect(RenderDepth(WithoutFloor({Cylinder{0.3, 4.0, 0.18, 1.7}}), kCamera));
  ASSERT_EQ(blob.status, DetectStatus::kOk);
  EXPECT_EQ(blob.floor_source, FloorSource::kPersonLowest);
  EXPECT_FALSE(blob.touches_bottom);
  ASSERT_TRUE(blob.floor_in_sensor);
  EXPECT_NEAR(blob.floor_in_sensor->normal.y(), -1, 1e-9);
  // The lowest grid row on the cylinder: within 2 px (1.5 cm at 3.8 m) of its foot.
  EXPECT_NEAR(FloorY(blob), 1.3, 0.02);
  EXPECT_NEAR(blob.top_height_m, 1.7, 0.03);
  EXPECT_NEAR(blob.bottom_height_m, 0, 1e-9);
}

TEST(PersonDetector, WithoutAFloorOrFeetTheStatureIsAssumed) {
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob =
      detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 1.4, 0.18, 1.85}}), kCamera));
  ASSERT_EQ(blob.status, DetectStatus::kOk);
  EXPECT_TRUE(blob.touches_bottom);
  EXPECT_EQ(blob.floor_source, FloorSource::kAssumedStature);
  const double stature = PersonDetectOptions{}.assumed_stature_m;
  EXPECT_NEAR(blob.top_height_m, stature, 1e-9);
  // The top at y = 1.3 - 1.85; the floor assumed 1.7 m below it.
  EXPECT_NEAR(FloorY(blob), 1.3 - 1.85 + stature, 0.02);
}

TEST(PersonDetector, FeetSeenOnceKeepTheirFloorWhenTheLegsLeaveTheImage) {
  PersonDetector detector(kCamera, 0.001);
  ASSERT_EQ(detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 4.0, 0.18, 1.85}}), kCamera))
                .status,
            DetectStatus::kOk);
  const PersonBlob near =
      detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 1.4, 0.18, 1.85}}), kCamera));
  ASSERT_EQ(near.status, DetectStatus::kOk);
  EXPECT_TRUE(near.touches_bottom);
  EXPECT_EQ(near.floor_source, FloorSource::kPersonLowest);
  EXPECT_NEAR(FloorY(near), 1.3, 0.02);
  EXPECT_NEAR(near.top_height_m, 1.85, 0.03);
  // Forgotten with the floor.
  detector.ResetFloor();
  EXPECT_EQ(detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 1.4, 0.18, 1.85}}), kCamera))
                .floor_source,
            FloorSource::kAssumedStature);
}

TEST(PersonDetector, FeetLiftedOffTheFloorKeepTheLowerFloor) {
  PersonDetector detector(kCamera, 0.001);
  ASSERT_EQ(detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 4.0, 0.18, 1.7}}), kCamera))
                .status,
            DetectStatus::kOk);
  // A jump: the whole person 25 cm up.
  const PersonBlob jump =
      detector.Detect(RenderDepth(WithoutFloor({Cylinder{0, 4.0, 0.18, 1.95, 0.25}}), kCamera));
  ASSERT_EQ(jump.status, DetectStatus::kOk);
  EXPECT_NEAR(FloorY(jump), 1.3, 0.02);
  EXPECT_NEAR(jump.bottom_height_m, 0.25, 0.03);
  EXPECT_NEAR(jump.top_height_m, 1.95, 0.03);
}

TEST(PersonDetector, WithoutAFloorTwoPeopleGiveTheLarger) {
  const Cylinder adult{-0.8, 4.0, 0.18, 1.75}, child{0.9, 4.2, 0.13, 1.2};
  PersonDetector detector(kCamera, 0.001);
  const PersonBlob blob = detector.Detect(RenderDepth(WithoutFloor({adult, child}), kCamera));
  ASSERT_EQ(blob.status, DetectStatus::kOk);
  EXPECT_EQ(blob.plausible_regions, 2);
  EXPECT_NEAR(blob.centroid.x(), adult.x, 0.05);
  EXPECT_NEAR(FloorY(blob), 1.3, 0.02);
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

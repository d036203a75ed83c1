// The crotch's height from a person's depth (crotch_height.h) on ray-cast figures of known
// geometry: legs apart, legs together, a leg in front of the gap, and degenerate input; and
// the legs scaled by it (body_calibration.h's WithLegsScaled, ScaleBeyondNoise).
#include "capture-client/tracker/crotch_height.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "capture-client/tracker/body_calibration.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using tracker_test::AboveFloor;
using tracker_test::SceneBlob;
using Capsule = tracker_test::SceneCapsule;

// A trunk (radius 0.17, its lowest point 0.78 m above the floor, at depth 3 m) on two legs
// (radius r) from the hips, 9 cm either side of the middle at 0.85 m, to the ankles.
std::vector<Capsule> Figure(const Eigen::Vector3d& left_ankle, const Eigen::Vector3d& right_ankle,
                            double r = 0.06) {
  return {{AboveFloor(0, 0.95, 3), AboveFloor(0, 1.45, 3), 0.17},
          {AboveFloor(-0.09, 0.85, 3), left_ankle, r},
          {AboveFloor(0.09, 0.85, 3), right_ankle, r}};
}

const PinholeCamera kCamera = PinholeCamera::KinectLike();

TEST(CrotchHeight, LegsApartShowTheGapUpToTheCrotch) {
  // Ankles 25 cm either side of the middle: between the legs the sensor sees the room up to
  // the trunk's lowest point, 0.78 m, on the middle line. Bound: the line is followed in 5 mm
  // steps and read on a grid of 2 px (1.2 cm at 3 m), so within 1.5 cm.
  const Eigen::Vector3d left = AboveFloor(-0.25, 0.08, 3), right = AboveFloor(0.25, 0.08, 3);
  const auto crotch = MeasureCrotchHeight(SceneBlob(Figure(left, right)), kCamera, left, right);
  ASSERT_TRUE(crotch);
  EXPECT_NEAR(*crotch, 0.78, 0.015);
}

TEST(CrotchHeight, LegsTogetherGiveNoMeasurement) {
  // Thick legs straight down from the hips touch: the first hit is a leg near the floor,
  // below min_gap_m.
  const Eigen::Vector3d left = AboveFloor(-0.09, 0.08, 3), right = AboveFloor(0.09, 0.08, 3);
  EXPECT_FALSE(MeasureCrotchHeight(SceneBlob(Figure(left, right, 0.1)), kCamera, left, right));
}

TEST(CrotchHeight, ALegInFrontOfTheGapGivesNoMeasurement) {
  // A stride along the line of sight: the near leg (its ankle at 2.6 m, under the middle)
  // hides the lines between the ankles, its surface 25-40 cm in front of their depth. The
  // least gap is left out (min_gap_m 0), so that only the depth test can refuse it.
  const Eigen::Vector3d near = AboveFloor(0, 0.08, 2.6), far = AboveFloor(0, 0.08, 3.4);
  const PersonBlob blob = SceneBlob(Figure(near, far));
  EXPECT_FALSE(MeasureCrotchHeight(blob, kCamera, near, far, {.min_gap_m = 0}));
}

TEST(CrotchHeight, DegenerateInputGivesNoMeasurement) {
  const Eigen::Vector3d left = AboveFloor(-0.25, 0.08, 3), right = AboveFloor(0.25, 0.08, 3);
  const PersonBlob good = SceneBlob(Figure(left, right));
  ASSERT_TRUE(MeasureCrotchHeight(good, kCamera, left, right));
  PersonBlob no_floor = good;
  no_floor.floor_in_sensor.reset();
  EXPECT_FALSE(MeasureCrotchHeight(no_floor, kCamera, left, right));
  PersonBlob no_person = good;
  no_person.status = DetectStatus::kNoPerson;
  EXPECT_FALSE(MeasureCrotchHeight(no_person, kCamera, left, right));
  EXPECT_FALSE(MeasureCrotchHeight(PersonBlob{}, kCamera, left, right));
  PersonBlob no_depth = good;  // a mask without its depth readings
  no_depth.depth_m = Image<float>();
  EXPECT_FALSE(MeasureCrotchHeight(no_depth, kCamera, left, right));
  const Eigen::Vector3d nan(std::nan(""), 0, 3);
  EXPECT_FALSE(MeasureCrotchHeight(good, kCamera, nan, right));
  // Ankles behind the sensor: the line never projects.
  const Eigen::Vector3d behind_l = AboveFloor(-0.25, 0.08, -3),
                        behind_r = AboveFloor(0.25, 0.08, -3);
  EXPECT_FALSE(MeasureCrotchHeight(good, kCamera, behind_l, behind_r));
  EXPECT_THROW(MeasureCrotchHeight(good, kCamera, left, right, {.step_m = 0}), CheckError);
}

TEST(CrotchHeight, ScalingTheLegsKeepsTheStandingHeight) {
  const BodyShape average = BodyShape::FromHeight(1.7);
  const BodyShape shorter = WithLegsScaled(average, 0.9);
  EXPECT_NEAR(shorter.thigh, 0.9 * average.thigh, 1e-12);
  EXPECT_NEAR(shorter.shin, 0.9 * average.shin, 1e-12);
  EXPECT_NEAR(shorter.StandingHeight(), average.StandingHeight(), 1e-12);
  EXPECT_EQ(shorter.head_radius, average.head_radius);
  EXPECT_NEAR(shorter.lower_spine + shorter.upper_spine,
              average.lower_spine + average.upper_spine + 0.1 * (average.thigh + average.shin),
              1e-12);
  EXPECT_THROW(WithLegsScaled(average, -1.0), CheckError);
}

TEST(CrotchHeight, AReadingWithinTheNoiseOfTheAverageKeepsTheAverage) {
  EXPECT_DOUBLE_EQ(ScaleBeyondNoise(1.0, 0.05, 0.8, 1.2), 1.0);
  EXPECT_DOUBLE_EQ(ScaleBeyondNoise(1.04, 0.05, 0.8, 1.2), 1.0);
  EXPECT_DOUBLE_EQ(ScaleBeyondNoise(0.96, 0.05, 0.8, 1.2), 1.0);
  EXPECT_NEAR(ScaleBeyondNoise(0.85, 0.05, 0.8, 1.2), 0.9, 1e-12);
  EXPECT_NEAR(ScaleBeyondNoise(1.1, 0.05, 0.8, 1.2), 1.05, 1e-12);
  EXPECT_DOUBLE_EQ(ScaleBeyondNoise(2.0, 0.05, 0.8, 1.2), 1.2);
  EXPECT_DOUBLE_EQ(ScaleBeyondNoise(0.1, 0.05, 0.8, 1.2), 0.8);
  EXPECT_THROW(ScaleBeyondNoise(0.0, 0.05, 0.8, 1.2), CheckError);
  EXPECT_THROW(ScaleBeyondNoise(std::nan(""), 0.05, 0.8, 1.2), CheckError);
  EXPECT_THROW(ScaleBeyondNoise(1.0, -0.1, 0.8, 1.2), CheckError);
}

}  // namespace
}  // namespace reenact::capture

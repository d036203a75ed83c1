#include "synthetic/sensor_placement.h"

#include <gtest/gtest.h>

#include "common/error/check.h"
#include "synthetic/body_model.h"
#include "synthetic/scenario.h"

namespace reenact::capture {
namespace {

const RoomModel& Room() { return *SharedRoom(); }
const PinholeCamera kCamera = PinholeCamera::KinectLike();

Skeleton Standing(const Eigen::Vector2d& xy) {
  BodyPose pose;
  pose.root_xy = xy;
  return PoseBody(pose).skeleton;
}

TEST(SensorSeesSkeleton, ByConstruction) {
  const Eigen::Isometry3d sensor = LookAt({0, -3, 1.3}, {0, 0, 0.95});
  StaticSensorOptions o;
  EXPECT_TRUE(SensorSeesSkeleton(Standing({0, 0}), kCamera, sensor, Room(), o));
  // 3 m to the side at 3 m depth: outside the 63-degree field of view.
  EXPECT_FALSE(SensorSeesSkeleton(Standing({3, 0}), kCamera, sensor, Room(), o));
  // Closer than min_depth_m (the feet fall out of the image as well).
  EXPECT_FALSE(SensorSeesSkeleton(Standing({0, -2.4}), kCamera, sensor, Room(), o));
  // Behind the sensor.
  EXPECT_FALSE(SensorSeesSkeleton(Standing({0, -3.5}), kCamera, sensor, Room(), o));
  // A skeleton without joints is trivially seen.
  EXPECT_TRUE(SensorSeesSkeleton(Skeleton(), kCamera, sensor, Room(), o));
}

TEST(SensorSeesSkeleton, FurnitureHidesJoints) {
  // Sensor low behind the cardboard box (x 2.0-2.6, y -0.6-0.2, 0.6 m high), looking across
  // it at a subject: the feet are hidden.
  const Eigen::Isometry3d sensor = LookAt({2.8, -0.2, 0.3}, {0, -0.2, 0.3});
  StaticSensorOptions o;
  o.margin_px = 0;
  o.body_radius_m = 0;
  o.min_depth_m = 0.1;
  Skeleton feet;
  feet.Set(Joint::kLeftFoot, {0, -0.2, 0.3});
  EXPECT_FALSE(SensorSeesSkeleton(feet, kCamera, sensor, Room(), o));
  // The same joint seen from the open side of the room.
  const Eigen::Isometry3d open = LookAt({-1.5, -0.2, 0.3}, {0, -0.2, 0.3});
  EXPECT_TRUE(SensorSeesSkeleton(feet, kCamera, open, Room(), o));
}

TEST(PlaceStaticSensor, InPlaceMotionGetsThePreferredPose) {
  const std::vector<Skeleton> motion(10, Standing({0, 0}));
  const auto pose = PlaceStaticSensor(motion, kCamera, Room());
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  const Eigen::Isometry3d expected = LookAt({0, -3, 1.3}, motion[0][Joint::kWaist]);
  EXPECT_LT((pose->matrix() - expected.matrix()).norm(), 1e-12);
}

TEST(PlaceStaticSensor, AWalkTowardsTheSensorIsWatchedFromWhereItStaysInView) {
  // Walking 3 m along -y from the origin would run into the preferred sensor position.
  std::vector<Skeleton> motion;
  for (int k = 0; k <= 30; ++k) motion.push_back(Standing({0, -0.1 * k}));
  StaticSensorOptions o;
  ASSERT_FALSE(
      SensorSeesSkeleton(motion.back(), kCamera, LookAt({0, -3, 1.3}, {0, 0, 0.95}), Room(), o));
  const auto pose = PlaceStaticSensor(motion, kCamera, Room(), o);
  ASSERT_TRUE(pose.ok()) << pose.error().message;
  for (const Skeleton& s : motion) EXPECT_TRUE(SensorSeesSkeleton(s, kCamera, *pose, Room(), o));
  const Eigen::Vector3d eye = pose->translation();
  EXPECT_NEAR(eye.z(), o.height_m, 1e-12);
  EXPECT_TRUE(((eye - Room().room_min).array() >= o.wall_clearance_m - 1e-9).all());
  EXPECT_TRUE(((Room().room_max - eye).array() >= o.wall_clearance_m - 1e-9).all());
}

TEST(PlaceStaticSensor, ImpossibleMotionIsAnError) {
  // Subjects 5 m apart on both sides: no sensor in a 6 m room sees both.
  const std::vector<Skeleton> motion = {Standing({-2.5, 0}), Standing({2.5, 2.0}),
                                        Standing({0, -3.5})};
  const auto pose = PlaceStaticSensor(motion, kCamera, Room());
  ASSERT_FALSE(pose.ok());
  EXPECT_EQ(pose.error().code, "unsupported");
  EXPECT_NE(pose.error().message.find("the motion spans x [-2."), std::string::npos)
      << pose.error().message;
}

TEST(PlaceStaticSensor, EmptyOrWaistlessMotionIsAnError) {
  EXPECT_EQ(PlaceStaticSensor({}, kCamera, Room()).error().code, "invalid_argument");
  const std::vector<Skeleton> none(1);
  EXPECT_EQ(PlaceStaticSensor(none, kCamera, Room()).error().code, "invalid_argument");
  StaticSensorOptions bad;
  bad.distance_step_m = 0;
  EXPECT_THROW(PlaceStaticSensor(none, kCamera, Room(), bad), CheckError);
}

}  // namespace
}  // namespace reenact::capture

// The posed body's top above the floor (body_start.h's PosedTopHeight), which decides when a
// body started short (seated) starts again at the person's height.
#include "capture-client/tracker/body_start.h"

#include <gtest/gtest.h>

#include "capture-client/tracker/heading.h"
#include "common/error/check.h"

namespace reenact::capture {
namespace {

const Eigen::Vector3d kUp(0, -1, 0);  // OpenCV sensor frame, level sensor
const Plane3 kFloor{kUp, -1.3};       // y = 1.3

TEST(PosedTopHeight, StandingUprightItIsTheStandingHeight) {
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  const ArticulatedPose p = UprightPose(body, Eigen::Vector3d(0, 1.3, 3), kUp, Eigen::Vector3d(0, 0, -1));
  // The rest pose stands on its soles: the top is the standing height by construction.
  EXPECT_NEAR(PosedTopHeight(body, body.Pose(p).skeleton, kFloor), body.shape().StandingHeight(),
              1e-9);
}

TEST(PosedTopHeight, ARaisedHandAboveTheHeadIsTheTop) {
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  Skeleton s = body.Pose(UprightPose(body, Eigen::Vector3d(0, 1.3, 3), kUp,
                                     Eigen::Vector3d(0, 0, -1)))
                   .skeleton;
  s[Joint::kRightHand] = Eigen::Vector3d(0.2, 1.3 - 2.1, 3);  // 2.1 m above the floor
  EXPECT_NEAR(PosedTopHeight(body, s, kFloor), 2.1, 1e-9);
}

TEST(BodyStartOptions, BadRestartAndFacingValuesAreABug) {
  BodyStartOptions o;
  o.facing_sensor_gain = 1;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.restart_taller_m = 0;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.restart_taller_frames = 0;
  EXPECT_THROW(o.Check(), CheckError);
  EXPECT_NO_THROW(BodyStartOptions{}.Check());
}

}  // namespace
}  // namespace reenact::capture

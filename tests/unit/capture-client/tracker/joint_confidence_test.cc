// Joints outside the image are reported missing (joint_confidence.h's MarkJointsOutOfView).
#include "capture-client/tracker/joint_confidence.h"

#include <gtest/gtest.h>

namespace reenact::capture {
namespace {

TEST(MarkJointsOutOfView, OnlyJointsProjectingIntoTheImageStay) {
  const PinholeCamera camera = PinholeCamera::KinectLike();  // 640 x 480, cy 255.3, fy 516.5
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j) {
    s.position[j] = Eigen::Vector3d(0, 0, 2);  // the image's centre
    s.confidence[j] = 0.7;
  }
  // Below the lower edge: y / z > (480 - 255.3) / 516.5 = 0.435; left of the left edge;
  // behind the sensor; on the sensor's plane (z = 0).
  s[Joint::kLeftFoot] = Eigen::Vector3d(0, 0.9, 2);
  s[Joint::kRightFoot] = Eigen::Vector3d(-2, 0, 2);
  s[Joint::kLeftKnee] = Eigen::Vector3d(0, 0, -1);
  s[Joint::kRightKnee] = Eigen::Vector3d(0, 0, 0);
  // Just inside the lower edge.
  s[Joint::kWaist] = Eigen::Vector3d(0, 0.85, 2);
  MarkJointsOutOfView(camera, &s);
  for (const Joint j : {Joint::kLeftFoot, Joint::kRightFoot, Joint::kLeftKnee, Joint::kRightKnee})
    EXPECT_EQ(s.confidence[Index(j)], 0) << JointName(j);
  EXPECT_EQ(s.confidence[Index(Joint::kWaist)], 0.7);
  EXPECT_EQ(s.confidence[Index(Joint::kHead)], 0.7);
  for (const Eigen::Vector3d& p : s.position) EXPECT_TRUE(p.allFinite());
}

}  // namespace
}  // namespace reenact::capture

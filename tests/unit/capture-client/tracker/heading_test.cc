// Candidate headings, upright start poses and the travel direction (heading.h), with their
// degenerate inputs.
#include "capture-client/tracker/heading.h"

#include <gtest/gtest.h>

#include <cmath>

namespace reenact::capture {
namespace {

const Eigen::Vector3d kUp(0, -1, 0);  // OpenCV sensor frame, level sensor

TEST(Heading, CandidatesAreEvenlySpacedAndStartFacingTheSensor) {
  const auto h = CandidateHeadings(kUp, Eigen::Vector3d(0.2, -0.5, -3), 8);
  ASSERT_EQ(h.size(), 8u);
  EXPECT_NEAR(h[0].dot(Eigen::Vector3d(0.2, 0, -3).normalized()), 1, 1e-12);
  for (size_t k = 0; k < h.size(); ++k) {
    EXPECT_NEAR(h[k].norm(), 1, 1e-12);
    EXPECT_NEAR(h[k].dot(kUp), 0, 1e-12);
    EXPECT_NEAR(h[k].dot(h[(k + 1) % 8]), std::cos(M_PI / 4), 1e-12);
  }
}

TEST(Heading, DegenerateDirectionsGiveNoCandidatesAndDefinedPoses) {
  EXPECT_TRUE(CandidateHeadings(kUp, Eigen::Vector3d(0, -2, 0), 8).empty());
  EXPECT_TRUE(CandidateHeadings(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, -1), 8).empty());
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  const ArticulatedPose p = UprightPose(body, Eigen::Vector3d(0, 1.3, 3), kUp, kUp);
  EXPECT_TRUE(p.root_rotation.allFinite());
  EXPECT_NEAR(p.root_rotation.determinant(), 1, 1e-9);
  EXPECT_NEAR(p.root_rotation.col(2).dot(kUp), 1, 1e-12);
}

TEST(Heading, UprightPoseStandsOnTheGroundFacingForward) {
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  const Eigen::Vector3d ground(0, 1.3, 3), forward(1, 0.3, 0);
  const ArticulatedPose p = UprightPose(body, ground, kUp, forward);
  EXPECT_NEAR(p.root_rotation.determinant(), 1, 1e-9);
  EXPECT_NEAR(p.root_rotation.col(0).dot(Eigen::Vector3d(1, 0, 0)), 1, 1e-12);
  // The feet (ankle joints) stand ankle_height above the ground.
  const Skeleton s = body.Pose(p).skeleton;
  EXPECT_NEAR((s[Joint::kLeftFoot] - ground).dot(kUp), body.shape().ankle_height, 1e-9);
  // TurnedTo turns it about up to face the other way, the waist kept.
  const ArticulatedPose t = TurnedTo(p, kUp, -forward);
  EXPECT_NEAR(t.root_rotation.col(0).dot(Eigen::Vector3d(-1, 0, 0)), 1, 1e-9);
  EXPECT_TRUE(t.root_translation.isApprox(p.root_translation));
}

TEST(Heading, TravelNeedsTheMinimumDistanceWithinTheWindow) {
  TravelDirection travel(5, 0.3);
  EXPECT_FALSE(travel.Direction(kUp));
  for (int k = 0; k < 5; ++k) travel.Add(Eigen::Vector3d(0.05 * k, 1.0 - 0.1 * k, 3));
  EXPECT_FALSE(travel.Direction(kUp));  // 0.2 m across the floor (the vertical part ignored)
  for (int k = 5; k < 12; ++k) travel.Add(Eigen::Vector3d(0.1 * k, 1.0, 3));
  const auto d = travel.Direction(kUp);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->x(), 1, 1e-12);
  EXPECT_FALSE(travel.Direction(Eigen::Vector3d::Zero()));
  travel.Clear();
  EXPECT_FALSE(travel.Direction(kUp));
}

}  // namespace
}  // namespace reenact::capture

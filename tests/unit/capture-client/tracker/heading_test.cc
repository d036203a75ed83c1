// Candidate headings, upright start poses and the travel direction (heading.h), with their
// degenerate inputs.
#include "capture-client/tracker/heading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error/check.h"

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

TEST(Heading, FacesAwayFromTheSensorByItsForwardAcrossTheFloor) {
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  const Eigen::Vector3d ground(0.5, 1.3, 3), sensor = Eigen::Vector3d::Zero();
  // Facing the sensor (-z, the way back to it) and turned around.
  EXPECT_FALSE(FacesAwayFrom(UprightPose(body, ground, kUp, Eigen::Vector3d(0, 0, -1)), kUp, sensor));
  // Side on: the way to the sensor, (-0.5, 0, -3), leans towards -x, so -x faces it.
  EXPECT_FALSE(FacesAwayFrom(UprightPose(body, ground, kUp, Eigen::Vector3d(-1, 0, 0)), kUp, sensor));
  EXPECT_TRUE(FacesAwayFrom(UprightPose(body, ground, kUp, Eigen::Vector3d(1, 0, 0)), kUp, sensor));
  EXPECT_TRUE(FacesAwayFrom(UprightPose(body, ground, kUp, Eigen::Vector3d(0, 0, 1)), kUp, sensor));
  // Degenerate: a sensor straight above the waist (no horizontal way to it), a zero up.
  const ArticulatedPose p = UprightPose(body, ground, kUp, Eigen::Vector3d(0, 0, 1));
  EXPECT_FALSE(FacesAwayFrom(p, kUp, p.root_translation + 2 * kUp));
  EXPECT_FALSE(FacesAwayFrom(p, Eigen::Vector3d::Zero(), sensor));
}

TEST(Heading, TurnedByTurnsTheWholeBodyAboutTheWaist) {
  const ArticulatedBody body(BodyShape::FromHeight(1.7));
  const Eigen::Vector3d ground(0, 1.3, 3), forward(0, 0, -1);
  ArticulatedPose p = UprightPose(body, ground, kUp, forward);
  p.hinge_angle[static_cast<int>(BodySegment::kLeftForearm)] = 0.8;  // limbs kept as they are
  const ArticulatedPose t = TurnedBy(p, 2 * kUp, std::numbers::pi / 6);
  // Turning by +30 degrees about up (-y) takes forward -z towards up x forward = +x.
  const Eigen::Vector3d expected(0.5, 0, -std::sqrt(3.0) / 2);
  EXPECT_NEAR(HorizontalForward(t, kUp)->dot(expected), 1, 1e-12);
  EXPECT_TRUE(t.root_translation.isApprox(p.root_translation));
  EXPECT_EQ(t.hinge_angle, p.hinge_angle);
  // Every joint keeps its height and its distance from the waist's vertical.
  const Skeleton a = body.Pose(p).skeleton, b = body.Pose(t).skeleton;
  for (int j = 0; j < kJointCount; ++j) {
    const Eigen::Vector3d da = a[static_cast<Joint>(j)] - p.root_translation;
    const Eigen::Vector3d db = b[static_cast<Joint>(j)] - t.root_translation;
    EXPECT_NEAR(da.dot(kUp), db.dot(kUp), 1e-12);
    EXPECT_NEAR(da.norm(), db.norm(), 1e-12);
  }
  // TurnedTo is the same turn, to a heading.
  EXPECT_TRUE(TurnedTo(p, kUp, expected).root_rotation.isApprox(t.root_rotation, 1e-12));
  // A zero up turns nothing.
  EXPECT_TRUE(TurnedBy(p, Eigen::Vector3d::Zero(), 1.0).root_rotation.isApprox(p.root_rotation));
}

TEST(Heading, TravelNeedsTheMinimumDistanceWithinTheWindow) {
  TravelDirection travel({.window_frames = 5, .max_window_frames = 5});
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

TEST(Heading, TravelNeedsASteadyWalk) {
  // 0.5 m along x in 10 frames: steady.
  TravelDirection travel({.window_frames = 10, .max_window_frames = 10});
  for (int k = 0; k < 10; ++k) travel.Add(Eigen::Vector3d(0.05 * k, 1.0, 3));
  ASSERT_TRUE(travel.Direction(kUp));
  // Turning on the spot for the window's first half, then stepping 0.4 m: 1 cm against 40;
  // the first half covers less than a quarter of the distance (a subject that turned and
  // steps back or aside does not face its displacement).
  const auto turn_then_step = [](TravelDirection& t) {
    for (int k = 0; k <= 5; ++k) t.Add(Eigen::Vector3d(0.002 * k, 1.0, 3));
    for (int k = 1; k < 5; ++k) t.Add(Eigen::Vector3d(0.01 + 0.1 * k, 1.0, 3));
  };
  travel.Clear();
  turn_then_step(travel);
  EXPECT_FALSE(travel.Direction(kUp));
  // Without the steadiness asked for, the same path gives its direction.
  TravelDirection any_walk({.window_frames = 10, .max_window_frames = 10, .min_half_share = 0});
  turn_then_step(any_walk);
  const auto d = any_walk.Direction(kUp);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->x(), 1, 1e-12);
  // A quarter circle of 0.6 m radius at an even pace: steady (the chord, 45 degrees from
  // either end's tangent, is the direction).
  travel.Clear();
  for (int k = 0; k < 10; ++k) {
    const double a = k * std::numbers::pi / 2 / 9;
    travel.Add(Eigen::Vector3d(0.6 * std::sin(a), 1.0, 3 + 0.6 * (1 - std::cos(a))));
  }
  const auto arc = travel.Direction(kUp);
  ASSERT_TRUE(arc);
  EXPECT_NEAR(arc->x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(arc->z(), std::sqrt(0.5), 1e-12);
}

TEST(Heading, ASlowWalkIsTakenOverAsManyFramesAsItNeeds) {
  // 1 cm per frame: 0.3 m takes 30 frames, more than the 20-frame window.
  TravelDirection travel({.window_frames = 20, .max_window_frames = 90});
  for (int k = 0; k < 25; ++k) travel.Add(Eigen::Vector3d(0, 1.0, 3 - 0.01 * k));
  EXPECT_FALSE(travel.Direction(kUp));  // 0.24 m so far
  for (int k = 25; k < 40; ++k) travel.Add(Eigen::Vector3d(0, 1.0, 3 - 0.01 * k));
  const auto d = travel.Direction(kUp);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->z(), -1, 1e-12);
  // Slower still: 0.3 m would take 100 frames, more than max_window_frames.
  TravelDirection slower({.window_frames = 20, .max_window_frames = 90});
  for (int k = 0; k < 200; ++k) slower.Add(Eigen::Vector3d(0.003 * k, 1.0, 3));
  EXPECT_FALSE(slower.Direction(kUp));
}

TEST(Heading, BadTravelOptionsAreABug) {
  EXPECT_THROW(TravelDirection({.window_frames = 1}), CheckError);
  EXPECT_THROW(TravelDirection({.window_frames = 20, .max_window_frames = 10}), CheckError);
  EXPECT_THROW(TravelDirection({.min_distance_m = 0}), CheckError);
  EXPECT_THROW(TravelDirection({.min_half_share = 0.6}), CheckError);
}

}  // namespace
}  // namespace reenact::capture

// Geodesic extremities of a ray-cast capsule body (ground truth: the posed body's joints) and
// of degenerate regions.
#include "capture-client/tracker/geodesic_extremities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using S = BodySegment;
using tracker_test::FacingSensor;
using tracker_test::LevelFloor;
using tracker_test::RenderBodyPoints;
using tracker_test::Rx;
using tracker_test::Ry;
using tracker_test::Rz;

constexpr double kPi = std::numbers::pi;

// Bounds. An extremity is the surface point geodesically farthest from the torso centre, so it
// lies on the end cap of the limb's last capsule: within the cap's radius of the axis end (the
// hand joint: forearm_radius; the head centre: head_radius), or, for a foot, anywhere on the
// foot capsule (the ankle to foot_length forward, radius foot_radius). A node is the mean of
// the points in its voxel: at most half a voxel diagonal (0.87 voxel_m) further off.
double HandBound(const BodyShape& s, const GeodesicExtremityOptions& o) {
  return s.forearm_radius + 0.87 * o.voxel_m;
}
double HeadBound(const BodyShape& s, const GeodesicExtremityOptions& o) {
  return s.head_radius + 0.87 * o.voxel_m;
}
double FootBound(const BodyShape& s, const GeodesicExtremityOptions& o) {
  return s.foot_length + s.foot_radius + 0.87 * o.voxel_m;
}

// The extremity with `label` nearest to p (nullptr when there is none).
const Extremity* Nearest(const GeodesicExtremities& g, ExtremityLabel label,
                         const Eigen::Vector3d& p) {
  const Extremity* best = nullptr;
  for (const Extremity* e : g.WithLabel(label))
    if (!best || (e->position - p).norm() < (best->position - p).norm()) best = e;
  return best;
}

std::string Describe(const GeodesicExtremities& g) {
  std::ostringstream os;
  os << "\ntorso centre " << g.torso_centre.transpose();
  for (const Extremity& e : g.extremities)
    os << "\n"
       << ExtremityLabelName(e.label) << " at " << e.position.transpose() << " geodesic "
       << e.geodesic_m << " height " << e.height_m;
  return os.str();
}

void ExpectAt(const GeodesicExtremities& g, ExtremityLabel label, const Eigen::Vector3d& truth,
              double bound) {
  const Extremity* e = Nearest(g, label, truth);
  ASSERT_NE(e, nullptr) << ExtremityLabelName(label);
  EXPECT_LT((e->position - truth).norm(), bound) << ExtremityLabelName(label) << Describe(g);
}

TEST(GeodesicExtremities, TPoseGivesHeadHandsAndFeet) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  ArticulatedPose pose = FacingSensor(body);
  pose.local[static_cast<int>(S::kLeftUpperArm)] = Rx(kPi / 2);    // arm along body +y (left)
  pose.local[static_cast<int>(S::kRightUpperArm)] = Rx(-kPi / 2);  // along -y
  const Skeleton truth = body.Pose(pose).skeleton;
  const GeodesicExtremityOptions options;
  const GeodesicExtremities g = FindGeodesicExtremities(RenderBodyPoints(body, pose), LevelFloor());
  ASSERT_TRUE(g.valid);
  EXPECT_EQ(g.reachable, g.nodes);  // one connected surface
  EXPECT_EQ(g.extremities.size(), 5u) << Describe(g);
  EXPECT_EQ(g.WithLabel(ExtremityLabel::kHead).size(), 1u);
  EXPECT_EQ(g.WithLabel(ExtremityLabel::kHand).size(), 2u);
  EXPECT_EQ(g.WithLabel(ExtremityLabel::kFoot).size(), 2u);
  const BodyShape& s = body.shape();
  ExpectAt(g, ExtremityLabel::kHead, truth[Joint::kHead], HeadBound(s, options));
  ExpectAt(g, ExtremityLabel::kHand, truth[Joint::kLeftHand], HandBound(s, options));
  ExpectAt(g, ExtremityLabel::kHand, truth[Joint::kRightHand], HandBound(s, options));
  ExpectAt(g, ExtremityLabel::kFoot, truth[Joint::kLeftFoot], FootBound(s, options));
  ExpectAt(g, ExtremityLabel::kFoot, truth[Joint::kRightFoot], FootBound(s, options));
  // An outstretched hand is farther along the surface than the head.
  EXPECT_GT(g.WithLabel(ExtremityLabel::kHand).back()->geodesic_m,
            g.WithLabel(ExtremityLabel::kHead)[0]->geodesic_m);
}

TEST(GeodesicExtremities, OneArmRaisedIsAHandAboveTheHead) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  ArticulatedPose pose = FacingSensor(body);
  pose.local[static_cast<int>(S::kRightUpperArm)] = Rx(-0.95 * kPi);  // up, 9 degrees out
  // The other arm 30 degrees out (hanging straight, the capsule body's hand lies in its
  // thigh's surface and is no extremity of the surface).
  pose.local[static_cast<int>(S::kLeftUpperArm)] = Rx(kPi / 6);
  const Skeleton truth = body.Pose(pose).skeleton;
  ASSERT_GT(truth[Joint::kRightHand].y(), truth[Joint::kHead].y() - 1.0);  // sanity of setup
  ASSERT_LT(truth[Joint::kRightHand].y(), truth[Joint::kHead].y() - 0.3);  // above the head
  const GeodesicExtremityOptions options;
  const GeodesicExtremities g = FindGeodesicExtremities(RenderBodyPoints(body, pose), LevelFloor());
  ASSERT_TRUE(g.valid);
  const BodyShape& s = body.shape();
  ExpectAt(g, ExtremityLabel::kHead, truth[Joint::kHead], HeadBound(s, options));
  ExpectAt(g, ExtremityLabel::kHand, truth[Joint::kRightHand], HandBound(s, options));
  ExpectAt(g, ExtremityLabel::kHand, truth[Joint::kLeftHand], HandBound(s, options));
  ExpectAt(g, ExtremityLabel::kFoot, truth[Joint::kLeftFoot], FootBound(s, options));
  ExpectAt(g, ExtremityLabel::kFoot, truth[Joint::kRightFoot], FootBound(s, options));
}

TEST(GeodesicExtremities, AnArmInFrontOfTheTorsoStaysSeparatedFromIt) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  ArticulatedPose pose = FacingSensor(body);
  // Left upper arm swung 60 degrees forward and turned inwards, the elbow bent 90 degrees: the
  // forearm lies across the belly in front of it, its image inside the torso's.
  pose.local[static_cast<int>(S::kLeftUpperArm)] = Ry(-kPi / 3) * Rz(-kPi / 2);
  pose.hinge_angle[static_cast<int>(S::kLeftForearm)] = kPi / 2;
  const PosedBody3 posed = body.Pose(pose);
  const Skeleton& truth = posed.skeleton;
  const Eigen::Vector3d elbow = truth[Joint::kLeftElbow], hand = truth[Joint::kLeftHand];
  // Set-up: the hand lies in front of the torso (towards the sensor, -z) and inside its width.
  ASSERT_LT(hand.z(), truth[Joint::kTorso].z() - 0.15);
  ASSERT_LT(std::abs(hand.x() - truth[Joint::kTorso].x()), 0.15);
  ASSERT_LT((hand - elbow).normalized().dot(Eigen::Vector3d::UnitX()), -0.7);  // across
  const GeodesicExtremityOptions options;
  const GeodesicExtremities g = FindGeodesicExtremities(RenderBodyPoints(body, pose), LevelFloor());
  ASSERT_TRUE(g.valid);
  const Extremity* e = Nearest(g, ExtremityLabel::kHand, hand);
  ASSERT_NE(e, nullptr);
  EXPECT_LT((e->position - hand).norm(), HandBound(body.shape(), options));
  // Separated: the path to the hand runs over the shoulder and down the arm, at least the
  // upper arm and forearm long, while straight through the gap the torso centre is within
  // 0.5 m of the hand.
  ASSERT_LT((g.torso_centre - hand).norm(), 0.5);
  EXPECT_GT(e->geodesic_m, body.shape().upper_arm + body.shape().forearm);
}

TEST(GeodesicExtremities, EmptyRegionIsInvalid) {
  const GeodesicExtremities g = FindGeodesicExtremities({}, LevelFloor());
  EXPECT_FALSE(g.valid);
  EXPECT_EQ(g.nodes, 0);
  EXPECT_TRUE(g.extremities.empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const GeodesicExtremities h = FindGeodesicExtremities(
      {Eigen::Vector3d(nan, 0, 3), Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 3)},
      LevelFloor());
  EXPECT_FALSE(h.valid);
}

TEST(GeodesicExtremities, OnePointHasNoExtremity) {
  const GeodesicExtremities g = FindGeodesicExtremities({Eigen::Vector3d(0, 0, 3)}, std::nullopt);
  EXPECT_TRUE(g.valid);
  EXPECT_EQ(g.nodes, 1);
  EXPECT_EQ(g.reachable, 1);
  EXPECT_TRUE(g.torso_centre.isApprox(Eigen::Vector3d(0, 0, 3)));
  EXPECT_TRUE(g.extremities.empty());  // shorter than min_length_m
}

TEST(GeodesicExtremities, FlatDiscGivesSeparatedPointsOnItsRim) {
  // A disc of radius 0.4 m facing the sensor at 3 m, sampled every 1 cm: its centre is the
  // torso centre, every rim point a geodesic maximum at 0.4 m, none prominent against another
  // (the rim varies by the sampling only): the farthest alone, or a few, each on the rim.
  std::vector<Eigen::Vector3d> points;
  const double radius = 0.4;
  for (double x = -radius; x <= radius; x += 0.01)
    for (double y = -radius; y <= radius; y += 0.01)
      if (x * x + y * y <= radius * radius) points.emplace_back(x, y, 3);
  const GeodesicExtremityOptions options;
  const GeodesicExtremities g = FindGeodesicExtremities(points, std::nullopt, options);
  ASSERT_TRUE(g.valid);
  EXPECT_LT((g.torso_centre - Eigen::Vector3d(0, 0, 3)).norm(), options.voxel_m);
  ASSERT_GE(g.extremities.size(), 1u);
  EXPECT_LE(static_cast<int>(g.extremities.size()), options.max_extremities);
  for (size_t i = 0; i < g.extremities.size(); ++i) {
    const Extremity& e = g.extremities[i];
    EXPECT_TRUE(e.position.allFinite());
    // On the rim: within a voxel of the radius, in 3D and along the surface.
    EXPECT_NEAR((e.position - Eigen::Vector3d(0, 0, 3)).norm(), radius, options.voxel_m);
    EXPECT_NEAR(e.geodesic_m, radius, 2 * options.voxel_m);
    // Separated (the disc is flat and convex: geodesic = Euclidean, up to the graph's detours).
    for (size_t j = 0; j < i; ++j)
      EXPECT_GE((e.position - g.extremities[j].position).norm(), 0.8 * options.min_separation_m);
  }
}

TEST(GeodesicExtremities, BadOptionsAreABug) {
  GeodesicExtremityOptions o;
  o.neighbour_m = o.voxel_m;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.max_extremities = 0;
  EXPECT_THROW(FindGeodesicExtremities({}, std::nullopt, o), CheckError);
}

}  // namespace
}  // namespace reenact::capture

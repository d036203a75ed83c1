// The trunk's depth from side views (torso_depth.h) on ray-cast bodies of known shape: a trunk
// deeper than the tracked body's, seen side-on, turned and facing; the breadth kept when the
// depth is set; the collector's rule; and degenerate views. The trunk's breadth from the
// calibration pose's facing view, and the depth kept when the breadth is set.
#include "capture-client/tracker/torso_depth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "capture-client/tracker/heading.h"
#include "common/error/check.h"
#include "common/skeleton/skeleton.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using tracker_test::SceneBlob;
using tracker_test::SceneCapsule;

const PinholeCamera kCamera = PinholeCamera::KinectLike();
const Eigen::Vector3d kUp(0, -1, 0);

// The truth: a 1.75 m body whose trunk is 20 cm deep (radius 0.1) and 32 cm broad (spread
// 0.06). The tracked body has the same bones and breadth but a trunk 14 cm deep, as a front
// view's calibration fits it.
BodyShape TrueShape() {
  BodyShape s = BodyShape::FromHeight(1.75);
  s.torso_radius = 0.1;
  s.torso_half_spread = 0.06;
  return s;
}
BodyShape ShallowShape() {
  BodyShape s = TrueShape();
  s.torso_radius = 0.07;
  s.torso_half_spread = 0.09;
  return s;
}

// Standing at depth 3 m on the floor point x, facing `forward`, arms held out sideways (off the
// trunk's silhouette from every side).
ArticulatedPose Standing(const ArticulatedBody& body, const Eigen::Vector3d& forward,
                         double x = 0) {
  ArticulatedPose pose = UprightPose(body, tracker_test::AboveFloor(x, 0, 3), kUp, forward);
  pose.local[static_cast<int>(BodySegment::kLeftUpperArm)] = tracker_test::Rx(std::numbers::pi / 2);
  pose.local[static_cast<int>(BodySegment::kRightUpperArm)] =
      tracker_test::Rx(-std::numbers::pi / 2);
  return pose;
}

// The posed body's capsules as a ray-cast figure.
std::vector<SceneCapsule> Figure(const ArticulatedBody& body, const ArticulatedPose& pose) {
  const PosedBody3 posed = body.Pose(pose);
  std::vector<SceneCapsule> figure;
  for (const BodyCapsule& c : body.capsules()) {
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    figure.push_back({t * c.a, t * c.b, c.radius});
  }
  return figure;
}

// The widths the shallow body measures, posed as the truth, with the truth turned `turn_deg`
// from side-on to its line of sight towards the sensor (0: facing the sensor's right, across
// the line of sight; 90: facing the sensor).
std::vector<TrunkWidth> WidthsAt(double turn_deg, double x = 0) {
  const TorsoDepthOptions every_view{.max_side_deg = 90};
  const double a = turn_deg * std::numbers::pi / 180;
  const Eigen::Vector3d away = Eigen::Vector3d(x, 0, 3).normalized();  // horizontal sight
  const Eigen::Vector3d side(away.z(), 0, -away.x());
  const Eigen::Vector3d forward = std::cos(a) * side - std::sin(a) * away;
  const ArticulatedBody truth(TrueShape()), tracked(ShallowShape());
  const ArticulatedPose pose = Standing(truth, forward, x);
  return MeasureTrunkWidths(tracked, tracked.Pose(pose), SceneBlob(Figure(truth, pose)), kCamera,
                            every_view);
}

const TrunkWidth* Find(const std::vector<TrunkWidth>& widths, BodySegment s) {
  for (const TrunkWidth& w : widths)
    if (w.segment == s) return &w;
  return nullptr;
}

// Bound for one segment's half width: the points sample the silhouette on a 2 px grid, 1.2 cm
// at 3 m, so a slice's extent plus one grid step is within a grid step of the true width,
// within half of it in w; the median over the slices does not add to that.
constexpr double kGridBound = 0.006;

TEST(TorsoDepth, ASideViewShowsTheTrunksDepth) {
  const auto widths = WidthsAt(0);
  for (const BodySegment s :
       {BodySegment::kPelvis, BodySegment::kLowerSpine, BodySegment::kChest}) {
    const TrunkWidth* w = Find(widths, s);
    ASSERT_NE(w, nullptr) << static_cast<int>(s);
    EXPECT_NEAR(w->half_width_m, 0.1, kGridBound) << static_cast<int>(s);
    EXPECT_LT(w->sin_from_side, 1e-6);
  }
}

TEST(TorsoDepth, TurnedViewsShowTheStadiumsWidthAcrossTheLineOfSight) {
  // w = r + s |sin theta| (torso_depth.h): 0.1 + 0.06 sin 40 degrees, and the breadth 0.16
  // facing the sensor. The abdomen only: no arm or leg reaches its heights.
  for (const double turn : {40.0, 90.0}) {
    const auto widths = WidthsAt(turn);
    const TrunkWidth* w = Find(widths, BodySegment::kLowerSpine);
    ASSERT_NE(w, nullptr) << turn;
    const double sin_turn = std::sin(turn * std::numbers::pi / 180);
    EXPECT_NEAR(w->sin_from_side, sin_turn, 1e-6) << turn;
    EXPECT_NEAR(w->half_width_m, 0.1 + 0.06 * sin_turn, kGridBound) << turn;
  }
}

TEST(TorsoDepth, AnEdgeHiddenByANearerPartIsNotMeasured) {
  // Side-on, an upper-arm-sized capsule (radius 5 cm) 30 cm in front of the trunk (nearer the
  // sensor) hides its front edge from the waist to the torso joint: there the trunk's points
  // end at the occluder's edge, 5 cm short of the trunk's, and the abdomen would read 2-3 cm
  // narrow. Those slices are left out: the abdomen gives no width, or from slices at its ends
  // the true one, and the chest, whose edges are free, reads its depth as before.
  const ArticulatedBody truth(TrueShape()), tracked(ShallowShape());
  const ArticulatedPose pose = Standing(truth, Eigen::Vector3d(1, 0, 0));
  const PosedBody3 posed = truth.Pose(pose);
  const Eigen::Vector3d waist = posed.skeleton.position[static_cast<int>(Joint::kWaist)];
  const Eigen::Vector3d torso = posed.skeleton.position[static_cast<int>(Joint::kTorso)];
  std::vector<SceneCapsule> figure = Figure(truth, pose);
  const Eigen::Vector3d front(0.1, 0, -0.3);  // the front edge, 30 cm nearer
  const Eigen::Vector3d cap = 0.05 * kUp;
  figure.push_back({waist + front + cap, torso + front - cap, 0.05});
  const auto widths = MeasureTrunkWidths(tracked, tracked.Pose(pose), SceneBlob(figure), kCamera);
  if (const TrunkWidth* abdomen = Find(widths, BodySegment::kLowerSpine)) {
    EXPECT_NEAR(abdomen->half_width_m, 0.1, kGridBound);
  }
  const TrunkWidth* chest = Find(widths, BodySegment::kChest);
  ASSERT_NE(chest, nullptr);
  EXPECT_NEAR(chest->half_width_m, 0.1, kGridBound);
}

TEST(TorsoDepth, ATrunkCutByTheImagesEdgeGivesNoWidth) {
  // Side-on at x = -1.85 m, 3 m away: the image's left edge (x = -1.85 m at that depth) runs
  // through the trunk.
  const auto widths = WidthsAt(0, -1.85);
  EXPECT_EQ(Find(widths, BodySegment::kLowerSpine), nullptr);
  EXPECT_EQ(Find(widths, BodySegment::kPelvis), nullptr);
  // Fully inside, 1.2 m to the left and side-on to its line of sight, it is measured as in
  // the middle.
  const TrunkWidth* inside = Find(WidthsAt(0, -1.2), BodySegment::kLowerSpine);
  ASSERT_NE(inside, nullptr);
  EXPECT_NEAR(inside->half_width_m, 0.1, kGridBound);
}

TEST(TorsoDepth, DegenerateViewsGiveNoWidthAndNoNan) {
  const ArticulatedBody body(TrueShape());
  const ArticulatedPose side = Standing(body, Eigen::Vector3d(1, 0, 0));
  const PersonBlob blob = SceneBlob(Figure(body, side));
  EXPECT_TRUE(MeasureTrunkWidths(body, body.Pose(side), PersonBlob{}, kCamera).empty());
  PersonBlob no_person = blob;
  no_person.status = DetectStatus::kNoPerson;
  EXPECT_TRUE(MeasureTrunkWidths(body, body.Pose(side), no_person, kCamera).empty());
  // A model posed far from the points owns none of them.
  ArticulatedPose away = side;
  away.root_translation.x() += 2;
  EXPECT_TRUE(MeasureTrunkWidths(body, body.Pose(away), blob, kCamera).empty());
  // The trunk lying along the line of sight (its up the sensor's z): seen along its axis.
  ArticulatedPose along = side;
  along.root_rotation.col(0) = Eigen::Vector3d(1, 0, 0);
  along.root_rotation.col(1) = Eigen::Vector3d(0, 1, 0);
  along.root_rotation.col(2) = Eigen::Vector3d(0, 0, 1);
  along.root_translation = Eigen::Vector3d(0, 0, 2);
  for (const TrunkWidth& w :
       MeasureTrunkWidths(body, body.Pose(along), SceneBlob(Figure(body, along)), kCamera))
    ADD_FAILURE() << "segment " << static_cast<int>(w.segment) << " measured along its axis";
  // Behind the sensor.
  ArticulatedPose behind = side;
  behind.root_translation.z() = -3;
  EXPECT_TRUE(MeasureTrunkWidths(body, body.Pose(behind), blob, kCamera).empty());
  EXPECT_THROW(MeasureTrunkWidths(body, body.Pose(side), blob, kCamera, {.slice_m = 0}),
               CheckError);
}

// Nothing but the trunk's cross-section differs between a shape and one built from it: the
// bones and the other radii.
void ExpectOnlyTheTrunkChanged(const BodyShape& changed, const BodyShape& original) {
  BodyShape back = changed;
  back.torso_radius = original.torso_radius;
  back.torso_half_spread = original.torso_half_spread;
  EXPECT_EQ(back.PartLengths(), original.PartLengths());
  EXPECT_EQ(back.PartRadii(), original.PartRadii());
}

TEST(TorsoDepth, SettingTheDepthKeepsTheBreadth) {
  const BodyShape shallow = ShallowShape();
  const BodyShape deep = WithTorsoDepth(shallow, 0.1);
  EXPECT_DOUBLE_EQ(deep.torso_radius, 0.1);
  EXPECT_NEAR(deep.torso_half_spread, 0.06, 1e-12);
  ExpectOnlyTheTrunkChanged(deep, shallow);
  // Deeper than broad: one round capsule; shallower than min_depth_ratio: kept at it.
  EXPECT_DOUBLE_EQ(WithTorsoDepth(shallow, 0.3).torso_radius, 0.16);
  EXPECT_DOUBLE_EQ(WithTorsoDepth(shallow, 0.3).torso_half_spread, 0.0);
  EXPECT_NEAR(WithTorsoDepth(shallow, 0.01, 0.5).torso_radius, 0.08, 1e-12);
  EXPECT_THROW(WithTorsoDepth(shallow, 0.0), CheckError);
  EXPECT_THROW(WithTorsoDepth(shallow, std::nan("")), CheckError);
  EXPECT_THROW(WithTorsoDepth(shallow, 0.1, 0.0), CheckError);
}

TEST(TorsoDepth, OnlyViewsNearSideOnAreMeasured) {
  // By default within 30 degrees of side-on: 20 degrees is measured, 40 and facing are not.
  const ArticulatedBody truth(TrueShape()), tracked(ShallowShape());
  for (const double turn : {20.0, 40.0, 90.0}) {
    const double a = turn * std::numbers::pi / 180;
    const ArticulatedPose pose = Standing(truth, Eigen::Vector3d(std::cos(a), 0, -std::sin(a)));
    const auto widths =
        MeasureTrunkWidths(tracked, tracked.Pose(pose), SceneBlob(Figure(truth, pose)), kCamera);
    EXPECT_EQ(Find(widths, BodySegment::kLowerSpine) != nullptr, turn < 30) << turn;
  }
}

// A tracked body whose trunk is broader than the truth's (36 cm against 32: the spread 0.08
// against 0.06, as average proportions made CesiumMan's), same bones and depth.
BodyShape BroadShape() {
  BodyShape s = TrueShape();
  s.torso_half_spread = 0.08;
  return s;
}

// The breadth the broad body measures, posed as the truth turned turn_deg from side-on.
std::optional<double> BreadthAt(double turn_deg, double max_facing_deg = 30) {
  const double a = turn_deg * std::numbers::pi / 180;
  const ArticulatedBody truth(TrueShape()), tracked(BroadShape());
  const ArticulatedPose pose = Standing(truth, Eigen::Vector3d(std::cos(a), 0, -std::sin(a)));
  return MeasureTrunkBreadth(tracked, tracked.Pose(pose), SceneBlob(Figure(truth, pose)), kCamera,
                             max_facing_deg);
}

TEST(TorsoDepth, AFacingViewShowsTheAbdomensBreadth) {
  // Facing the sensor, arms held out: the abdomen's silhouette is the truth's breadth, half
  // of it r + s = 0.16 (w at |sin theta| = 1), within the grid's bound.
  const auto facing = BreadthAt(90);
  ASSERT_TRUE(facing);
  EXPECT_NEAR(*facing, 0.16, kGridBound);
  // 25 degrees off facing is still within the default 30: w = r + s sin 65 degrees.
  const auto turned = BreadthAt(65);
  ASSERT_TRUE(turned);
  EXPECT_NEAR(*turned, 0.1 + 0.06 * std::sin(65 * std::numbers::pi / 180), kGridBound);
  // Side-on, or 50 degrees off facing, the silhouette does not show the breadth: nothing.
  EXPECT_FALSE(BreadthAt(0));
  EXPECT_FALSE(BreadthAt(40));
  // max_facing_deg 0 takes the facing view only.
  EXPECT_TRUE(BreadthAt(90, 0));
  EXPECT_FALSE(BreadthAt(65, 0));
  EXPECT_THROW(BreadthAt(90, 91), CheckError);
  EXPECT_THROW(BreadthAt(90, -1), CheckError);
}

TEST(TorsoDepth, DegenerateViewsGiveNoBreadth) {
  const ArticulatedBody body(TrueShape());
  const ArticulatedPose facing = Standing(body, Eigen::Vector3d(0, 0, -1));
  EXPECT_FALSE(MeasureTrunkBreadth(body, body.Pose(facing), PersonBlob{}, kCamera));
  // A model posed beside the points owns none of them.
  ArticulatedPose away = facing;
  away.root_translation.x() += 2;
  EXPECT_FALSE(
      MeasureTrunkBreadth(body, body.Pose(away), SceneBlob(Figure(body, facing)), kCamera));
}

TEST(TorsoDepth, SettingTheBreadthKeepsTheDepth) {
  const BodyShape broad = BroadShape();
  const BodyShape narrower = WithTorsoBreadth(broad, 0.16);
  EXPECT_DOUBLE_EQ(narrower.torso_radius, 0.1);
  EXPECT_NEAR(narrower.torso_half_spread, 0.06, 1e-12);
  ExpectOnlyTheTrunkChanged(narrower, broad);
  // Narrower than deep: one round capsule of that breadth.
  EXPECT_DOUBLE_EQ(WithTorsoBreadth(broad, 0.07).torso_radius, 0.07);
  EXPECT_DOUBLE_EQ(WithTorsoBreadth(broad, 0.07).torso_half_spread, 0.0);
  EXPECT_THROW(WithTorsoBreadth(broad, 0.0), CheckError);
  EXPECT_THROW(WithTorsoBreadth(broad, std::nan("")), CheckError);
}

TEST(TorsoDepth, TheCollectorGivesTheQuantileOfSideViewsOnce) {
  TorsoDepthCollector collector({.side_frames = 3, .quantile = 0.5});
  const auto side = [](double w) {
    return std::vector<TrunkWidth>{{.half_width_m = w, .sin_from_side = 0.1}};
  };
  EXPECT_FALSE(collector.Add({}));  // no side view: not counted
  EXPECT_FALSE(collector.Add(side(std::nan(""))));
  EXPECT_FALSE(collector.Add(side(-0.1)));
  EXPECT_FALSE(collector.Add(side(0.10)));
  EXPECT_FALSE(collector.Add(side(0.12)));
  const auto depth = collector.Add(side(0.09));
  ASSERT_TRUE(depth);
  EXPECT_DOUBLE_EQ(*depth, 0.10);
  EXPECT_TRUE(collector.done());
  EXPECT_FALSE(collector.Add(side(0.2)));
  collector.Clear();
  EXPECT_FALSE(collector.done());
  // By default the lower quartile (nearest rank: the 1st of 4).
  TorsoDepthCollector quartile({.side_frames = 4});
  for (const double w : {0.12, 0.10, 0.13}) EXPECT_FALSE(quartile.Add(side(w)));
  EXPECT_DOUBLE_EQ(quartile.Add(side(0.11)).value_or(0), 0.10);
  EXPECT_THROW(TorsoDepthCollector({.side_frames = 0}), CheckError);
  EXPECT_THROW(TorsoDepthCollector({.max_side_deg = 91}), CheckError);
  EXPECT_THROW(TorsoDepthCollector({.quantile = 1.5}), CheckError);
}

}  // namespace
}  // namespace reenact::capture

// Virtual views of the static background, checked against the synthetic scene rendered from
// the same virtual pose: the truth by construction.
#include "capture-client/map/virtual_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const SyntheticScene& Scene() {
  static const SyntheticScene scene = [] {
    auto s = SyntheticScene::Create("turn-and-kick");
    REENACT_CHECK(s.ok(), "scene");
    return std::move(*s);
  }();
  return scene;
}

Eigen::Vector3d Pivot() { return Scene().skeleton_in_world(0)[Joint::kWaist]; }

TEST(VirtualViews, TurnKeepsThePivotDistanceHeightAndAim) {
  const Eigen::Isometry3d sensor = Scene().world_from_sensor(0);
  const Eigen::Vector3d up = Scene().world_up();
  for (double yaw : {-40.0, 20.0, 90.0}) {
    const Eigen::Isometry3d turned = TurnAboutVertical(sensor, Pivot(), up, yaw);
    EXPECT_NEAR((turned.translation() - Pivot()).norm(), (sensor.translation() - Pivot()).norm(),
                1e-9);
    EXPECT_NEAR(turned.translation().dot(up), sensor.translation().dot(up), 1e-9);
    // The pivot has the same coordinates in the turned camera as in the sensor.
    EXPECT_LT((turned.inverse() * Pivot() - sensor.inverse() * Pivot()).norm(), 1e-9);
    // The horizontal direction to the camera turned by yaw about up.
    const auto horizontal = [&](const Eigen::Vector3d& v) { return v - v.dot(up) * up; };
    const Eigen::Vector3d a = horizontal(sensor.translation() - Pivot()).normalized();
    const Eigen::Vector3d b = horizontal(turned.translation() - Pivot()).normalized();
    const double angle = std::atan2(a.cross(b).dot(up), a.dot(b)) * 180 / std::numbers::pi;
    EXPECT_NEAR(angle, yaw, 1e-9);
  }
  // No up direction: nothing to turn about.
  const Eigen::Isometry3d same = TurnAboutVertical(sensor, Pivot(), Eigen::Vector3d::Zero(), 30);
  EXPECT_TRUE(same.isApprox(sensor));
}

TEST(VirtualViews, RenderedViewAgreesWithTheSceneSeenFromThere) {
  // The empty room from the sensor, rendered into a view turned 20 degrees, against the
  // scene's own rendering from that pose. Pixels the sensor never saw stay holes; where both
  // have depth, depth agrees to within the forward projection's rounding (a pixel's depth
  // taken from a neighbouring ray: 1 cm at 4 m on a 60-degree slant) and colour to within
  // the resampling blur of the room's texture.
  SyntheticRenderOptions empty;
  empty.draw_subject = false;
  const SyntheticView sensor =
      Scene().Render(0, Scene().sensor_camera(), Scene().world_from_sensor(0), empty);
  const Eigen::Isometry3d turned =
      TurnAboutVertical(Scene().world_from_sensor(0), Pivot(), Scene().world_up(), 20);
  const SyntheticView truth = Scene().Render(0, Scene().sensor_camera(), turned, empty);
  VirtualViewOptions options;
  const VirtualView view =
      RenderVirtualView(sensor.color, sensor.depth, 0.001, ImageGray8(), Scene().sensor_camera(),
                        Scene().world_from_sensor(0), turned, options);
  ASSERT_EQ(view.depth.width, truth.depth.width);
  std::vector<double> depth_error, colour_error;
  int valid = 0;
  for (int y = 0; y < truth.depth.height; ++y) {
    for (int x = 0; x < truth.depth.width; ++x) {
      if (view.depth.at(x, y) == 0) continue;
      ++valid;
      if (truth.depth.at(x, y) == 0) continue;
      depth_error.push_back(std::abs(view.depth.at(x, y) - truth.depth.at(x, y)) * 0.001);
      for (int c = 0; c < 3; ++c)
        colour_error.push_back(std::abs(view.color.at(x, y, c) - truth.color.at(x, y, c)));
    }
  }
  const double pixels = truth.depth.width * truth.depth.height;
  EXPECT_GT(valid / pixels, 0.7);  // a 20-degree turn hides little of a room
  std::sort(depth_error.begin(), depth_error.end());
  EXPECT_LT(depth_error[depth_error.size() / 2], 0.01);
  EXPECT_LT(depth_error[depth_error.size() * 9 / 10], 0.03);
  double mean = 0;
  for (double e : colour_error) mean += e;
  mean /= static_cast<double>(colour_error.size());
  EXPECT_LT(mean, 20.0);
}

TEST(VirtualViews, FeaturesLieOnTheRoomAndNeverOnTheSubject) {
  // From a frame with the subject in view and its mask: every virtual feature's point must
  // be on a room surface (its depth in the true empty-room rendering from the same virtual
  // pose agrees), so neither the subject nor hole borders become map points.
  const SyntheticView sensor = Scene().RenderSensor(0);
  VirtualViewOptions options;
  options.yaw_deg = {-30, 30};
  SyntheticRenderOptions empty;
  empty.draw_subject = false;
  const std::vector<VirtualMapPoint> points =
      VirtualViewFeatures(sensor.color, sensor.depth, 0.001, sensor.mask, Scene().sensor_camera(),
                          Scene().world_from_sensor(0), Pivot(), Scene().world_up(), options);
  ASSERT_GT(points.size(), 300u);
  const SyntheticView room =
      Scene().Render(0, Scene().sensor_camera(), Scene().world_from_sensor(0), empty);
  int on_room = 0, seen = 0;
  for (const VirtualMapPoint& p : points) {
    // Checked from the sensor, which saw every point the virtual views were made from.
    const Eigen::Vector3d c = Scene().world_from_sensor(0).inverse() * p.position_in_world;
    const auto px = Scene().sensor_camera().Project(c);
    ASSERT_TRUE(px.has_value());
    const int u = static_cast<int>(std::lround(px->x())),
              v = static_cast<int>(std::lround(px->y()));
    if (!room.depth.Contains(u, v) || room.depth.at(u, v) == 0) continue;
    ++seen;
    on_room += std::abs(c.z() - room.depth.at(u, v) * 0.001) < 0.03 + 0.01 * c.z();
  }
  EXPECT_GT(seen, static_cast<int>(points.size() * 9 / 10));
  EXPECT_GT(on_room, seen * 95 / 100);
}

TEST(VirtualViews, AddedToAMapTheyMergeAndCount) {
  const SyntheticView sensor = Scene().RenderSensor(0);
  VirtualViewOptions options;
  options.yaw_deg = {25};
  const std::vector<VirtualViewKeyframe> keyframes = {
      {sensor.color, sensor.depth, sensor.mask, Scene().world_from_sensor(0), Pivot()}};
  size_t added = 0;
  const proto::ClipMap once = AddVirtualViews({}, keyframes, 0.001, Scene().sensor_camera(),
                                              Scene().world_up(), options, {}, &added);
  EXPECT_EQ(once.points.size(), added);
  EXPECT_GT(added, 100u);
  // The same keyframe again: its features are observations of the points already there.
  size_t again = 0;
  const proto::ClipMap twice = AddVirtualViews(once, keyframes, 0.001, Scene().sensor_camera(),
                                               Scene().world_up(), options, {}, &again);
  EXPECT_EQ(again, 0u);
  EXPECT_EQ(twice.points.size(), once.points.size());
  // No keyframes, or no yaw: the map unchanged.
  EXPECT_EQ(AddVirtualViews(once, {}, 0.001, Scene().sensor_camera(), Scene().world_up(), options,
                            {}, &again)
                .points.size(),
            once.points.size());
  options.yaw_deg.clear();
  EXPECT_EQ(AddVirtualViews(once, keyframes, 0.001, Scene().sensor_camera(), Scene().world_up(),
                            options, {}, &again)
                .points.size(),
            once.points.size());
  EXPECT_EQ(again, 0u);
}

TEST(VirtualViews, PivotFallsBackFromWaistToTorsoToTheJointsPresent) {
  Skeleton s;
  EXPECT_FALSE(SubjectPivot(s, Eigen::Isometry3d::Identity()).has_value());
  s[Joint::kHead] = {0, 0, 2};
  s.confidence[Index(Joint::kHead)] = 1;
  s[Joint::kLeftFoot] = {0, 2, 2};
  s.confidence[Index(Joint::kLeftFoot)] = 1;
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
  world_from_sensor.translation() = Eigen::Vector3d(1, 0, 0);
  EXPECT_TRUE(SubjectPivot(s, world_from_sensor)->isApprox(Eigen::Vector3d(1, 1, 2)));
  s[Joint::kTorso] = {0, 0.5, 2};
  s.confidence[Index(Joint::kTorso)] = 1;
  EXPECT_TRUE(SubjectPivot(s, world_from_sensor)->isApprox(Eigen::Vector3d(1, 0.5, 2)));
  s[Joint::kWaist] = {0, 0.8, 2};
  s.confidence[Index(Joint::kWaist)] = 1;
  EXPECT_TRUE(SubjectPivot(s, world_from_sensor)->isApprox(Eigen::Vector3d(1, 0.8, 2)));
}

TEST(VirtualViews, BadOptionsAndInputsAreBugs) {
  VirtualViewOptions o;
  o.yaw_deg = {0};
  EXPECT_THROW(o.Check(), CheckError);
  o.yaw_deg = {120};
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.keyframe_interval = 0;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  const SyntheticView sensor = Scene().RenderSensor(0);
  const ImageDepthMm small(10, 10, 1, 1000);
  EXPECT_THROW(RenderVirtualView(sensor.color, small, 0.001, ImageGray8(), Scene().sensor_camera(),
                                 Scene().world_from_sensor(0), Scene().world_from_sensor(0), o),
               CheckError);
  // All-zero depth: an empty view, no features.
  const ImageDepthMm none(sensor.depth.width, sensor.depth.height, 1, 0);
  EXPECT_TRUE(VirtualViewFeatures(sensor.color, none, 0.001, sensor.mask, Scene().sensor_camera(),
                                  Scene().world_from_sensor(0), Pivot(), Scene().world_up(), o)
                  .empty());
}

}  // namespace
}  // namespace reenact::capture

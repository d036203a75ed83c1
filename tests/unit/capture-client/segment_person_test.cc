// Person segmentation on the synthetic scene's sensor frames against its ground-truth mask
// (issue 5: IoU >= 0.9 on turn-and-kick), with and without Kinect-like depth noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "capture-client/segment/mask_overlap.h"
#include "capture-client/segment/person_segmenter.h"
#include "synthetic/room.h"
#include "synthetic/scenario.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const SyntheticScene& Scene() {
  static const SyntheticScene scene = SyntheticScene::Create("turn-and-kick", 1).value();
  return scene;
}

Skeleton SensorSkeleton(const SyntheticScene& scene, int frame) {
  return scene.skeleton_in_world(frame).Transformed(scene.world_from_sensor(frame).inverse());
}

SegmentFrameGeometry Geometry(const SyntheticScene& scene, int frame) {
  return {scene.world_from_sensor(frame), scene.world_up()};
}

// Calibration pose, arms down, turning (facing the sensor, sideways, back), the kick's
// peak (frame 135: right foot 0.74 m up) and its start, the raised arm.
constexpr int kFrames[] = {0, 30, 60, 75, 90, 105, 128, 135, 140, 165};

class SegmentTurnAndKick : public ::testing::TestWithParam<bool> {};

TEST_P(SegmentTurnAndKick, IouAtLeast0p9OnEveryFrameIncludingTheKick) {
  const SyntheticScene& scene = Scene();
  ASSERT_GT(scene.skeleton_in_world(135)[Joint::kRightFoot].z(), 0.5);  // the kick is in
  SyntheticRenderOptions render;
  render.depth_noise = GetParam();
  PersonSegmenter segmenter(scene.sensor_camera(), 0.001);
  for (int frame : kFrames) {
    const SyntheticView view = scene.RenderSensor(frame, render);
    const auto result =
        segmenter.Segment(view.depth, SensorSkeleton(scene, frame), Geometry(scene, frame));
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->status, SegmentStatus::kOk);
    const MaskOverlap overlap = CompareMasks(result->mask, view.mask);
    EXPECT_GE(overlap.iou, 0.9) << "frame " << frame;
    EXPECT_EQ(result->mask_pixels,
              std::count(result->mask.data.begin(), result->mask.data.end(), 255));
  }
}

INSTANTIATE_TEST_SUITE_P(Noise, SegmentTurnAndKick, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "NoiseOn" : "NoiseOff"; });

// Where each wrongly included pixel lies in the room (from the noise-free depth of the same
// frame): floor (world z below 2 cm), furniture (inside a box grown by 2 cm), else wall; and
// how many floor pixels lie under the feet (within 0.3 m of a foot joint across the floor).
struct FalsePositives {
  int floor = 0, furniture = 0, wall = 0;
  int floor_under_feet = 0;
};

FalsePositives Classify(const SyntheticScene& scene, int frame, const ImageGray8& mask,
                        const SyntheticView& clean) {
  const auto room = SharedRoom();
  const PinholeCamera& camera = scene.sensor_camera();
  const Eigen::Isometry3d world_from_sensor = scene.world_from_sensor(frame);
  const Skeleton skeleton = scene.skeleton_in_world(frame);
  FalsePositives out;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      if (clean.mask.at(x, y) || clean.depth.at(x, y) == 0) continue;
      const Eigen::Vector3d p =
          world_from_sensor * camera.Unproject(Eigen::Vector2d(x, y), clean.depth.at(x, y) * 1e-3);
      if (p.z() < 0.02)
        for (Joint foot : {Joint::kLeftFoot, Joint::kRightFoot})
          if ((p - skeleton[foot]).head<2>().norm() < 0.3) {
            ++out.floor_under_feet;
            break;
          }
      if (!mask.at(x, y)) continue;
      bool in_box = false;
      for (const Box& box : room->furniture)
        in_box = in_box || ((p.array() >= box.min.array() - 0.02).all() &&
                            (p.array() <= box.max.array() + 0.02).all());
      if (p.z() < 0.02)
        ++out.floor;
      else if (in_box)
        ++out.furniture;
      else
        ++out.wall;
    }
  return out;
}

TEST_P(SegmentTurnAndKick, FloorWallsAndFurnitureStayOut) {
  const SyntheticScene& scene = Scene();
  SyntheticRenderOptions render;
  render.depth_noise = GetParam();
  PersonSegmenter segmenter(scene.sensor_camera(), 0.001);
  for (int frame : kFrames) {
    const SyntheticView view = scene.RenderSensor(frame, render);
    const SyntheticView clean = scene.RenderSensor(frame);
    const auto result =
        segmenter.Segment(view.depth, SensorSkeleton(scene, frame), Geometry(scene, frame));
    ASSERT_TRUE(result.ok());
    const FalsePositives wrong = Classify(scene, frame, result->mask, clean);
    // Walls and furniture lie metres behind the subject: not one pixel. The floor touches the
    // feet: a noisy floor reading may pass the clearance next to a shoe, a handful at most
    // (against ~25000 subject pixels).
    EXPECT_EQ(wrong.wall, 0) << "frame " << frame;
    EXPECT_EQ(wrong.furniture, 0) << "frame " << frame;
    EXPECT_LE(wrong.floor, 10) << "frame " << frame;
    EXPECT_GT(wrong.floor_under_feet, 300) << "frame " << frame;  // there was floor to take
    EXPECT_TRUE(result->floor_in_sensor.has_value());
  }
}

TEST(SegmentPerson, FloorIsFittedOnceForAStaticSensorAndMatchesTheWorldFloor) {
  const SyntheticScene& scene = Scene();
  SyntheticRenderOptions render;
  render.depth_noise = true;
  PersonSegmenter segmenter(scene.sensor_camera(), 0.001);
  int fits = 0;
  for (int frame = 0; frame < scene.frame_count(); frame += 20) {
    const SyntheticView view = scene.RenderSensor(frame, render);
    const auto result =
        segmenter.Segment(view.depth, SensorSkeleton(scene, frame), Geometry(scene, frame));
    ASSERT_TRUE(result.ok());
    ASSERT_TRUE(result->floor_in_sensor);
    fits += result->floor_refitted;
    if (frame == 0) {
      EXPECT_TRUE(result->floor_refitted);
    }
    // The true floor: world z = 0, i.e. normal world_up and offset 0 in the world frame.
    const Plane3 world = result->floor_in_sensor->Transformed(scene.world_from_sensor(frame));
    EXPECT_GT(world.normal.dot(Eigen::Vector3d::UnitZ()), std::cos(1.0 * std::numbers::pi / 180));
    EXPECT_NEAR(world.offset, 0.0, 0.01);
  }
  EXPECT_EQ(fits, 1);
}

TEST(SegmentPerson, WithoutPoseOrUpTheSkeletonGivesTheUpAxis) {
  const SyntheticScene& scene = Scene();
  SyntheticRenderOptions render;
  render.depth_noise = true;
  PersonSegmenter segmenter(scene.sensor_camera(), 0.001);
  for (int frame : {0, 90, 135}) {
    const SyntheticView view = scene.RenderSensor(frame, render);
    const auto result = segmenter.Segment(view.depth, SensorSkeleton(scene, frame));
    ASSERT_TRUE(result.ok());
    ASSERT_TRUE(result->floor_in_sensor);
    EXPECT_GE(CompareMasks(result->mask, view.mask).iou, 0.9) << "frame " << frame;
  }
}

TEST(SegmentPerson, AMovedSensorWithoutPoseRefitsTheCachedFloor) {
  const SyntheticScene& scene = Scene();
  PersonSegmenter segmenter(scene.sensor_camera(), 0.001);
  const SyntheticView first = scene.RenderSensor(0);
  const auto a = segmenter.Segment(first.depth, SensorSkeleton(scene, 0));
  ASSERT_TRUE(a.ok() && a->floor_refitted);
  const auto b = segmenter.Segment(first.depth, SensorSkeleton(scene, 0));
  ASSERT_TRUE(b.ok() && b->floor_in_sensor);
  EXPECT_FALSE(b->floor_refitted);  // cached in the sensor frame: still fits
  // The sensor 40 cm lower and 1 m to the side, still looking at the subject: the cached
  // plane no longer fits in the sensor frame.
  const Eigen::Isometry3d moved =
      LookAt(Eigen::Vector3d(1.0, -2.8, 0.9), Eigen::Vector3d(0.0, 0.0, 0.95));
  const SyntheticView view = scene.Render(0, scene.sensor_camera(), moved);
  const Skeleton skeleton = scene.skeleton_in_world(0).Transformed(moved.inverse());
  const auto c = segmenter.Segment(view.depth, skeleton);
  ASSERT_TRUE(c.ok());
  EXPECT_TRUE(c->floor_refitted);
  ASSERT_TRUE(c->floor_in_sensor);
  const Plane3 world = c->floor_in_sensor->Transformed(moved);
  EXPECT_NEAR(world.offset, 0.0, 0.01);
  EXPECT_GE(CompareMasks(c->mask, view.mask).iou, 0.9);
}

}  // namespace
}  // namespace reenact::capture

// Recording from a moving (hand-held) synthetic sensor: the clip keeps the pose of every
// frame and the background map lands on the room's surfaces, which it does only if every
// keyframe is lifted with its own pose.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "capture-client/map/background_map_builder.h"
#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "proto/clip/clip_directory.h"
#include "synthetic/room.h"
#include "synthetic/synthetic_scene.h"
#include "tests/support/temp_dir.h"

namespace reenact::capture {
namespace {

using reenact::test_support::TempDir;

namespace fs = std::filesystem;

// Distance from p to the nearest room face (a rectangle: walls, floor, ceiling, furniture).
double DistanceToRoom(const RoomModel& room, const Eigen::Vector3d& p) {
  double best = INFINITY;
  for (const RoomFace& f : room.faces) {
    const Eigen::Vector3d d = p - f.origin;
    const double u = std::clamp(d.dot(f.u_axis), 0.0, f.width);
    const double v = std::clamp(d.dot(f.v_axis), 0.0, f.height);
    best = std::min(best, (f.origin + u * f.u_axis + v * f.v_axis - p).norm());
  }
  return best;
}

TEST(MovingSensorRecording, KeepsEveryPoseAndBuildsAConsistentMap) {
  constexpr int kFrames = 61;
  auto source = SyntheticSource::Open("walk-handheld");
  ASSERT_TRUE(source.ok()) << source.error().message;
  const SyntheticScene scene = SyntheticScene::Create("walk-handheld").value();
  TempDir tmp;
  RecordOptions options;
  options.max_frames = kFrames;
  options.keyframe_interval = 15;  // keyframes 0, 15, .., 60: the sensor moves ~0.4 m
  const auto summary = RecordClip(**source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(summary->frames, kFrames);

  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  ASSERT_EQ(clip->manifest().frame_count, kFrames);
  for (int k = 0; k < kFrames; k += 5) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    EXPECT_LT((frame->world_from_sensor.matrix() - scene.world_from_sensor(k).matrix()).norm(),
              1e-9)
        << k;
  }
  EXPECT_GT(
      (scene.world_from_sensor(60).translation() - scene.world_from_sensor(0).translation()).norm(),
      0.3);

  // Map points lie on the room's surfaces: depth is exact to 1 mm at these distances, so a
  // point is off by more than 3 cm only where a keypoint sits on a depth edge.
  const auto map = clip->ReadMap();
  ASSERT_TRUE(map.ok()) << map.error().message;
  ASSERT_GT(map->points.size(), 500u);
  const RoomModel& room = *SharedRoom();
  size_t on_surface = 0, seen_twice = 0;
  for (const auto& p : map->points) {
    on_surface += DistanceToRoom(room, p.position_in_world) < 0.03;
    seen_twice += p.observations >= 2;
  }
  EXPECT_GT(on_surface, map->points.size() * 95 / 100);
  // Keyframes of the same walls from poses 0.05-0.15 m apart re-observe the same features.
  EXPECT_GT(seen_twice, map->points.size() / 20);
}

TEST(MovingSensorRecording, TheSurfaceCheckCatchesAWrongPose) {
  // Control for the test above: frame 60 lifted with frame 0's pose (as if the sensor were
  // static) puts most of its points off the room's surfaces.
  const SyntheticScene scene = SyntheticScene::Create("walk-handheld").value();
  const SyntheticView view = scene.RenderSensor(60);
  BackgroundMapBuilder builder;
  builder.AddKeyframe(view.color, view.depth, 0.001, view.mask, scene.sensor_camera(),
                      scene.world_from_sensor(0));
  const proto::ClipMap map = std::move(builder).Finish();
  ASSERT_GT(map.points.size(), 100u);
  size_t on_surface = 0;
  for (const auto& p : map.points)
    on_surface += DistanceToRoom(*SharedRoom(), p.position_in_world) < 0.03;
  EXPECT_LT(on_surface, map.points.size() / 2);
}

}  // namespace
}  // namespace reenact::capture

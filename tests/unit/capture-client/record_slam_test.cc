// Recording with SLAM poses: the recorder tracks the sensor itself when the source has no
// poses (real sensors) or when told to (PoseSource::kSlam), stores SLAM's map, takes
// skeletons from a lookup (an imported track), and fails clearly when a recording has no
// skeleton or no usable depth.
#include <gtest/gtest.h>

#include <filesystem>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/source/synthetic_source.h"
#include "capture-client/source/tum_source.h"
#include "common/align/trajectory_error.h"
#include "proto/clip/clip_directory.h"
#include "synthetic/room.h"
#include "synthetic/synthetic_scene.h"
#include "tests/support/as_real_sensor.h"
#include "tests/support/temp_dir.h"

namespace reenact::capture {
namespace {

using reenact::test_support::AsRealSensor;
using reenact::test_support::TempDir;
namespace fs = std::filesystem;

// Distance from p to the nearest face of the synthetic room.
double DistanceToRoom(const Eigen::Vector3d& p) {
  double best = INFINITY;
  for (const RoomFace& f : SharedRoom()->faces) {
    const Eigen::Vector3d d = p - f.origin;
    const double u = std::clamp(d.dot(f.u_axis), 0.0, f.width);
    const double v = std::clamp(d.dot(f.v_axis), 0.0, f.height);
    best = std::min(best, (f.origin + u * f.u_axis + v * f.v_axis - p).norm());
  }
  return best;
}

double AngleDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() * 180 / M_PI;
}

std::unique_ptr<FrameSource> Synthetic(const std::string& scenario) {
  auto source = SyntheticSource::Open(scenario);
  EXPECT_TRUE(source.ok()) << source.error().message;
  return std::move(source).value();
}

TEST(RecordWithSlam, HandheldSensorIsTrackedAndTheMapIsBackgroundOnly) {
  // walk-handheld: the sensor walks 0.4 m around a walking person. The source's poses are
  // ignored (kSlam) except to anchor the world at frame 0, so the stored poses can be
  // compared with the ground truth directly.
  constexpr int kFrames = 60;
  auto source = Synthetic("walk-handheld");
  const SyntheticScene scene = SyntheticScene::Create("walk-handheld").value();
  TempDir tmp;
  RecordOptions options;
  options.max_frames = kFrames;
  options.poses = PoseSource::kSlam;
  const auto summary = RecordClip(*source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_TRUE(summary->slam_poses);
  EXPECT_EQ(summary->frames, kFrames);
  EXPECT_GT(summary->slam_keyframes, 1);

  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  // Rendered images with 1 mm depth: a frame-to-map tracker holds the pose to a few
  // millimetres over two seconds; 2 cm / 1 degree is the viewer's own relocalisation goal.
  double worst_m = 0, worst_deg = 0;
  for (int k = 0; k < kFrames; ++k) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    const Eigen::Isometry3d truth = scene.world_from_sensor(k);
    worst_m =
        std::max(worst_m, (frame->world_from_sensor.translation() - truth.translation()).norm());
    worst_deg = std::max(worst_deg, AngleDeg(frame->world_from_sensor, truth));
    // The skeleton is stored in the SLAM world: it must land on the true one.
    const Skeleton truth_skeleton = scene.skeleton_in_world(k);
    EXPECT_LT((frame->skeleton_in_world[Joint::kTorso] - truth_skeleton[Joint::kTorso]).norm(),
              0.03)
        << k;
  }
  EXPECT_LT(worst_m, 0.02);
  EXPECT_LT(worst_deg, 1.0);

  // The stored map is SLAM's, in the same world: its points lie on the room's surfaces (not on
  // the person, who stands 1.5-3 m inside the room), and the manifest's up is the scene's.
  // With SLAM's default depth noise (made for real sensors: 5 cm at 1 m) bundle adjustment
  // lets far points slide along their rays and half of them miss by more than 3 cm; the
  // source's own depth_sigma_1m_m keeps them on the walls.
  const auto map = clip->ReadMap();
  ASSERT_TRUE(map.ok()) << map.error().message;
  ASSERT_GT(map->points.size(), 200u);
  size_t on_surface = 0;
  for (const auto& p : map->points) on_surface += DistanceToRoom(p.position_in_world) < 0.03;
  EXPECT_GT(on_surface, map->points.size() * 95 / 100);
  EXPECT_LT((clip->manifest().world_up - *source->info().world_up).norm(), 1e-9);
}

TEST(RecordWithSlam, SourceWithoutPosesIsTrackedAndUpComesFromTheFloor) {
  // turn-and-kick from a static sensor, given as a real sensor gives it (no pose, no mask):
  // SLAM's world is the first camera frame, so every stored pose must be the identity, and the
  // world's up must be the floor's normal seen from the first camera.
  constexpr int kFrames = 30;
  AsRealSensor source(Synthetic("turn-and-kick"), /*keep_skeleton=*/true);
  TempDir tmp;
  RecordOptions options;
  options.max_frames = kFrames;
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  // The wrapper drops poses, so the skeleton it keeps cannot be placed: the source's
  // world-frame skeletons need its poses. That is the error to expect without a lookup.
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "unsupported");
  EXPECT_FALSE(fs::exists(tmp.path() / "clip"));

  // With the skeletons given in the sensor frame (as an imported track gives them).
  AsRealSensor again(Synthetic("turn-and-kick"), /*keep_skeleton=*/false);
  options.skeletons = [&](int64_t index, double) { return again.SkeletonOf(index); };
  const auto recorded = RecordClip(again, tmp.path() / "clip", options);
  ASSERT_TRUE(recorded.ok()) << recorded.error().message;
  EXPECT_TRUE(recorded->slam_poses);
  EXPECT_EQ(recorded->frames, kFrames);
  EXPECT_EQ(recorded->segmented_frames, kFrames);
  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  for (int k = 0; k < kFrames; k += 5) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    EXPECT_LT(frame->world_from_sensor.translation().norm(), 0.01) << k;
    EXPECT_LT(AngleDeg(frame->world_from_sensor, Eigen::Isometry3d::Identity()), 0.5) << k;
  }
  const Eigen::Isometry3d world_from_sensor0 = *again.removed()[0].world_from_sensor;
  const Eigen::Vector3d true_up_in_sensor =
      world_from_sensor0.linear().transpose() * *again.info().world_up;
  EXPECT_LT(std::acos(std::clamp(clip->manifest().world_up.dot(true_up_in_sensor), -1.0, 1.0)) *
                180 / M_PI,
            2.0);
}

TEST(RecordWithSlam, AFrameSkeletonSourceIsGivenSlamsPredictionOrTheSourcesPose) {
  // A tracker's static scene needs each frame's sensor pose before SLAM tracks that frame
  // (SLAM needs the frame's person mask, made from its skeleton): the recorder gives SLAM's
  // prediction. walk-handheld given as a real sensor gives it; SLAM's world is the first camera.
  constexpr int kFrames = 20;
  AsRealSensor source(Synthetic("walk-handheld"), /*keep_skeleton=*/false);
  std::vector<FramePoseHint> hints;
  RecordOptions options;
  options.max_frames = kFrames;
  options.frame_skeletons = [&](int64_t index, const SensorFrame&,
                                const FramePoseHint& pose) -> Expected<std::optional<Skeleton>> {
    hints.push_back(pose);
    return source.SkeletonOf(index);
  };
  TempDir tmp;
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  ASSERT_EQ(hints.size(), static_cast<size_t>(kFrames));
  EXPECT_FALSE(hints[0].world_from_sensor);  // SLAM founds its map on this frame
  const Eigen::Isometry3d map_from_truth = source.removed()[0].world_from_sensor->inverse();
  const Eigen::Vector3d true_up = map_from_truth.linear() * *source.info().world_up;
  for (int k = 1; k < kFrames; ++k) {
    ASSERT_TRUE(hints[k].world_from_sensor && hints[k].world_up) << k;
    // At 30 frames a second a hand-held sensor moves about 1 cm a frame; the prediction carries
    // the last motion on, and SLAM's poses hold to a few millimetres (slam_synthetic_test):
    // 2 cm and 1 degree.
    const Eigen::Isometry3d truth = map_from_truth * *source.removed()[k].world_from_sensor;
    EXPECT_LT((hints[k].world_from_sensor->translation() - truth.translation()).norm(), 0.02) << k;
    EXPECT_LT(AngleDeg(*hints[k].world_from_sensor, truth), 1.0) << k;
    // The up, from the floor segmented under the first frame: as in the test above, 2 degrees.
    EXPECT_LT(std::acos(std::clamp(hints[k].world_up->dot(true_up), -1.0, 1.0)) * 180 / M_PI, 2.0)
        << k;
  }

  // A source with poses: the tracker is given them, and the source's up, as they are.
  auto posed = Synthetic("walk-handheld");
  const SyntheticScene scene = SyntheticScene::Create("walk-handheld").value();
  hints.clear();
  options.max_frames = 3;
  options.frame_skeletons = [&](int64_t index, const SensorFrame&,
                                const FramePoseHint& pose) -> Expected<std::optional<Skeleton>> {
    hints.push_back(pose);
    return std::optional(
        scene.skeleton_in_world(index).Transformed(scene.world_from_sensor(index).inverse()));
  };
  ASSERT_TRUE(RecordClip(*posed, tmp.path() / "posed", options).ok());
  ASSERT_EQ(hints.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(hints[k].world_from_sensor && hints[k].world_up) << k;
    EXPECT_TRUE(hints[k].world_from_sensor->isApprox(scene.world_from_sensor(k), 1e-12)) << k;
    EXPECT_TRUE(hints[k].world_up->isApprox(scene.world_up(), 1e-12)) << k;
  }
}

TEST(RecordWithSlam, FramesWithoutSkeletonServeSlamButAreNotStored) {
  constexpr int kFrames = 30;
  AsRealSensor source(Synthetic("turn-and-kick"), /*keep_skeleton=*/false);
  TempDir tmp;
  RecordOptions options;
  options.max_frames = kFrames;
  options.skeletons = [&](int64_t index, double) -> std::optional<Skeleton> {
    if (index % 3 != 0) return std::nullopt;
    return source.SkeletonOf(index);
  };
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_EQ(summary->source_frames, kFrames);
  EXPECT_EQ(summary->frames, kFrames / 3);
  EXPECT_EQ(summary->frames_without_skeleton, kFrames - kFrames / 3);
  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  for (int k = 0; k < kFrames / 3; ++k) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    EXPECT_DOUBLE_EQ(frame->timestamp_s, source.removed()[3 * k].timestamp_s);
  }
}

TEST(RecordWithSlam, NoSkeletonAtAllIsAClearErrorAndLeavesNothing) {
  AsRealSensor source(Synthetic("turn-and-kick"), /*keep_skeleton=*/false);
  TempDir tmp;
  RecordOptions options;
  options.max_frames = 10;
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "no_skeleton");
  EXPECT_NE(summary.error().message.find("--skeleton"), std::string::npos)
      << summary.error().message;
  EXPECT_FALSE(fs::exists(tmp.path() / "clip"));
}

TEST(RecordWithSlam, AllZeroDepthIsAClearErrorAndLeavesNothing) {
  AsRealSensor source(Synthetic("turn-and-kick"), /*keep_skeleton=*/false, /*zero_depth=*/true);
  TempDir tmp;
  RecordOptions options;
  options.max_frames = 10;
  options.skeletons = [&](int64_t index, double) { return source.SkeletonOf(index); };
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_FALSE(summary.ok());
  EXPECT_EQ(summary.error().code, "no_pose");
  EXPECT_NE(summary.error().message.find("depth"), std::string::npos) << summary.error().message;
  EXPECT_FALSE(fs::exists(tmp.path() / "clip"));
}

TEST(RecordWithSlam, RealTumRecordingIsTrackedCloseToItsGroundTruth) {
  // The TUM sequence has no person; a skeleton 10 m away (beyond the Kinect's range:
  // segmentation finds nobody, so SLAM sees the whole image) stands in for an imported track.
  const fs::path dir = fs::path(REENACT_SHARED_DATA_DIR) / "tum-fr1-rpy-head";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no TUM data at " << dir;
  auto tum = TumSource::OpenSpec(dir.string() + "?undistort=both");
  ASSERT_TRUE(tum.ok()) << tum.error().message;
  TumSource& source = **tum;
  EXPECT_GT(source.info().color_readout_ratio, 0);  // a Kinect: rolling shutter
  Skeleton far_away;
  for (int j = 0; j < kJointCount; ++j) far_away.Set(static_cast<Joint>(j), {0.01 * j, 0, 10});
  TempDir tmp;
  RecordOptions options;
  options.skeletons = [&](int64_t, double) { return far_away; };
  const auto summary = RecordClip(source, tmp.path() / "clip", options);
  ASSERT_TRUE(summary.ok()) << summary.error().message;
  EXPECT_TRUE(summary->slam_poses);
  EXPECT_EQ(summary->frames_without_pose, 0);
  ASSERT_EQ(summary->frames, summary->source_frames);

  const auto clip = proto::ReadClipDirectory(tmp.path() / "clip");
  ASSERT_TRUE(clip.ok()) << clip.error().message;
  std::vector<Eigen::Isometry3d> truth, estimate;
  for (int k = 0; k < summary->frames; ++k) {
    const auto frame = clip->ReadFrame(k);
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    if (!source.ground_truth()[k]) continue;
    truth.push_back(*source.ground_truth()[k]);
    estimate.push_back(frame->world_from_sensor);
  }
  ASSERT_GT(truth.size(), 30u);
  // As in slam_tum_test: the RMS spread of the true positions is what a tracker that left
  // the sensor in place would score; the recorder's poses must explain most of the motion.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& t : truth) mean += t.translation() / truth.size();
  double spread = 0;
  for (const auto& t : truth) spread += (t.translation() - mean).squaredNorm() / truth.size();
  spread = std::sqrt(spread);
  const auto ate = AbsoluteTrajectoryError(truth, estimate);
  ASSERT_TRUE(ate.ok());
  EXPECT_LT(ate.ate_rmse_m, spread / 2) << "spread " << spread;
  EXPECT_GT(clip->manifest().map.point_count, 200);
}

}  // namespace
}  // namespace reenact::capture

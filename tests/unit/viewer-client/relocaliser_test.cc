// The viewer's relocaliser on synthetic data with known poses: the clip map is built from
// the synthetic scene's sensor frames at their true poses (as the recorder does), viewer
// frames are rendered from known cameras turned about the subject, so the true
// viewer_from_world is known by construction.
#include "viewer-client/reloc/relocaliser.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "capture-client/map/background_map_builder.h"
#include "common/error/check.h"
#include "synthetic/synthetic_scene.h"
#include "viewer-client/play/orbit_camera.h"

namespace reenact::viewer {
namespace {

struct World {
  capture::SyntheticScene scene;
  proto::ClipMap map;
  Eigen::Vector3d subject_centre;
};

// turn-and-kick (static sensor): the map from sensor frames 0, 30, ..., 150.
const World& TestWorld() {
  static const World world = [] {
    auto scene = capture::SyntheticScene::Create("turn-and-kick");
    REENACT_CHECK(scene.ok(), "scene");
    capture::BackgroundMapBuilder builder;
    for (int f = 0; f < scene->frame_count(); f += 30) {
      const capture::SyntheticView view = scene->RenderSensor(f);
      builder.AddKeyframe(view.color, view.depth, 0.001, view.mask, scene->sensor_camera(),
                          scene->world_from_sensor(f));
    }
    const Skeleton skeleton = scene->skeleton_in_world(0);
    return World{*scene, std::move(builder).Finish(), skeleton[Joint::kTorso]};
  }();
  return world;
}

// world_from_viewer turned by angle_deg about the vertical through the subject, raised by
// height_m, looking at the subject.
Eigen::Isometry3d ViewerPose(double angle_deg, double height_m = 0) {
  const World& w = TestWorld();
  OrbitCameraOptions orbit;
  orbit.angle_deg = angle_deg;
  orbit.height_offset_m = height_m;
  const auto pose = OrbitWorldFromViewer(w.scene.world_from_sensor(0), w.subject_centre,
                                         w.scene.world_up(), orbit);
  REENACT_CHECK(pose.has_value(), "orbit pose");
  return *pose;
}

cv::Mat RenderGray(int frame, const Eigen::Isometry3d& world_from_viewer) {
  const World& w = TestWorld();
  const capture::SyntheticView view =
      w.scene.Render(frame, w.scene.sensor_camera(), world_from_viewer);
  const cv::Mat rgb(view.color.height, view.color.width, CV_8UC3,
                    const_cast<uint8_t*>(view.color.data.data()));
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  return gray;
}

struct PoseError {
  double position_m, angle_deg;
};

PoseError Error(const Eigen::Isometry3d& viewer_from_world, const Eigen::Isometry3d& truth_w_f_v) {
  const Eigen::Isometry3d world_from_viewer = viewer_from_world.inverse();
  const Eigen::Isometry3d delta = truth_w_f_v.inverse() * world_from_viewer;
  return {(world_from_viewer.translation() - truth_w_f_v.translation()).norm(),
          Eigen::AngleAxisd(delta.linear()).angle() * 180 / std::numbers::pi};
}

Relocaliser Make(const proto::ClipMap& map, const RelocaliserOptions& options = {}) {
  auto r = Relocaliser::Create(map, TestWorld().scene.sensor_camera(), options);
  REENACT_CHECK(r.ok(), "relocaliser");
  return std::move(*r);
}

// Bounds. The rendering is exact and the map's depths carry only millimetre quantisation, so
// what is left is where ORB puts its keypoints: on whole pixels of their pyramid level (up to
// 0.5 s^octave px off, about 0.8 px median here), on a background that is nearly one plane
// 5-5.5 m away (the back wall), where 1 px is 1.07 cm and a sideways shift of the camera is
// almost the same picture as a turn (the two differ only through the spread of depths). A
// least-squares fit from the true pose with the true matches lands 1.2 cm / 0.12 degrees
// (straight on) to 2.1 cm / 0.23 degrees (20 degrees around) away from the truth, so the
// bounds are twice that: 4 cm and 0.5 degrees (the 2 cm is met on most frames, see
// reenact-eval reloc, not on every one).
constexpr double kMaxPositionErrorM = 0.04;
constexpr double kMaxAngleErrorDeg = 0.5;
TEST(Relocaliser, FindsKnownPosesFromScratch) {
  ASSERT_GT(TestWorld().map.points.size(), 200u);
  for (double angle : {0.0, 10.0, -20.0, 30.0}) {
    Relocaliser reloc = Make(TestWorld().map);
    const Eigen::Isometry3d truth = ViewerPose(angle, 0.1);
    const auto result = reloc.ProcessFrame(RenderGray(45, truth));
    ASSERT_TRUE(result.ok()) << result.error().message;
    ASSERT_EQ(result->status, RelocStatus::kRelocalised) << angle << ": " << result->reason;
    ASSERT_TRUE(result->viewer_from_world.has_value());
    EXPECT_GE(result->inliers, 30);
    const PoseError e = Error(*result->viewer_from_world, truth);
    // At 30 degrees this map without virtual views keeps only 50-60 inliers, and the fixed
    // placement error of each map point (relocaliser.h) averages over few of them: 4.0 cm
    // with 1000 viewer features, 4.5 cm with 2000 (measured). Far around the subject clips
    // carry virtual views; relocaliser_virtual_views_test.cc holds 4 cm there up to 45 degrees.
    EXPECT_LT(e.position_m, std::abs(angle) >= 30 ? 1.5 * kMaxPositionErrorM : kMaxPositionErrorM)
        << "at " << angle << " degrees";
    EXPECT_LT(e.angle_deg, kMaxAngleErrorDeg) << "at " << angle << " degrees";
  }
}

TEST(Relocaliser, TracksAMovingViewerFrameToFrame) {
  Relocaliser reloc = Make(TestWorld().map);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Isometry3d truth = ViewerPose(2.0 * k, 0.02 * k);
    const auto result = reloc.ProcessFrame(RenderGray(60 + k, truth));
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(result->status, k == 0 ? RelocStatus::kRelocalised : RelocStatus::kTracked)
        << "frame " << k << ": " << result->reason;
    ASSERT_TRUE(result->viewer_from_world.has_value());
    const PoseError e = Error(*result->viewer_from_world, truth);
    EXPECT_LT(e.position_m, kMaxPositionErrorM) << "frame " << k;
    EXPECT_LT(e.angle_deg, kMaxAngleErrorDeg) << "frame " << k;
  }
}

// The CPU time per stage: each stage a part of the frame's total, the descriptor search only
// when relocalising, and the matching's work counted (every frame matches by projection: a
// relocalised pose is confirmed that way).
TEST(Relocaliser, ReportsCpuTimePerStage) {
  Relocaliser reloc = Make(TestWorld().map);
  for (int k = 0; k < 3; ++k) {
    const auto result = reloc.ProcessFrame(RenderGray(60 + k, ViewerPose(2.0 * k)));
    ASSERT_TRUE(result.ok()) << result.error().message;
    ASSERT_NE(result->status, RelocStatus::kLost) << result->reason;
    const RelocStageTimes& cpu = result->cpu;
    EXPECT_GT(cpu.features_ms, 0.0);
    EXPECT_GE(cpu.features_ms, cpu.orb.detect_ms + cpu.orb.spread_ms + cpu.orb.subpixel_ms - 1e-6);
    const double parts = cpu.features_ms + cpu.grid_ms + cpu.match_ms + cpu.refine_ms +
                         cpu.relocalise_ms + cpu.smooth_ms;
    EXPECT_GE(cpu.total_ms, parts - 1e-6);
    EXPECT_EQ(cpu.relocalise_ms > 0, result->status == RelocStatus::kRelocalised);
    EXPECT_GT(cpu.matching.comparisons, 0);
    EXPECT_GE(cpu.matching.projected, cpu.matching.in_view);
    // At most two tracking attempts (a failed track, then the confirmation) of three passes,
    // each over at most the whole map.
    EXPECT_LE(cpu.matching.projected, 6 * static_cast<int64_t>(reloc.map_size()));
  }
}

TEST(Relocaliser, LostOnAFeaturelessFrameThenRelocalisesAgain) {
  Relocaliser reloc = Make(TestWorld().map);
  const Eigen::Isometry3d truth = ViewerPose(5);
  ASSERT_EQ(reloc.ProcessFrame(RenderGray(0, truth))->status, RelocStatus::kRelocalised);
  // A covered lens: one grey level, no corners.
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(90));
  const auto lost = reloc.ProcessFrame(blank);
  ASSERT_TRUE(lost.ok());
  EXPECT_EQ(lost->status, RelocStatus::kLost);
  EXPECT_EQ(lost->features, 0);
  EXPECT_FALSE(lost->viewer_from_world.has_value());
  EXPECT_NE(lost->reason.find("no features"), std::string::npos) << lost->reason;
  const auto again = reloc.ProcessFrame(RenderGray(1, truth));
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->status, RelocStatus::kRelocalised);
}

TEST(Relocaliser, AFrameOfAnotherSceneIsLostNotWrong) {
  // Random blocks of grey: plenty of ORB features, none of them in the map.
  Relocaliser reloc = Make(TestWorld().map);
  cv::Mat blocks(480, 640, CV_8UC1);
  cv::RNG rng(7);
  for (int y = 0; y < 480; y += 8)
    for (int x = 0; x < 640; x += 8) blocks(cv::Rect(x, y, 8, 8)).setTo(rng.uniform(0, 256));
  const auto result = reloc.ProcessFrame(blocks);
  ASSERT_TRUE(result.ok());
  EXPECT_GT(result->features, 100);
  EXPECT_EQ(result->status, RelocStatus::kLost);
  EXPECT_FALSE(result->viewer_from_world.has_value());
}

TEST(Relocaliser, EmptyMapIsRefused) {
  const auto r = Relocaliser::Create(proto::ClipMap{}, PinholeCamera::KinectLike());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "invalid_argument");
  EXPECT_NE(r.error().message.find("empty"), std::string::npos) << r.error().message;
}

TEST(Relocaliser, MapTooSmallIsRefusedWithCounts) {
  proto::ClipMap small;
  small.points.assign(TestWorld().map.points.begin(), TestWorld().map.points.begin() + 12);
  const auto r = Relocaliser::Create(small, PinholeCamera::KinectLike());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "invalid_argument");
  EXPECT_NE(r.error().message.find("too small"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("12 points"), std::string::npos) << r.error().message;
}

TEST(Relocaliser, SmallMapThatPassesCreateLosesFramesWithoutCrashing) {
  // 12 points let through by a lowered min_map_points give too few matches (at most 12 of
  // the 30 inliers needed): the frame is lost, and says why.
  proto::ClipMap small;
  small.points.assign(TestWorld().map.points.begin(), TestWorld().map.points.begin() + 12);
  RelocaliserOptions options;
  options.min_map_points = 4;
  Relocaliser reloc = Make(small, options);
  const auto result = reloc.ProcessFrame(RenderGray(0, ViewerPose(0)));
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, RelocStatus::kLost);
  EXPECT_FALSE(result->reason.empty());
}

TEST(Relocaliser, FrameOfTheWrongSizeIsRefused) {
  Relocaliser reloc = Make(TestWorld().map);
  const auto r = reloc.ProcessFrame(cv::Mat(240, 320, CV_8UC1, cv::Scalar(0)));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "invalid_argument");
  EXPECT_NE(r.error().message.find("320x240"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("640x480"), std::string::npos) << r.error().message;
  const auto depth_like = reloc.ProcessFrame(cv::Mat(480, 640, CV_16UC1, cv::Scalar(0)));
  ASSERT_FALSE(depth_like.ok());
  EXPECT_EQ(depth_like.error().code, "invalid_argument");
  EXPECT_FALSE(reloc.ProcessFrame(cv::Mat()).ok());
  EXPECT_FALSE(reloc.ProcessFrame(ImageRgb8{}).ok());
}

TEST(Relocaliser, InvalidCameraIsRefused) {
  PinholeCamera bad = PinholeCamera::KinectLike();
  bad.fx = 0;
  const auto r = Relocaliser::Create(TestWorld().map, bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "invalid_argument");
}

TEST(Relocaliser, OptionsCheck) {
  RelocaliserOptions o;
  EXPECT_NO_THROW(o.Check());
  o.min_map_points = 3;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.wide_search_radius_px = o.search_radius_px / 2;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.reloc_ratio = 0;
  EXPECT_THROW(o.Check(), CheckError);
  EXPECT_EQ(RelocStatusName(RelocStatus::kTracked), "tracked");
}

}  // namespace
}  // namespace reenact::viewer

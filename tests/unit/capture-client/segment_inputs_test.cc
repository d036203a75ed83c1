// Person segmentation: bad and degenerate input (errors and statuses), frame-source frames,
// a subject cut by the image border, options and per-pixel rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "capture-client/segment/mask_overlap.h"
#include "capture-client/segment/person_segmenter.h"
#include "capture-client/segment/pixel_rays.h"
#include "common/error/check.h"
#include "synthetic/scenario.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const SyntheticScene& Scene() {
  static const SyntheticScene scene = SyntheticScene::Create("turn-and-kick", 1).value();
  return scene;
}
const SyntheticView& View0() {
  static const SyntheticView view = Scene().RenderSensor(0);
  return view;
}
Skeleton Skeleton0() {
  return Scene().skeleton_in_world(0).Transformed(Scene().world_from_sensor(0).inverse());
}
Skeleton Moved(Skeleton s, const Eigen::Vector3d& by) {
  for (auto& p : s.position) p += by;
  return s;
}
bool Empty(const ImageGray8& mask) {
  return std::all_of(mask.data.begin(), mask.data.end(), [](uint8_t v) { return v == 0; });
}
PersonSegmenter Segmenter() { return PersonSegmenter(Scene().sensor_camera(), 0.001); }

TEST(SegmentInputs, NoSkeletonIsAnError) {
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(View0().depth, Skeleton());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, "invalid_argument");
  EXPECT_NE(result.error().message.find("no skeleton"), std::string::npos);
}

TEST(SegmentInputs, NonFiniteJointIsAnError) {
  Skeleton s = Skeleton0();
  s[Joint::kLeftElbow].x() = std::numeric_limits<double>::quiet_NaN();
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(View0().depth, s);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("l_elbow"), std::string::npos);
}

TEST(SegmentInputs, DepthOfAnotherSizeIsAnError) {
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(ImageDepthMm(320, 240, 1, 3000), Skeleton0());
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, "invalid_argument");
  EXPECT_NE(result.error().message.find("320x240"), std::string::npos);
  EXPECT_NE(result.error().message.find("640x480"), std::string::npos);
}

TEST(SegmentInputs, BadWorldUpIsAnError) {
  auto segmenter = Segmenter();
  SegmentFrameGeometry geometry{Scene().world_from_sensor(0), Eigen::Vector3d::Zero()};
  EXPECT_FALSE(segmenter.Segment(View0().depth, Skeleton0(), geometry).ok());
}

TEST(SegmentInputs, AllZeroDepthGivesAnEmptyMaskAndAStatus) {
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(ImageDepthMm(640, 480, 1, 0), Skeleton0());
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, SegmentStatus::kNoDepth);
  EXPECT_EQ(result->mask.width, 640);
  EXPECT_EQ(result->mask.height, 480);
  EXPECT_TRUE(Empty(result->mask));
  EXPECT_EQ(result->mask_pixels, 0);
  EXPECT_EQ(SegmentStatusName(result->status), "no_depth");
}

TEST(SegmentInputs, SkeletonBehindTheCamera) {
  Skeleton s = Skeleton0();
  for (auto& p : s.position) p.z() = -p.z();
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(View0().depth, s);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, SegmentStatus::kSkeletonBehindCamera);
  EXPECT_TRUE(Empty(result->mask));
}

TEST(SegmentInputs, SkeletonOutsideTheImage) {
  auto segmenter = Segmenter();
  for (const Eigen::Vector3d& by : {Eigen::Vector3d(20, 0, 0), Eigen::Vector3d(0, -20, 0)}) {
    const auto result = segmenter.Segment(View0().depth, Moved(Skeleton0(), by));
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->status, SegmentStatus::kSkeletonOutsideImage);
    EXPECT_TRUE(Empty(result->mask));
  }
}

TEST(SegmentInputs, SkeletonThatTheDepthDoesNotShowGivesNoSeeds) {
  // 1.5 m nearer the sensor than the person: nothing at its depth along its bones.
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(View0().depth, Moved(Skeleton0(), {0, 0, -1.5}));
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, SegmentStatus::kNoSeeds);
  EXPECT_TRUE(Empty(result->mask));
}

TEST(SegmentInputs, SkeletonWithOnlySomeJoints) {
  // An upper-body tracker: no legs and no waist. No floor guess, but the upper body is found
  // and nothing outside the subject is taken.
  Skeleton s = Skeleton0();
  for (Joint j : {Joint::kWaist, Joint::kLeftHip, Joint::kLeftKnee, Joint::kLeftFoot,
                  Joint::kRightHip, Joint::kRightKnee, Joint::kRightFoot})
    s.confidence[Index(j)] = 0;
  auto segmenter = Segmenter();
  const auto result = segmenter.Segment(View0().depth, s);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, SegmentStatus::kOk);
  EXPECT_FALSE(result->floor_in_sensor.has_value());
  const MaskOverlap overlap = CompareMasks(result->mask, View0().mask);
  EXPECT_EQ(overlap.precision, 1.0);
  EXPECT_GT(overlap.recall, 0.4);  // head, arms and torso: about half the subject's pixels
}

TEST(SegmentInputs, ATrackersSkeletonOffByCentimetresStillSegments) {
  // Every joint 3 cm off (random direction) and the whole skeleton 5 cm to the side and
  // 5 cm deeper: a depth tracker's error, not ground truth.
  const SyntheticScene& scene = Scene();
  SyntheticRenderOptions noisy;
  noisy.depth_noise = true;
  auto segmenter = Segmenter();
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0, 1);
  for (int frame : {0, 90, 135}) {
    Skeleton s =
        scene.skeleton_in_world(frame).Transformed(scene.world_from_sensor(frame).inverse());
    for (auto& p : s.position) {
      const Eigen::Vector3d dir(n(rng), n(rng), n(rng));
      p += 0.03 * dir.normalized() + Eigen::Vector3d(0.05, 0, 0.05);
    }
    const SyntheticView view = scene.RenderSensor(frame, noisy);
    const auto result = segmenter.Segment(view.depth, s);
    ASSERT_TRUE(result.ok());
    EXPECT_GE(CompareMasks(result->mask, view.mask).iou, 0.9) << "frame " << frame;
  }
}

TEST(SegmentInputs, SubjectCutByTheImageBorder) {
  // The sensor turned 30 degrees left (about its own y axis): the subject sits at the right
  // border, partly outside the image.
  const SyntheticScene& scene = Scene();
  const Eigen::Isometry3d turned =
      scene.world_from_sensor(0) *
      Eigen::AngleAxisd(-30 * std::numbers::pi / 180, Eigen::Vector3d::UnitY());
  SyntheticRenderOptions noisy;
  noisy.depth_noise = true;
  const SyntheticView view = scene.Render(0, scene.sensor_camera(), turned, noisy);
  const long visible = std::count(view.mask.data.begin(), view.mask.data.end(), 255);
  ASSERT_GT(visible, 2000);
  ASSERT_LT(visible, 20000);
  auto segmenter = Segmenter();
  const auto result =
      segmenter.Segment(view.depth, scene.skeleton_in_world(0).Transformed(turned.inverse()),
                        {turned, scene.world_up()});
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->status, SegmentStatus::kOk);
  EXPECT_GE(CompareMasks(result->mask, view.mask).iou, 0.9);
}

TEST(SegmentInputs, FrameSourceFrames) {
  SensorFrame frame;
  frame.depth = View0().depth;
  auto segmenter = Segmenter();
  const auto up = Scene().world_up();
  const auto no_skeleton = segmenter.SegmentFrame(frame, up);
  ASSERT_FALSE(no_skeleton.ok());
  EXPECT_NE(no_skeleton.error().message.find("no skeleton"), std::string::npos);

  frame.skeleton_in_world = Scene().skeleton_in_world(0);
  const auto no_pose = segmenter.SegmentFrame(frame, up);
  ASSERT_FALSE(no_pose.ok());
  EXPECT_NE(no_pose.error().message.find("sensor pose"), std::string::npos);

  frame.world_from_sensor = Scene().world_from_sensor(0);
  const auto result = segmenter.SegmentFrame(frame, up);
  ASSERT_TRUE(result.ok());
  auto direct = Segmenter();
  const auto expected = direct.Segment(View0().depth, Skeleton0(), {frame.world_from_sensor, up});
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(result->mask.data, expected->mask.data);
  EXPECT_GE(CompareMasks(result->mask, View0().mask).iou, 0.9);
}

TEST(SegmentInputs, OptionsOutOfRangeThrow) {
  const auto throws = [](auto change) {
    PersonSegmentOptions o;
    change(o);
    EXPECT_THROW(o.Check(), CheckError);
  };
  EXPECT_NO_THROW(PersonSegmentOptions().Check());
  throws([](PersonSegmentOptions& o) { o.min_depth_m = 5, o.max_depth_m = 4; });
  throws([](PersonSegmentOptions& o) { o.floor_max_tilt_deg = 90; });
  throws([](PersonSegmentOptions& o) { o.floor_sample_stride_px = 0; });
  throws([](PersonSegmentOptions& o) { o.floor_fit = {0, 0}; });
  throws([](PersonSegmentOptions& o) { o.floor_min_inliers = 2; });
  throws([](PersonSegmentOptions& o) { o.floor_keep_ratio = 0; });
  throws([](PersonSegmentOptions& o) { o.depth_step = {-0.01, 0.01}; });
  throws([](PersonSegmentOptions& o) { o.seed_step_px = 0.1; });
  throws([](PersonSegmentOptions& o) { o.body_margin_m = 0; });
  throws([](PersonSegmentOptions& o) { o.core_radius_m = 0.5; });
  throws([](PersonSegmentOptions& o) { o.max_hole_run_px = -1; });
  throws([](PersonSegmentOptions& o) { o.hole_person_ratio = 0; });
  throws([](PersonSegmentOptions& o) {
    o.seed_in_front_m = std::numeric_limits<double>::quiet_NaN();
  });
  EXPECT_THROW(PersonSegmenter(Scene().sensor_camera(), 0), CheckError);
  EXPECT_THROW(PersonSegmenter(PinholeCamera{}, 0.001), CheckError);
}

TEST(PixelRays, PointsProjectBackToTheirPixelWithDistortion) {
  PinholeCamera camera = PinholeCamera::KinectLike();
  camera.distortion = {0.2, -0.5, 0.001, -0.002, 0.3};  // Freiburg 1-like
  const PixelRays rays(camera);
  for (const auto& [x, y] : {std::pair{0, 0}, {639, 0}, {320, 240}, {17, 460}, {600, 300}}) {
    const Eigen::Vector3d p = rays.Point(x, y, 2.5);
    EXPECT_DOUBLE_EQ(p.z(), 2.5);
    const auto uv = camera.Project(p);
    ASSERT_TRUE(uv);
    EXPECT_NEAR(uv->x(), x, 1e-3);
    EXPECT_NEAR(uv->y(), y, 1e-3);
  }
}

}  // namespace
}  // namespace reenact::capture

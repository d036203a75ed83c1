// tum: source: the real sequence ../shared/data/tum-fr1-rpy-head (first 60 pairs of TUM's
// freiburg1_rpy with its ground truth), and constructed sequences for the geometry and the
// bad input.
#include "capture-client/source/tum_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "capture-client/source/frame_source.h"
#include "common/geometry/rotation.h"
#include "tests/unit/capture-client/source_test_util.h"

namespace reenact::capture {
namespace {

using testing::PlainTumFrame;
namespace fs = std::filesystem;
using testing::TempDir;
using testing::TumTestFrame;
using testing::WriteTumSequence;

fs::path RealTum() { return testing::SharedData("tum-fr1-rpy-head"); }

#define REQUIRE_REAL_TUM()                                     \
  do {                                                         \
    if (!fs::exists(RealTum())) {                              \
      GTEST_SKIP() << RealTum() << " is absent (shared data)"; \
    }                                                          \
  } while (0)

struct GtLine {
  double t;
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

// groundtruth.txt read independently of the code under test.
std::vector<GtLine> ReadGroundTruthLines(const fs::path& file) {
  std::vector<GtLine> lines;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    GtLine g;
    double x, y, z, qx, qy, qz, qw;
    s >> g.t >> x >> y >> z >> qx >> qy >> qz >> qw;
    g.p = {x, y, z};
    g.q = Eigen::Quaterniond(qw, qx, qy, qz).normalized();
    lines.push_back(g);
  }
  return lines;
}

TEST(TumSource, ReadsTheRealSequence) {
  REQUIRE_REAL_TUM();
  auto source = TumSource::OpenSpec(RealTum().string());  // fr1 detected from the name
  ASSERT_TRUE(source.ok()) << source.error().message;
  TumSource& tum = **source;
  EXPECT_EQ(tum.camera(), TumCamera::kFreiburg1);
  const SensorInfo& info = tum.info();
  EXPECT_EQ(info.frame_count, 60);
  EXPECT_NEAR(info.frame_rate_hz, 30, 2);
  // Undistorted: the Freiburg 1 K of the data README, distortion removed.
  EXPECT_DOUBLE_EQ(info.color_camera.fx, 517.3);
  EXPECT_DOUBLE_EQ(info.color_camera.cy, 255.3);
  EXPECT_TRUE(info.color_camera.distortion.IsZero());
  EXPECT_NE(info.description.find("undistorted"), std::string::npos);
  ASSERT_TRUE(tum.has_ground_truth());

  const std::vector<GtLine> gt = ReadGroundTruthLines(RealTum() / "groundtruth.txt");
  ASSERT_GT(gt.size(), 100u);
  int frames = 0;
  double last_t = -1;
  while (true) {
    auto next = tum.Next();
    ASSERT_TRUE(next.ok()) << next.error().message;
    if (!next->has_value()) break;
    const SensorFrame& f = **next;
    EXPECT_EQ(f.color.width, 640);
    EXPECT_EQ(f.depth.height, 480);
    EXPECT_GT(f.timestamp_s, last_t);
    last_t = f.timestamp_s;
    EXPECT_FALSE(f.world_from_sensor.has_value());  // ground truth is not a tracked pose
    size_t valid = 0, plausible = 0;
    for (uint16_t d : f.depth.data) {
      valid += d > 0;
      plausible += d >= 500 && d <= 8000;
    }
    EXPECT_GT(valid, f.depth.data.size() / 2);
    EXPECT_GT(plausible, valid * 9 / 10);

    // Ground truth: between the two groundtruth.txt lines around the frame's time, so no
    // farther from the nearer of them than half the step between them (in position and
    // angle), up to rounding.
    const auto& pose = tum.ground_truth()[frames];
    ASSERT_TRUE(pose.has_value()) << "frame " << frames;
    size_t b = 0;
    while (b < gt.size() && gt[b].t <= f.timestamp_s) ++b;
    ASSERT_TRUE(b > 0 && b < gt.size());
    const GtLine& lo = gt[b - 1];
    const GtLine& hi = gt[b];
    const GtLine& nearest = f.timestamp_s - lo.t < hi.t - f.timestamp_s ? lo : hi;
    EXPECT_LE((pose->translation() - nearest.p).norm(), 0.5 * (hi.p - lo.p).norm() + 1e-9);
    const double step_angle = lo.q.angularDistance(hi.q);
    EXPECT_LE(RotationAngle(pose->linear() * nearest.q.toRotationMatrix().transpose()),
              0.5 * step_angle + 1e-6);
    // And on the chord between them.
    EXPECT_NEAR((pose->translation() - lo.p).norm() + (pose->translation() - hi.p).norm(),
                (hi.p - lo.p).norm(), 1e-9);
    ++frames;
  }
  EXPECT_EQ(frames, 60);
}

TEST(TumSource, UndistortionMovesAPixelWhereThePinholeModelSays) {
  // A scene point seen by the distorted Freiburg 1 camera at Project(P) (Brown-Conrady) must
  // appear at K (X/Z, Y/Z) in the undistorted colour image. The colour image is black with a
  // 5x5 white square around Project(P); the undistorted square's centroid is measured.
  const PinholeCamera fr1 = TumColorCamera(TumCamera::kFreiburg1);
  const Eigen::Vector3d point(-0.55, -0.4, 1.0);  // towards the top-left corner
  const Eigen::Vector2d distorted = *fr1.Project(point);
  ASSERT_TRUE(distorted.x() > 5 && distorted.y() > 5) << distorted.transpose();
  PinholeCamera pinhole = fr1;
  pinhole.distortion = {};
  const Eigen::Vector2d undistorted = *pinhole.Project(point);
  ASSERT_GT((distorted - undistorted).norm(), 8);  // the test needs a visible displacement

  TumTestFrame frame = PlainTumFrame(1.0, 5000);
  frame.bgr.setTo(cv::Scalar::all(0));
  const int u = static_cast<int>(std::lround(distorted.x())),
            v = static_cast<int>(std::lround(distorted.y()));
  frame.bgr(cv::Rect(u - 2, v - 2, 5, 5)).setTo(cv::Scalar::all(255));
  TempDir tmp;
  WriteTumSequence(tmp.path() / "seq", {frame});
  auto source = OpenFrameSource("tum:" + (tmp.path() / "seq").string() + "?camera=fr1");
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_TRUE(next.ok()) << next.error().message;
  const ImageRgb8& color = (*next)->color;
  double sum = 0, sx = 0, sy = 0;
  for (int y = 0; y < color.height; ++y)
    for (int x = 0; x < color.width; ++x) {
      const double w = color.at(x, y, 0);
      sum += w;
      sx += w * x;
      sy += w * y;
    }
  ASSERT_GT(sum, 0);
  // The square is centred on the rounded pixel: expect the model's position of that pixel.
  const Eigen::Vector2d rounded_source(u, v);
  const Eigen::Vector2d expected =
      Eigen::Vector2d(fr1.fx, fr1.fy).cwiseProduct(fr1.Undistort(rounded_source)) +
      Eigen::Vector2d(fr1.cx, fr1.cy);
  EXPECT_NEAR(sx / sum, expected.x(), 0.5);
  EXPECT_NEAR(sy / sum, expected.y(), 0.5);
  EXPECT_NEAR(expected.x(), undistorted.x(), 1.0);
  // Depth is left as recorded (TumSource header): still 5000 / 5 mm everywhere.
  EXPECT_EQ((*next)->depth.at(0, 0), 1000);
  EXPECT_EQ((*next)->depth.at(639, 479), 1000);
}

TEST(TumSource, UndistortBothKeepsDepthOnTheColourGrid) {
  // A depth step drawn where a colour edge is: after undistort=both, both move together.
  TumTestFrame frame = PlainTumFrame(1.0, 0);
  frame.bgr.setTo(cv::Scalar::all(0));
  frame.bgr(cv::Rect(0, 0, 100, 480)).setTo(cv::Scalar::all(255));
  frame.depth(cv::Rect(0, 0, 100, 480)).setTo(cv::Scalar(10000));
  TempDir tmp;
  WriteTumSequence(tmp.path() / "seq", {frame});
  auto source =
      OpenFrameSource("tum:" + (tmp.path() / "seq").string() + "?camera=fr1&undistort=both");
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_TRUE(next.ok()) << next.error().message;
  const SensorFrame& f = **next;
  int disagree = 0, edge_moved = 0;
  for (int y = 100; y < 380; ++y)
    for (int x = 0; x < 200; ++x) {
      const bool bright = f.color.at(x, y, 0) > 127, near = f.depth.at(x, y) == 2000;
      disagree += bright != near;
      edge_moved += (x < 100) != bright;
    }
  EXPECT_GT(edge_moved, 280);    // the edge did move (by several pixels per row)
  EXPECT_LT(disagree, 2 * 280);  // depth followed to within a pixel per row
}

TEST(TumSource, AssociatesRgbAndDepthListsByTimestamp) {
  // Depth 5 ms after each colour image, except the third, whose depth was taken long after:
  // that colour image and that depth map have no partner within 20 ms and are left out.
  std::vector<TumTestFrame> frames;
  for (int i = 0; i < 5; ++i) frames.push_back(PlainTumFrame(100 + i / 30.0, 5000 + i));
  frames[2].depth_time = 200;
  TempDir tmp;
  const fs::path dir = tmp.path() / "rgbd_dataset_freiburg2_test";  // fr2 from the name
  WriteTumSequence(dir, frames);
  auto source = TumSource::Open(dir, {});
  ASSERT_TRUE(source.ok()) << source.error().message;
  EXPECT_EQ((*source)->camera(), TumCamera::kFreiburg2);
  EXPECT_EQ((*source)->frames().listed_in, "rgb.txt + depth.txt");
  std::vector<int> depth_mm;
  while (true) {
    auto next = (*source)->Next();
    ASSERT_TRUE(next.ok()) << next.error().message;
    if (!next->has_value()) break;
    depth_mm.push_back((*next)->depth.at(320, 240));
    EXPECT_FALSE((*source)->has_ground_truth());
  }
  // (5000 + i) / 5 rounded, i = 0, 1, 3, 4.
  EXPECT_EQ(depth_mm, (std::vector<int>{1000, 1000, 1001, 1001}));
}

TEST(TumSource, DepthUnitsBecomeMillimetres) {
  TumTestFrame frame = PlainTumFrame(1.0, 0);
  const uint16_t values[] = {0, 5, 12, 13, 5000, 65535};
  for (int i = 0; i < 6; ++i) frame.depth.at<uint16_t>(0, i) = values[i];
  TempDir tmp;
  WriteTumSequence(tmp.path() / "fr3_seq", {frame});
  auto source = OpenFrameSource("tum:" + (tmp.path() / "fr3_seq").string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_TRUE(next.ok()) << next.error().message;
  const int expected[] = {0, 1, 2, 3, 1000, 13107};  // value / 5, rounded
  for (int i = 0; i < 6; ++i) EXPECT_EQ((*next)->depth.at(i, 0), expected[i]) << values[i];
}

TEST(TumSourceBadInput, ListedImageMissing) {
  std::vector<TumTestFrame> frames = {PlainTumFrame(1.0, 5000), PlainTumFrame(1.1, 5000)};
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_desk";
  WriteTumSequence(dir, frames);
  fs::remove(dir / "rgb" / "1.100000.png");
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "not_found");
  EXPECT_NE(source.error().message.find("rgb/1.100000.png"), std::string::npos)
      << source.error().message;
  EXPECT_NE(source.error().message.find("rgb.txt"), std::string::npos);
  EXPECT_NE(source.error().message.find("unpack it again"), std::string::npos);
}

TEST(TumSourceBadInput, NoAssociationsAndNoRgbList) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_empty";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000)});
  fs::remove(dir / "rgb.txt");
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "not_found");
  EXPECT_NE(source.error().message.find("no associations.txt and no rgb.txt"), std::string::npos)
      << source.error().message;
  auto absent = OpenFrameSource("tum:" + (tmp.path() / "nowhere_fr1").string());
  ASSERT_FALSE(absent.ok());
  EXPECT_EQ(absent.error().code, "not_found");
}

TEST(TumSourceBadInput, ColourAndDepthSizesDiffer) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_small_depth";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000, 320, 240)});
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error().code, "corrupt");
  EXPECT_NE(next.error().message.find("colour is 640x480 but depth is 320x240"), std::string::npos)
      << next.error().message;
}

TEST(TumSourceBadInput, AllZeroDepthIsAnError) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_no_depth";
  std::vector<TumTestFrame> frames;
  for (int i = 0; i < 3; ++i) frames.push_back(PlainTumFrame(1.0 + i / 30.0, 0));
  WriteTumSequence(dir, frames);
  // A stream shorter than the leading-frame limit: its frames come, then the end is an error.
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  int yielded = 0;
  Error error;
  while (true) {
    auto next = (*source)->Next();
    if (!next.ok()) {
      error = next.error();
      break;
    }
    ASSERT_TRUE(next->has_value()) << "the stream ended without an error";
    ++yielded;
  }
  EXPECT_EQ(yielded, 3);
  EXPECT_EQ(error.code, "no_depth");
  EXPECT_NE(error.message.find("no depth reading"), std::string::npos) << error.message;
  // With a limit of 2 frames, the error comes at the second.
  TumSourceOptions options;
  options.max_leading_empty_depth_frames = 2;
  auto limited = TumSource::Open(dir, options);
  ASSERT_TRUE(limited.ok());
  ASSERT_TRUE((*limited)->Next().ok());
  auto second = (*limited)->Next();
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.error().code, "no_depth");
}

TEST(TumSourceBadInput, ZeroDepthAfterValidDepthPassesThrough) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_covered";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000), PlainTumFrame(1.1, 0), PlainTumFrame(1.2, 0)});
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_TRUE(source.ok());
  for (int i = 0; i < 3; ++i) ASSERT_TRUE((*source)->Next().ok()) << i;
  auto end = (*source)->Next();
  ASSERT_TRUE(end.ok());
  EXPECT_FALSE(end->has_value());
}

TEST(TumSourceBadInput, CameraNeitherNamedNorDetectable) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "my_sequence";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000)});
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "usage");
  EXPECT_NE(source.error().message.find("camera=fr1"), std::string::npos) << source.error().message;
  auto bad = OpenFrameSource("tum:" + dir.string() + "?camera=kinect");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("fr1, fr2 or fr3"), std::string::npos);
  EXPECT_TRUE(OpenFrameSource("tum:" + dir.string() + "?camera=freiburg3").ok());
}

TEST(TumSourceBadInput, MalformedListsNameTheLine) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_bad";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000)});
  std::ofstream(dir / "rgb.txt", std::ios::app) << "1.5\n";  // line 5: no file name
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "corrupt");
  EXPECT_NE(source.error().message.find("rgb.txt line 5"), std::string::npos)
      << source.error().message;

  const fs::path dir2 = tmp.path() / "fr1_bad_gt";
  WriteTumSequence(dir2, {PlainTumFrame(1.0, 5000)});
  testing::WriteText(dir2 / "groundtruth.txt",
                     "# ground truth\n0.9 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 0 2\n");
  auto gt = OpenFrameSource("tum:" + dir2.string());
  ASSERT_FALSE(gt.ok());
  EXPECT_EQ(gt.error().code, "corrupt");
  EXPECT_NE(gt.error().message.find("groundtruth.txt line 3"), std::string::npos)
      << gt.error().message;
  EXPECT_NE(gt.error().message.find("unit quaternion"), std::string::npos);
}

TEST(TumSourceBadInput, UndecodableImage) {
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_broken_png";
  WriteTumSequence(dir, {PlainTumFrame(1.0, 5000)});
  testing::WriteText(dir / "depth" / "1.005000.png", "not a png");
  auto source = OpenFrameSource("tum:" + dir.string());
  ASSERT_TRUE(source.ok()) << source.error().message;
  auto next = (*source)->Next();
  ASSERT_FALSE(next.ok());
  EXPECT_EQ(next.error().code, "corrupt");
  EXPECT_NE(next.error().message.find("depth/1.005000.png"), std::string::npos)
      << next.error().message;
}

TEST(TumSource, GroundTruthMatchesInterpolationOfConstructedMotion) {
  // Motion capture at 100 Hz of a camera moving along x at 1 m/s and turning about y at
  // 1 rad/s; frames at 1/30 s. Interpolation of a constant-velocity motion is exact.
  TempDir tmp;
  const fs::path dir = tmp.path() / "fr1_motion";
  std::vector<TumTestFrame> frames;
  for (int i = 0; i < 4; ++i) frames.push_back(PlainTumFrame(10 + i / 30.0, 5000));
  WriteTumSequence(dir, frames);
  std::ofstream gt(dir / "groundtruth.txt");
  gt.precision(17);
  for (int k = 0; k <= 20; ++k) {
    const double t = 9.99 + k * 0.01, s = t - 10;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(s, Eigen::Vector3d::UnitY()));
    gt << t << " " << s << " 0 1.5 " << q.x() << " " << q.y() << " " << q.z() << " " << q.w()
       << "\n";
  }
  gt.close();
  auto source = TumSource::Open(dir, {});
  ASSERT_TRUE(source.ok()) << source.error().message;
  for (int i = 0; i < 4; ++i) {
    const auto& pose = (*source)->ground_truth()[i];
    ASSERT_TRUE(pose.has_value());
    const double s = (*source)->frames().frames[i].color_time_s - 10;
    EXPECT_NEAR((pose->translation() - Eigen::Vector3d(s, 0, 1.5)).norm(), 0, 1e-9);
    EXPECT_NEAR(RotationAngle(
                    pose->linear() *
                    Eigen::AngleAxisd(s, Eigen::Vector3d::UnitY()).toRotationMatrix().transpose()),
                0, 1e-9);
  }
}

}  // namespace
}  // namespace reenact::capture

// The synthetic viewer camera (viewer-client/camera/synthetic_camera_source.h): its path is
// checked against the construction it documents (turn about the subject's vertical, the
// sensor's distance and height, aimed at the subject), its frames against the scene, and every
// bad spec is refused with a message that names the problem.
#include "viewer-client/camera/synthetic_camera_source.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/geometry/pinhole_camera.h"

namespace reenact::viewer {
namespace {

const capture::SyntheticScene& Scene() {
  static const capture::SyntheticScene scene =
      capture::SyntheticScene::Create("turn-and-kick").value();
  return scene;
}

// Signed angle (degrees) about +z from a to b, both projected on the floor.
double YawDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.x() * b.x() + a.y() * b.y()) * 180 /
         std::numbers::pi;
}

TEST(SyntheticViewerPath, TurnsAboutTheSubjectAtTheSensorsDistanceAndHeight) {
  const capture::SyntheticScene& scene = Scene();
  const int n = 41;  // k = 10: +D, k = 30: -D
  const double max_deg = 40;
  const SyntheticViewerPath path = MakeSyntheticViewerPath(scene, n, max_deg);
  ASSERT_EQ(path.world_from_viewer.size(), 41u);
  const Eigen::Vector3d centre = scene.skeleton_in_world(0)[Joint::kWaist];
  const Eigen::Vector3d eye0 = scene.world_from_sensor(0).translation();
  const Eigen::Vector3d r0 = eye0 - centre;
  // Bob 1.2 cm, shake 3 mm per axis: the eye stays within 2 cm of the ideal circle.
  for (int k : {0, 10, 20, 30, 40}) {
    const Eigen::Vector3d eye = path.world_from_viewer[k].translation();
    const Eigen::Vector3d r = eye - centre;
    EXPECT_NEAR(r.head<2>().norm(), r0.head<2>().norm(), 0.02) << k;
    EXPECT_NEAR(eye.z(), eye0.z(), 0.02) << k;
    EXPECT_NEAR(YawDeg(r0, r), path.angle_deg[k], 0.5) << k;
    // Aimed at the subject: the centre projects near the principal point (0.3 degrees of
    // shake per axis is about 3 pixels at fx 525; the bob tilts nothing).
    const Eigen::Vector3d in_camera = path.world_from_viewer[k].inverse() * centre;
    ASSERT_GT(in_camera.z(), 0);
    const std::optional<Eigen::Vector2d> px = scene.sensor_camera().Project(in_camera);
    ASSERT_TRUE(px.has_value()) << k;
    EXPECT_NEAR(px->x(), scene.sensor_camera().cx, 12) << k;
    EXPECT_NEAR(px->y(), scene.sensor_camera().cy, 12) << k;
  }
  EXPECT_NEAR(path.angle_deg[10], 40, 1e-9);
  EXPECT_NEAR(path.angle_deg[30], -40, 1e-9);
  EXPECT_NEAR(path.angle_deg[20], 0, 1e-9);
}

TEST(SyntheticViewerPath, RefusesDegenerateArguments) {
  EXPECT_THROW(MakeSyntheticViewerPath(Scene(), 1, 45), CheckError);
  EXPECT_THROW(MakeSyntheticViewerPath(Scene(), 10, 0), CheckError);
  EXPECT_THROW(MakeSyntheticViewerPath(Scene(), 10, NAN), CheckError);
}

TEST(SyntheticCamera, DeliversTheSpecsFramesWithTheirTruth) {
  auto source = OpenCameraSource("synthetic:turn-and-kick?frames=3&max_deg=20", std::nullopt);
  ASSERT_TRUE(source.ok()) << source.error().message;
  EXPECT_NE((*source)->description().find("turn-and-kick"), std::string::npos);
  const PinholeCamera& camera = (*source)->camera();
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(camera.height, 480);
  const SyntheticViewerPath path = MakeSyntheticViewerPath(Scene(), 3, 20);
  for (int k = 0; k < 3; ++k) {
    auto frame = (*source)->Next();
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    ASSERT_TRUE(frame->has_value());
    EXPECT_DOUBLE_EQ((*frame)->timestamp_s, k / Scene().frame_rate_hz());
    ASSERT_TRUE((*frame)->true_world_from_viewer.has_value());
    EXPECT_TRUE((*frame)->true_world_from_viewer->isApprox(path.world_from_viewer[k], 1e-12));
    EXPECT_EQ((*frame)->color.width, 640);
    EXPECT_EQ((*frame)->color.channels, 3);
  }
  auto end = (*source)->Next();
  ASSERT_TRUE(end.ok());
  EXPECT_FALSE(end->has_value());
}

// The room alone by default: the same picture as with the subject wherever the subject is not,
// and another one where it is.
TEST(SyntheticCamera, ShowsTheRoomWithoutTheSubjectUnlessAsked) {
  auto empty = OpenCameraSource("synthetic:turn-and-kick?frames=2", std::nullopt);
  auto with = OpenCameraSource("synthetic:turn-and-kick?frames=2&subject=1", std::nullopt);
  ASSERT_TRUE(empty.ok() && with.ok());
  const CameraFrame a = *(*empty)->Next().value(), b = *(*with)->Next().value();
  const capture::SyntheticView truth =
      Scene().Render(0, Scene().sensor_camera(), *a.true_world_from_viewer);
  int subject = 0, subject_differs = 0, room_differs = 0;
  for (size_t i = 0; i < truth.mask.data.size(); ++i) {
    const bool differs = a.color.data[3 * i] != b.color.data[3 * i] ||
                         a.color.data[3 * i + 1] != b.color.data[3 * i + 1] ||
                         a.color.data[3 * i + 2] != b.color.data[3 * i + 2];
    if (truth.mask.data[i]) {
      ++subject;
      subject_differs += differs;
    } else {
      room_differs += differs;
    }
  }
  EXPECT_GT(subject, 5000);  // a person 3 m away fills a good part of 640x480
  EXPECT_EQ(room_differs, 0);
  EXPECT_GT(subject_differs, subject * 9 / 10);
}

void ExpectUsage(const std::string& spec, const std::string& says,
                 const std::string& code = "usage") {
  auto source = OpenCameraSource(spec, std::nullopt);
  ASSERT_FALSE(source.ok()) << spec;
  EXPECT_EQ(source.error().code, code) << spec << ": " << source.error().message;
  EXPECT_NE(source.error().message.find(says), std::string::npos)
      << spec << ": " << source.error().message;
  EXPECT_EQ(source.error().message.find('\n'), std::string::npos) << source.error().message;
}

TEST(SyntheticCamera, BadSpecsAreRefused) {
  ExpectUsage("synthetic:", "needs a scenario");
  ExpectUsage("synthetic:?frames=3", "needs a scenario");
  ExpectUsage("synthetic:turn-and-kick?fps=3", "fps");
  ExpectUsage("synthetic:turn-and-kick?frames", "NAME=VALUE");
  ExpectUsage("synthetic:turn-and-kick?frames=3&frames=4", "given twice");
  ExpectUsage("synthetic:turn-and-kick?frames=1", "frames=1");
  ExpectUsage("synthetic:turn-and-kick?frames=ten", "whole number");
  ExpectUsage("synthetic:turn-and-kick?max_deg=0", "(0, 90]");
  ExpectUsage("synthetic:turn-and-kick?max_deg=91", "(0, 90]");
  ExpectUsage("synthetic:turn-and-kick?max_deg=nan", "(0, 90]");
  ExpectUsage("synthetic:turn-and-kick?subject=maybe", "subject");
  ExpectUsage("synthetic:turn-and-kick?seed=-1", "seed");
  ExpectUsage("synthetic:turn-and-kick?body_height=1.7", "body=FILE.glb");
  ExpectUsage("synthetic:no-such-scene", "turn-and-kick", "not_found");
}

TEST(SyntheticCamera, RefusesACalibrationFile) {
  auto source = OpenCameraSource("synthetic:turn-and-kick", std::filesystem::path("k.yaml"));
  ASSERT_FALSE(source.ok());
  EXPECT_EQ(source.error().code, "usage");
  EXPECT_NE(source.error().message.find("--calibration"), std::string::npos);
}

}  // namespace
}  // namespace reenact::viewer

// Viewer camera sources and calibration files: the TUM sequence in ../shared/data, files
// written by the test, and every bad input refused with a message that says what is wrong.
#include "viewer-client/camera/camera_source.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "viewer-client/camera/camera_calibration.h"
#include "viewer-client/camera/tum_directory_source.h"
#include "viewer-client/camera/video_capture_source.h"

namespace reenact::viewer {
namespace {

namespace fs = std::filesystem;

const fs::path kTum = fs::path(REENACT_SHARED_DATA_DIR) / "tum-fr1-rpy-head";
const fs::path kCalibration = fs::path(REENACT_SOURCE_DIR) / "docs" / "calibration";

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("reenact_camera_test_" + std::to_string(::getpid()) + "_" + std::to_string(next_++));
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }
  fs::path Write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ / name) << text;
    return path_ / name;
  }

 private:
  static inline int next_ = 0;
  fs::path path_;
};

void ExpectError(const Error& e, const std::string& code, const std::string& says) {
  EXPECT_EQ(e.code, code) << e.message;
  EXPECT_NE(e.message.find(says), std::string::npos) << e.message;
}

// The TUM fr1 values of the benchmark's page (also in capture-client/source/tum_camera.h).
TEST(CameraCalibration, ReadsTheTumFr1YamlFile) {
  const auto c = LoadCameraCalibration(kCalibration / "tum-fr1.yaml");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->width, 640);
  EXPECT_EQ(c->height, 480);
  EXPECT_DOUBLE_EQ(c->fx, 517.3);
  EXPECT_DOUBLE_EQ(c->fy, 516.5);
  EXPECT_DOUBLE_EQ(c->cx, 318.6);
  EXPECT_DOUBLE_EQ(c->cy, 255.3);
  EXPECT_DOUBLE_EQ(c->distortion.k1, 0.2624);
  EXPECT_DOUBLE_EQ(c->distortion.k3, 1.1633);
}

TEST(CameraCalibration, ReadsJsonAndAbsentDistortion) {
  const auto json = LoadCameraCalibration(kCalibration / "kinect-like.json");
  ASSERT_TRUE(json.ok()) << json.error().message;
  const PinholeCamera k = PinholeCamera::KinectLike();
  EXPECT_DOUBLE_EQ(json->fx, k.fx);
  EXPECT_DOUBLE_EQ(json->cy, k.cy);
  EXPECT_TRUE(json->distortion.IsZero());
  const auto fr3 = LoadCameraCalibration(kCalibration / "tum-fr3.yaml");
  ASSERT_TRUE(fr3.ok()) << fr3.error().message;
  EXPECT_TRUE(fr3->distortion.IsZero());
  EXPECT_DOUBLE_EQ(fr3->fy, 539.2);
}

TEST(CameraCalibration, BadFilesAreRefused) {
  TempDir dir;
  ExpectError(LoadCameraCalibration(dir.path() / "absent.yaml").error(), "not_found",
              "does not exist");
  ExpectError(LoadCameraCalibration(dir.Write("junk.yaml", "this: [is: not")).error(), "corrupt",
              "junk.yaml");
  const std::string size = "%YAML:1.0\nimage_width: 640\nimage_height: 480\n";
  const std::string k33 =
      "camera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n"
      "  data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n";
  ExpectError(LoadCameraCalibration(dir.Write("nok.yaml", size)).error(), "corrupt",
              "camera_matrix");
  ExpectError(LoadCameraCalibration(dir.Write("nosize.yaml", "%YAML:1.0\n" + k33)).error(),
              "corrupt", "image_width");
  ExpectError(LoadCameraCalibration(
                  dir.Write("k22.yaml", size + "camera_matrix: !!opencv-matrix\n  rows: 2\n"
                                               "  cols: 2\n  dt: d\n  data: [1., 0., 0., 1.]\n"))
                  .error(),
              "corrupt", "3x3");
  ExpectError(
      LoadCameraCalibration(
          dir.Write("negf.yaml",
                    size + "camera_matrix: !!opencv-matrix\n  rows: 3\n  cols: 3\n"
                           "  dt: d\n  data: [ -500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"))
          .error(),
      "corrupt", "fx, fy > 0");
  ExpectError(LoadCameraCalibration(
                  dir.Write("d3.yaml", size + k33 +
                                           "distortion_coefficients: !!opencv-matrix\n  rows: 1\n"
                                           "  cols: 3\n  dt: d\n  data: [ 0.1, 0.2, 0.3 ]\n"))
                  .error(),
              "corrupt", "4, 5 or 8");
  ExpectError(LoadCameraCalibration(
                  dir.Write("d8.yaml",
                            size + k33 +
                                "distortion_coefficients: !!opencv-matrix\n  rows: 1\n"
                                "  cols: 8\n  dt: d\n  data: [ 0.1, 0.2, 0, 0, 0.3, 0.5, 0, 0 ]\n"))
                  .error(),
              "unsupported", "k4-k6");
}

TEST(CameraSource, ReadsTheTumSequenceInTimeOrder) {
  if (!fs::exists(kTum)) GTEST_SKIP() << "no " << kTum;
  auto source = OpenCameraSource("tum:" + kTum.string(), kCalibration / "tum-fr1.yaml");
  ASSERT_TRUE(source.ok()) << source.error().message;
  EXPECT_EQ((*source)->camera().width, 640);
  double last = 0;
  for (int i = 0; i < 3; ++i) {
    auto frame = (*source)->Next();
    ASSERT_TRUE(frame.ok()) << frame.error().message;
    ASSERT_TRUE(frame->has_value());
    EXPECT_EQ((*frame)->color.width, 640);
    EXPECT_EQ((*frame)->color.channels, 3);
    EXPECT_GT((*frame)->timestamp_s, last);
    last = (*frame)->timestamp_s;
  }
  const auto listed = ReadTumColorFrames(kTum);
  ASSERT_TRUE(listed.ok());
  EXPECT_GT(listed->size(), 3u);
}

TEST(CameraSource, TumDirectoryBadInput) {
  TempDir dir;
  const PinholeCamera camera = PinholeCamera::KinectLike();
  ExpectError(ReadTumColorFrames(dir.path() / "absent").error(), "not_found", "does not exist");
  ExpectError(ReadTumColorFrames(dir.path()).error(), "not_found", "rgb.txt");
  dir.Write("rgb.txt", "# comment\n");
  ExpectError(ReadTumColorFrames(dir.path()).error(), "empty", "no frame");
  dir.Write("rgb.txt", "1.0 rgb/a.png\n0.5 rgb/b.png\n");
  ExpectError(ReadTumColorFrames(dir.path()).error(), "corrupt", "line 2");
  dir.Write("rgb.txt", "one rgb/a.png\n");
  ExpectError(ReadTumColorFrames(dir.path()).error(), "corrupt", "finite");
  dir.Write("rgb.txt", "1.0\n");
  ExpectError(ReadTumColorFrames(dir.path()).error(), "corrupt", "line 1");
  // A listed image that is missing, then one of the wrong size.
  dir.Write("rgb.txt", "1.0 missing.png\n2.0 small.png\n");
  cv::imwrite((dir.path() / "small.png").string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(1)));
  auto source = OpenTumDirectorySource(dir.path(), camera);
  ASSERT_TRUE(source.ok()) << source.error().message;
  ExpectError((*source)->Next().error(), "corrupt", "missing.png");
  ExpectError((*source)->Next().error(), "invalid_argument", "320x240");
  auto end = (*source)->Next();
  ASSERT_TRUE(end.ok());
  EXPECT_FALSE(end->has_value());
}

TEST(CameraSource, VideoFileFrames) {
  TempDir dir;
  const fs::path file = dir.path() / "clip.avi";
  {
    cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10,
                           cv::Size(640, 480));
    ASSERT_TRUE(writer.isOpened());
    for (int i = 0; i < 4; ++i) writer.write(cv::Mat(480, 640, CV_8UC3, cv::Scalar(40 * i, 0, 0)));
  }
  auto source = OpenCameraSource("video:" + file.string(), kCalibration / "kinect-like.json");
  ASSERT_TRUE(source.ok()) << source.error().message;
  int frames = 0;
  while (true) {
    auto f = (*source)->Next();
    ASSERT_TRUE(f.ok()) << f.error().message;
    if (!f->has_value()) break;
    EXPECT_EQ((*f)->color.height, 480);
    ++frames;
  }
  EXPECT_EQ(frames, 4);
  // The same video against a calibration of another size: refused per frame.
  const fs::path small = dir.Write(
      "small.yaml",
      "%YAML:1.0\nimage_width: 320\nimage_height: 240\ncamera_matrix: !!opencv-matrix\n"
      "  rows: 3\n  cols: 3\n  dt: d\n  data: [ 250., 0., 160., 0., 250., 120., 0., 0., 1. ]\n");
  auto other = OpenCameraSource("video:" + file.string(), small);
  ASSERT_TRUE(other.ok()) << other.error().message;
  ExpectError((*other)->Next().error(), "invalid_argument", "640x480");
}

TEST(CameraSource, BadSpecsAndFiles) {
  TempDir dir;
  const fs::path calib = kCalibration / "kinect-like.json";
  ExpectError(OpenCameraSource("webcam", calib).error(), "usage", "unknown camera");
  ExpectError(OpenCameraSource("tum:", calib).error(), "usage", "needs a path");
  ExpectError(OpenCameraSource("live:x", calib).error(), "usage", "camera number");
  ExpectError(OpenCameraSource("video:" + (dir.path() / "a.mp4").string(), std::nullopt).error(),
              "usage", "--calibration");
  ExpectError(OpenCameraSource("video:" + (dir.path() / "a.mp4").string(), calib).error(),
              "not_found", "does not exist");
  const fs::path text = dir.Write("notavideo.mp4", "hello");
  EXPECT_FALSE(OpenCameraSource("video:" + text.string(), calib).ok());
  ExpectError(OpenCameraSource("tum:" + dir.path().string(), std::nullopt).error(), "usage",
              "--calibration");
}

// No camera is attached on the build machines: the error must say so, not crash. (Where a
// camera is attached this test opens it and expects frames of the calibration's size.)
TEST(CameraSource, LiveCameraWithoutDeviceIsAClearError) {
  auto live = OpenCameraSource("live:57", kCalibration / "kinect-like.json");
  ASSERT_FALSE(live.ok());
  EXPECT_EQ(live.error().code, "unavailable");
  EXPECT_NE(live.error().message.find("camera 57"), std::string::npos) << live.error().message;
}

}  // namespace
}  // namespace reenact::viewer

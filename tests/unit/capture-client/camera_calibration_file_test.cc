// ReadCameraCalibrationFile: OpenCV FileStorage files written by cv::FileStorage itself (YAML
// and JSON), hand-written YAML without the %YAML line, the plain camera.json form, and one
// test per malformed key.
#include "capture-client/source/camera_calibration_file.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "tests/unit/capture-client/source_test_util.h"

namespace reenact::capture {
namespace {

using testing::TempDir;
using testing::WriteText;
namespace fs = std::filesystem;

// An OpenCV calibration as cv::FileStorage writes it (the layout of OpenCV's own tools).
void WriteOpenCvCalibration(const fs::path& file, const cv::Mat& k, const cv::Mat& d) {
  cv::FileStorage out(file.string(), cv::FileStorage::WRITE);
  out << "image_width" << 640 << "image_height" << 480;
  out << "camera_matrix" << k << "distortion_coefficients" << d;
}

cv::Mat FreiburgK() {
  return (cv::Mat_<double>(3, 3) << 517.3, 0, 318.6, 0, 516.5, 255.3, 0, 0, 1);
}
cv::Mat FreiburgD() { return (cv::Mat_<double>(1, 5) << 0.2624, -0.9531, -0.0054, 0.0026, 1.1633); }

void ExpectFreiburg(const PinholeCamera& c) {
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_DOUBLE_EQ(c.fx, 517.3);
  EXPECT_DOUBLE_EQ(c.fy, 516.5);
  EXPECT_DOUBLE_EQ(c.cx, 318.6);
  EXPECT_DOUBLE_EQ(c.cy, 255.3);
  EXPECT_DOUBLE_EQ(c.distortion.k1, 0.2624);
  EXPECT_DOUBLE_EQ(c.distortion.k2, -0.9531);
  EXPECT_DOUBLE_EQ(c.distortion.p1, -0.0054);
  EXPECT_DOUBLE_EQ(c.distortion.p2, 0.0026);
  EXPECT_DOUBLE_EQ(c.distortion.k3, 1.1633);
}

void ExpectError(const Expected<CameraCalibrationFile>& read, const std::string& code,
                 const std::string& fragment) {
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().code, code) << read.error().message;
  EXPECT_NE(read.error().message.find(fragment), std::string::npos) << read.error().message;
}

// A calibration file written from `text`, read back.
Expected<CameraCalibrationFile> ReadText(const std::string& text,
                                         const std::string& name = "calibration.yml") {
  TempDir tmp;
  WriteText(tmp.path() / name, text);
  return ReadCameraCalibrationFile(tmp.path() / name);
}

TEST(CameraCalibrationFile, ReadsOpenCvYamlAndJsonAsFileStorageWritesThem) {
  for (const char* name : {"calibration.yml", "calibration.json"}) {
    SCOPED_TRACE(name);
    TempDir tmp;
    WriteOpenCvCalibration(tmp.path() / name, FreiburgK(), FreiburgD());
    const auto read = ReadCameraCalibrationFile(tmp.path() / name);
    ASSERT_TRUE(read.ok()) << read.error().message;
    ExpectFreiburg(read->camera);
    EXPECT_FALSE(read->depth_unit_m || read->fps || read->frames || read->mirrored);
  }
}

TEST(CameraCalibrationFile, ReadsHandWrittenYamlWithoutTheHeaderLine) {
  const auto read = ReadText(
      "image_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n  rows: 3\n"
      "  cols: 3\n  dt: d\n  data: [ 517.3, 0., 318.6, 0., 516.5, 255.3, 0., 0., 1. ]\n"
      "distortion_coefficients: [ 0.2624, -0.9531, -0.0054, 0.0026, 1.1633 ]\nmirrored: true\n"
      "depth_unit_m: 0.0002\n");
  ASSERT_TRUE(read.ok()) << read.error().message;
  ExpectFreiburg(read->camera);
  EXPECT_EQ(read->mirrored, true);
  EXPECT_EQ(read->depth_unit_m, 0.0002);
}

TEST(CameraCalibrationFile, ReadsThePlainCameraJsonForm) {
  const auto read = ReadText(
      R"({ "width": 320, "height": 240, "fx": 285.63, "fy": 280, "cx": 160.0, "cy": 119.5,
           "depth_unit_m": 0.001, "frames": 48, "fps": 30, "mirrored": 0 })",
      "camera.json");
  ASSERT_TRUE(read.ok()) << read.error().message;
  const PinholeCamera& c = read->camera;
  EXPECT_EQ(c.width, 320);
  EXPECT_EQ(c.height, 240);
  EXPECT_DOUBLE_EQ(c.fx, 285.63);
  EXPECT_DOUBLE_EQ(c.fy, 280);
  EXPECT_DOUBLE_EQ(c.cx, 160);
  EXPECT_DOUBLE_EQ(c.cy, 119.5);
  EXPECT_TRUE(c.distortion.IsZero());
  EXPECT_EQ(read->depth_unit_m, 0.001);
  EXPECT_EQ(read->frames, 48);
  EXPECT_EQ(read->fps, 30.0);
  EXPECT_EQ(read->mirrored, false);
}

TEST(CameraCalibrationFile, ImageSizeIsOptional) {
  const auto read = ReadText(R"({"fx": 500, "fy": 500, "cx": 10, "cy": 20})", "c.json");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->camera.width, 0);
  EXPECT_EQ(read->camera.height, 0);
  EXPECT_DOUBLE_EQ(read->camera.cy, 20);
}

TEST(CameraCalibrationFile, EightCoefficientsWithZeroRationalTermsAreAccepted) {
  TempDir tmp;
  cv::Mat d = cv::Mat::zeros(1, 8, CV_64F);
  FreiburgD().copyTo(d(cv::Rect(0, 0, 5, 1)));
  WriteOpenCvCalibration(tmp.path() / "c.yml", FreiburgK(), d);
  const auto read = ReadCameraCalibrationFile(tmp.path() / "c.yml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  ExpectFreiburg(read->camera);
}

TEST(CameraCalibrationFileBadInput, RationalDistortionIsUnsupported) {
  TempDir tmp;
  cv::Mat d = cv::Mat::zeros(1, 8, CV_64F);
  d.at<double>(0, 6) = 0.01;
  WriteOpenCvCalibration(tmp.path() / "c.yml", FreiburgK(), d);
  ExpectError(ReadCameraCalibrationFile(tmp.path() / "c.yml"), "unsupported", "k4-k6");
}

TEST(CameraCalibrationFileBadInput, WrongDistortionCount) {
  TempDir tmp;
  WriteOpenCvCalibration(tmp.path() / "c.yml", FreiburgK(), cv::Mat::zeros(1, 3, CV_64F));
  ExpectError(ReadCameraCalibrationFile(tmp.path() / "c.yml"), "corrupt",
              "distortion_coefficients must hold 4, 5 or 8 values");
}

TEST(CameraCalibrationFileBadInput, SkewOrAWrongShapeOfCameraMatrix) {
  TempDir tmp;
  cv::Mat k = FreiburgK();
  k.at<double>(0, 1) = 0.5;
  WriteOpenCvCalibration(tmp.path() / "skew.yml", k, FreiburgD());
  ExpectError(ReadCameraCalibrationFile(tmp.path() / "skew.yml"), "corrupt", "no skew");
  WriteOpenCvCalibration(tmp.path() / "2x3.yml", FreiburgK()(cv::Rect(0, 0, 3, 2)), FreiburgD());
  ExpectError(ReadCameraCalibrationFile(tmp.path() / "2x3.yml"), "corrupt",
              "camera_matrix must be 3x3");
}

TEST(CameraCalibrationFileBadInput, MissingFileIsNotFound) {
  TempDir tmp;
  ExpectError(ReadCameraCalibrationFile(tmp.path() / "none.yml"), "not_found", "none.yml");
}

TEST(CameraCalibrationFileBadInput, UnreadableFiles) {
  ExpectError(ReadText(""), "corrupt", "empty");
  ExpectError(ReadText(R"({ "fx": 500, "fy": )", "c.json"), "corrupt",
              "not a readable YAML or JSON");
  ExpectError(ReadText("camera_matrix: [ 1, 2\n"), "corrupt", "not a readable YAML or JSON");
}

TEST(CameraCalibrationFileBadInput, MalformedKeysAreNamed) {
  ExpectError(ReadText(R"({"fx": 500, "fy": 500, "cx": 10})", "c.json"), "corrupt",
              "cy is missing");
  ExpectError(ReadText(R"({"fx": "wide", "fy": 500, "cx": 10, "cy": 10})", "c.json"), "corrupt",
              "fx must be a number");
  ExpectError(ReadText(R"({"fx": 0, "fy": 500, "cx": 10, "cy": 10})", "c.json"), "corrupt",
              "fx = 0 must be > 0");
  ExpectError(ReadText(R"({"fx": 500, "fy": -2, "cx": 10, "cy": 10})", "c.json"), "corrupt",
              "fy = -2 must be > 0");
  ExpectError(ReadText(R"({"width": 320, "fx": 500, "fy": 500, "cx": 10, "cy": 10})", "c.json"),
              "corrupt", "height is missing");
  ExpectError(ReadText(R"({"width": 32.5, "height": 24, "fx": 500, "fy": 500, "cx": 10, "cy": 10})",
                       "c.json"),
              "corrupt", "width must be an integer > 0");
  ExpectError(
      ReadText(R"({"fx": 500, "fy": 500, "cx": 10, "cy": 10, "depth_unit_m": 2})", "c.json"),
      "corrupt", "depth_unit_m = 2 must be in (0, 1]");
  ExpectError(ReadText(R"({"fx": 500, "fy": 500, "cx": 10, "cy": 10, "fps": 0})", "c.json"),
              "corrupt", "fps = 0 must be > 0");
  ExpectError(ReadText(R"({"fx": 500, "fy": 500, "cx": 10, "cy": 10, "frames": 0})", "c.json"),
              "corrupt", "frames must be an integer > 0");
  ExpectError(ReadText(R"({"fx": 500, "fy": 500, "cx": 10, "cy": 10, "mirrored": 2})", "c.json"),
              "corrupt", "mirrored must be 0 or 1");
  ExpectError(ReadText("camera_matrix: 5\n"), "corrupt",
              "camera_matrix must be an !!opencv-matrix");
  ExpectError(ReadText("camera_matrix: [ 500, 0, 10, 0, 500, 10, 0, 0, 1 ]\nfx: 500\n"), "corrupt",
              "camera_matrix and fx both");
  ExpectError(ReadText("image_width: 640\n"), "corrupt", "image_height is missing");
  ExpectError(ReadText("k: 1\n"), "corrupt", "fx is missing");
  ExpectError(ReadText("- 1\n- 2\n"), "corrupt", "not a YAML or JSON map");
}

}  // namespace
}  // namespace reenact::capture

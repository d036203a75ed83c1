#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "common/error/check.h"
#include "tests/support/temp_dir.h"
#include "viewer-client/output/contact_sheet.h"
#include "viewer-client/output/mp4_writer.h"
#include "viewer-client/output/png_writer.h"
#include "viewer-client/output/render_json.h"

namespace reenact::viewer {
namespace {

using reenact::test_support::TempDir;

namespace fs = std::filesystem;

ImageRgb8 Uniform(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  ImageRgb8 image(w, h, 3);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.at(x, y, 0) = r;
      image.at(x, y, 1) = g;
      image.at(x, y, 2) = b;
    }
  }
  return image;
}

bool PixelIs(const ImageRgb8& image, int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  return image.at(x, y, 0) == r && image.at(x, y, 1) == g && image.at(x, y, 2) == b;
}

TEST(ContactSheet, PlacesThumbnailsInAGridWithGaps) {
  std::vector<ImageRgb8> frames;
  for (int i = 0; i < 5; ++i) {
    frames.push_back(
        Uniform(40, 30, static_cast<uint8_t>(40 * i + 50), 200, static_cast<uint8_t>(10 * i)));
  }
  const int thumb_w = 20, thumb_h = 15, gap = kContactSheetGap, cols = 3, rows = 2;
  const ImageRgb8 sheet = MakeContactSheet(frames, cols, thumb_w);
  ASSERT_EQ(sheet.channels, 3);
  ASSERT_EQ(sheet.width, cols * thumb_w + (cols + 1) * gap);
  ASSERT_EQ(sheet.height, rows * thumb_h + (rows + 1) * gap);
  const auto& bg = kContactSheetBackground;
  for (int i = 0; i < 6; ++i) {
    const int x0 = gap + (i % cols) * (thumb_w + gap), y0 = gap + (i / cols) * (thumb_h + gap);
    // Bottom-right part of the thumbnail, clear of the label.
    const int x = x0 + thumb_w - 3, y = y0 + thumb_h - 3;
    if (i < 5) {
      EXPECT_TRUE(PixelIs(sheet, x, y, static_cast<uint8_t>(40 * i + 50), 200,
                          static_cast<uint8_t>(10 * i)))
          << i;
      // The label changes the top-left corner.
      bool label = false;
      for (int ly = y0; ly < y0 + 6; ++ly) {
        for (int lx = x0; lx < x0 + 6; ++lx) {
          label |= !PixelIs(sheet, lx, ly, static_cast<uint8_t>(40 * i + 50), 200,
                            static_cast<uint8_t>(10 * i));
        }
      }
      EXPECT_TRUE(label) << i;
    } else {
      EXPECT_TRUE(PixelIs(sheet, x, y, bg[0], bg[1], bg[2]));  // empty cell
    }
    // Gap pixels left of and above every cell.
    EXPECT_TRUE(PixelIs(sheet, x0 - 1, y0 + 5, bg[0], bg[1], bg[2])) << i;
    EXPECT_TRUE(PixelIs(sheet, x0 + 5, y0 - 1, bg[0], bg[1], bg[2])) << i;
  }
}

TEST(ContactSheet, UsesFewerColumnsThanAskedForFewFrames) {
  const std::vector<ImageRgb8> frames(2, Uniform(30, 60, 1, 2, 3));
  const ImageRgb8 sheet = MakeContactSheet(frames, 8, 10, {100, 107});
  EXPECT_EQ(sheet.width, 2 * 10 + 3 * kContactSheetGap);
  EXPECT_EQ(sheet.height, 20 + 2 * kContactSheetGap);
}

TEST(ContactSheet, RejectsFramesOfDifferentSizes) {
  const std::vector<ImageRgb8> frames{Uniform(40, 30, 0, 0, 0), Uniform(41, 30, 0, 0, 0)};
  EXPECT_THROW(MakeContactSheet(frames, 2, 20), CheckError);
  EXPECT_THROW(MakeContactSheet({}, 2, 20), CheckError);
}

TEST(PngWriter, WritesPixelsThatReadBackExactly) {
  TempDir dir;
  ImageRgb8 image(7, 5, 3);
  for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = static_cast<uint8_t>(i * 7);
  const std::string path = (dir.path() / "frame.png").string();
  ASSERT_TRUE(WritePng(path, image).ok());
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(bgr.type(), CV_8UC3);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      EXPECT_EQ(p[2], image.at(x, y, 0));
      EXPECT_EQ(p[1], image.at(x, y, 1));
      EXPECT_EQ(p[0], image.at(x, y, 2));
    }
  }
  ImageGray8 mask(4, 3, 1, 255);
  mask.at(1, 2) = 0;
  const std::string mask_path = (dir.path() / "mask.png").string();
  ASSERT_TRUE(WritePng(mask_path, mask).ok());
  const cv::Mat grey = cv::imread(mask_path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(grey.at<uint8_t>(2, 1), 0);
  EXPECT_EQ(grey.at<uint8_t>(0, 0), 255);
}

TEST(PngWriter, ReportsAMissingFolder) {
  TempDir dir;
  const Status s = WritePng((dir.path() / "no" / "such" / "f.png").string(), ImageRgb8(2, 2, 3));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "io");
}

TEST(PngWriter, RejectsAnEmptyImage) {
  TempDir dir;
  const Status s = WritePng((dir.path() / "f.png").string(), ImageRgb8());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "invalid_argument");
}

TEST(Mp4Writer, WritesFramesThatVideoCaptureCounts) {
  TempDir dir;
  const std::string path = (dir.path() / "clip.mp4").string();
  constexpr int kFrames = 15, kW = 64, kH = 48;
  {
    Expected<Mp4Writer> writer = Mp4Writer::Open(path, kW, kH, 15.0);
    ASSERT_TRUE(writer.ok()) << writer.error().message;
    EXPECT_TRUE(writer->codec() == "avc1" || writer->codec() == "mp4v");
    for (int i = 0; i < kFrames; ++i) {
      ASSERT_TRUE(writer->Write(Uniform(kW, kH, 200, static_cast<uint8_t>(10 * i), 30)).ok());
    }
    EXPECT_EQ(writer->frames_written(), kFrames);
  }  // closed by the destructor
  cv::VideoCapture capture(path);
  ASSERT_TRUE(capture.isOpened());
  EXPECT_EQ(static_cast<int>(capture.get(cv::CAP_PROP_FRAME_COUNT)), kFrames);
  int decoded = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    ASSERT_EQ(frame.cols, kW);
    ASSERT_EQ(frame.rows, kH);
    if (decoded == 0) {  // BGR on the OpenCV side: red 200 sits in channel 2
      const cv::Vec3b p = frame.at<cv::Vec3b>(kH / 2, kW / 2);
      EXPECT_NEAR(p[2], 200, 25);
      EXPECT_NEAR(p[0], 30, 25);
    }
    ++decoded;
  }
  EXPECT_EQ(decoded, kFrames);
}

TEST(Mp4Writer, ReportsAnUnwritablePath) {
  TempDir dir;
  Expected<Mp4Writer> writer = Mp4Writer::Open((dir.path() / "no" / "x.mp4").string(), 64, 48, 10);
  ASSERT_FALSE(writer.ok());
  EXPECT_EQ(writer.error().code, "io");
}

TEST(Mp4Writer, RejectsAFrameOfAnotherSize) {
  TempDir dir;
  Expected<Mp4Writer> writer = Mp4Writer::Open((dir.path() / "x.mp4").string(), 64, 48, 10);
  ASSERT_TRUE(writer.ok());
  const Status s = writer->Write(Uniform(32, 48, 0, 0, 0));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "invalid_argument");
  writer->Close();
  EXPECT_FALSE(writer->Write(Uniform(64, 48, 0, 0, 0)).ok());
}

TEST(Mp4Writer, RejectsANonPositiveFrameRate) {
  Expected<Mp4Writer> writer = Mp4Writer::Open("/tmp/never.mp4", 64, 48, 0);
  ASSERT_FALSE(writer.ok());
  EXPECT_EQ(writer.error().code, "invalid_argument");
}

TEST(RenderJson, SubjectLightSaysWhetherAndHowTheClipIsRelit) {
  SubjectLightFit fit;
  fit.found = true;
  fit.light = Eigen::Vector3d(0.3, -0.4, 1.2);
  fit.gain = 0.25;
  fit.samples = 4000;
  fit.bins = 300;
  const nlohmann::json j = SubjectLightJson(fit);
  EXPECT_EQ(j["found"], true);
  EXPECT_EQ(j["light_in_world"], nlohmann::json({0.3, -0.4, 1.2}));
  EXPECT_DOUBLE_EQ(j["strength"].get<double>(), 1.3);  // |(0.3, -0.4, 1.2)| = 1.3
  EXPECT_EQ(j["gain"], 0.25);
  EXPECT_EQ(j["samples"], 4000);
  EXPECT_EQ(j["bins"], 300);
  EXPECT_FALSE(j.contains("reason"));

  SubjectLightFit none;
  none.reason = "flat";
  const nlohmann::json k = SubjectLightJson(none);
  EXPECT_EQ(k["found"], false);
  EXPECT_EQ(k["strength"], 0.0);
  EXPECT_EQ(k["reason"], "flat");
}

}  // namespace
}  // namespace reenact::viewer

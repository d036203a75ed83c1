// reenact-capture record on a real recording (TUM RGB-D fr1_rpy from ../shared/data): the
// sensor is tracked by the recorder's SLAM and the skeletons come from an imported track, as
// a user without a synthetic scene records.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "tests/integration/process.h"

namespace reenact {
namespace {

using testing::kCapture;
using testing::RunProcess;
using testing::TempDir;

const std::string kTum = std::string(REENACT_SOURCE_DIR) + "/../shared/data/tum-fr1-rpy-head";

// A track of `frames` frames keyed by index: a standing figure 10 m in front of the sensor
// (beyond the Kinect's range, so segmentation finds nobody and SLAM sees the whole room).
void WriteFarAwayTrack(const std::string& path, int frames) {
  std::ofstream out(path);
  out << R"({"format": "reenact-skeleton-track", "version": 1, "frame": "sensor", "frames": [)";
  const char* joints[] = {"head",   "neck",       "torso",   "waist",  "l_shoulder", "l_elbow",
                          "l_hand", "r_shoulder", "r_elbow", "r_hand", "l_hip",      "l_knee",
                          "l_foot", "r_hip",      "r_knee",  "r_foot"};
  for (int i = 0; i < frames; ++i) {
    out << (i ? "," : "") << R"({"frame_index": )" << i << R"(, "joints": {)";
    for (int j = 0; j < 16; ++j)
      out << (j ? "," : "") << '"' << joints[j] << R"(": {"position": [)" << 0.01 * j
          << R"(, 0, 10], "confidence": 1})";
    out << "}}";
  }
  out << "]}";
}

TEST(RecordReal, TumRecordingWithAnImportedTrackIsTrackedBySlam) {
  if (!std::filesystem::is_directory(kTum)) GTEST_SKIP() << kTum << " is absent (shared data)";
  TempDir tmp;
  WriteFarAwayTrack(tmp.path() + "/track.json", 40);
  const std::string clip = tmp.path() + "/clip";
  const auto record =
      RunProcess({kCapture, "record", "--source", "tum:" + kTum + "?undistort=both", "--skeleton",
                  "json:" + tmp.path() + "/track.json", "--out", clip},
                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;
  EXPECT_NE(record.out.find("skeletons from"), std::string::npos) << record.out;
  EXPECT_NE(record.out.find("poses by SLAM"), std::string::npos) << record.out;
  // 40 track frames for a longer recording: the rest are read, tracked and not stored.
  EXPECT_NE(record.out.find("recorded 40 frames"), std::string::npos) << record.out;
  EXPECT_NE(record.out.find("without a skeleton"), std::string::npos) << record.out;

  const auto info = RunProcess({kCapture, "info", clip});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(info.out, m, std::regex(R"(map\s+(\d+) points)"))) << info.out;
  EXPECT_GT(std::stoi(m[1].str()), 100) << info.out;
}

TEST(RecordReal, AMissingTrackFileFailsBeforeRecording) {
  TempDir tmp;
  const auto r =
      RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick", "--skeleton",
                  "kinect:" + tmp.path() + "/none.txt", "--out", tmp.path() + "/clip"},
                 std::chrono::seconds(30));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("none.txt"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() + "/clip"));
}

TEST(RecordReal, AnUnknownPoseModeIsAUsageError) {
  TempDir tmp;
  const auto r = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick", "--poses",
                             "imu", "--out", tmp.path() + "/clip"},
                            std::chrono::seconds(30));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--poses"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace reenact

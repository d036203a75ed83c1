// reenact-capture record --skeleton track: skeletons from our depth tracker (issue 8), on the
// synthetic scene (which starts in the calibration pose) and on the real .oni recording of a
// room without a person (a clear outcome, not a crash, and nothing left behind).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/integration/process.h"

namespace reenact {
namespace {

using testing::kCapture;
using testing::RunProcess;
using testing::TempDir;

const std::string kOni =
    std::string(REENACT_SOURCE_DIR) + "/../shared/data/oni/kinect-room-12f.oni";

TEST(RecordTrack, SyntheticCalibrationPoseIsTrackedAndRecorded) {
  TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const auto record = RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick",
                                  "--frames", "40", "--skeleton", "track", "--out", clip},
                                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;
  EXPECT_NE(record.out.find("skeletons from the depth tracker"), std::string::npos) << record.out;
  EXPECT_NE(record.out.find("tracker: 40 of 40 frames tracked; started at frame 0 from the "
                            "calibration pose"),
            std::string::npos)
      << record.out;
  EXPECT_NE(record.out.find("recorded 40 frames"), std::string::npos) << record.out;
  // The synthetic source knows its poses, and the tracker is given every one.
  EXPECT_NE(record.out.find("the sensor's pose on 40 of 40 frames"), std::string::npos)
      << record.out;
  const auto info = RunProcess({kCapture, "info", clip});
  ASSERT_EQ(info.exit_code, 0) << info.err;
}

TEST(RecordTrack, WithSlamPosesTheTrackerIsGivenSlamsPrediction) {
  // --poses slam tracks the sensor as for a source without poses, after each frame's skeleton:
  // the tracker is given SLAM's prediction, which exists from the second frame on (SLAM founds
  // its map on the first), so 39 of 40 frames have a pose.
  TempDir tmp;
  const auto record =
      RunProcess({kCapture, "record", "--source", "synthetic:turn-and-kick", "--frames", "40",
                  "--skeleton", "track", "--poses", "slam", "--out", tmp.path() + "/clip"},
                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;
  EXPECT_NE(record.out.find("tracker: 40 of 40 frames tracked"), std::string::npos) << record.out;
  EXPECT_NE(record.out.find("the sensor's pose on 39 of 40 frames (the static scene beside the "
                            "subject is left in on the others)"),
            std::string::npos)
      << record.out;
}

TEST(RecordTrack, AWalkWithoutTheCalibrationPoseReportsTheMeasuredBody) {
  // The procedural body walking CMU 131_02 never shows the calibration pose: tracking starts
  // after 15 frames with average proportions, and the head and legs measured from the
  // silhouette read average for this body of average proportions (its readings lie within
  // the measurements' noise allowances; docs/measurements.md).
  TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const std::string bvh =
      std::string(REENACT_SOURCE_DIR) + "/../shared/data/mocap/cmu-131_02-walk.bvh";
  if (!std::filesystem::exists(bvh)) GTEST_SKIP() << bvh << " is absent (shared data)";
  const auto record = RunProcess({kCapture, "record", "--source", "synthetic:bvh:" + bvh,
                                  "--frames", "60", "--skeleton", "track", "--out", clip},
                                 std::chrono::seconds(300));
  ASSERT_EQ(record.exit_code, 0) << record.err;
  EXPECT_NE(record.out.find("started at frame 14 without the calibration pose: average "
                            "proportions, the head 1.00 and the legs 1.00 times the average's"),
            std::string::npos)
      << record.out;
}

TEST(RecordTrack, RoomWithoutAPersonFailsClearlyAndLeavesNothing) {
  if (!std::filesystem::exists(kOni)) GTEST_SKIP() << kOni << " is absent (shared data)";
  TempDir tmp;
  const std::string clip = tmp.path() + "/clip";
  const auto record = RunProcess(
      {kCapture, "record", "--source", "oni:" + kOni, "--skeleton", "track", "--out", clip},
      std::chrono::seconds(300));
  EXPECT_NE(record.exit_code, 0);
  EXPECT_NE(record.out.find("tracker: no skeleton in 12 frames"), std::string::npos) << record.out;
  EXPECT_NE(record.err.find("has a skeleton"), std::string::npos) << record.err;
  EXPECT_FALSE(std::filesystem::exists(clip));
}

}  // namespace
}  // namespace reenact

#include "tests/eval/clip_scene_frames.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

TEST(ClipSceneFrames, EveryFrameRecordedMapsOntoItself) {
  std::vector<double> t;
  for (int n = 0; n < 225; ++n) t.push_back(n / 30.0);
  const auto frames = SceneFramesOfClip(t, 30, 225);
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  ASSERT_EQ(frames->size(), 225u);
  for (int n = 0; n < 225; ++n) EXPECT_EQ((*frames)[n], n);
}

TEST(ClipSceneFrames, LostFramesAreSkippedNotShifted) {
  // Frames 2, 3 and 7 of ten lost, as the tracker's loss leaves out of a clip.
  const std::vector<int> kept = {0, 1, 4, 5, 6, 8, 9};
  std::vector<double> t;
  for (int n : kept) t.push_back(n / 30.0);
  const auto frames = SceneFramesOfClip(t, 30, 10);
  ASSERT_TRUE(frames.ok()) << frames.error().message;
  EXPECT_EQ(*frames, kept);
}

TEST(ClipSceneFrames, NoFramesGiveAnEmptyMap) {
  const auto frames = SceneFramesOfClip({}, 30, 0);
  ASSERT_TRUE(frames.ok());
  EXPECT_TRUE(frames->empty());
}

TEST(ClipSceneFrames, TimestampsThatAreNoLaterSceneFrameAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::vector<double>> bad = {
      {0, 0.5 / 30},            // between two frames
      {0, 2 / 30.0, 1 / 30.0},  // out of order
      {0, 0},                   // the same frame twice
      {10 / 30.0},              // beyond the last frame
      {-1 / 30.0},              // before the first
      {nan},
  };
  for (const std::vector<double>& t : bad) {
    const auto frames = SceneFramesOfClip(t, 30, 10);
    ASSERT_FALSE(frames.ok()) << t.back();
    EXPECT_EQ(frames.error().code, "internal");
    EXPECT_NE(frames.error().message.find("is not a later one of the scene's 10 frames"),
              std::string::npos)
        << frames.error().message;
  }
}

TEST(ClipSceneFrames, ARateThatIsNoRateIsAPreconditionFailure) {
  const std::vector<double> t = {0};
  EXPECT_THROW(SceneFramesOfClip(t, 0, 10), CheckError);
  EXPECT_THROW(SceneFramesOfClip(t, std::numeric_limits<double>::infinity(), 10), CheckError);
  EXPECT_THROW(SceneFramesOfClip(t, 30, -1), CheckError);
}

}  // namespace
}  // namespace reenact::eval

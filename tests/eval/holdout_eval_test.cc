// `reenact-eval holdout` without rendering: the held-out rule, the command line and the errors
// a run gives before it records or renders (gl_holdout_eval_test.cc runs it).
#include "tests/eval/holdout_eval.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "tests/eval/eval_cli_test_support.h"
#include "tests/eval/holdout_cli.h"
#include "tests/eval/holdout_frames.h"
#include "tests/support/temp_dir.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;
using cli_test::ExpectRefused;

std::vector<int> ExcludedFrames(const HeldOutFrames& frames) {
  std::vector<int> out;
  for (size_t n = 0; n < frames.excluded.size(); ++n)
    if (frames.excluded[n]) out.push_back(static_cast<int>(n));
  return out;
}

TEST(HoldoutFrames, EveryKthFrameFromKWithItsWindow) {
  // 20 frames, K 5, W 1: 5, 10, 15 (20 is past the end), each with 4..6 and so on.
  const auto f = SelectHeldOutFrames(20, 5, 1);
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->held_out, (std::vector<int>{5, 10, 15}));
  EXPECT_EQ(ExcludedFrames(*f), (std::vector<int>{4, 5, 6, 9, 10, 11, 14, 15, 16}));
  EXPECT_EQ(f->kept, 11);
}

TEST(HoldoutFrames, AHeldOutFrameNeedsItsWholeWindow) {
  // 12 frames, K 2, W 3: 2 has no 3 frames before it, 10 none after it (10 + 3 > 11).
  const auto f = SelectHeldOutFrames(12, 2, 3);
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_EQ(f->held_out, (std::vector<int>{4, 6, 8}));
  EXPECT_EQ(f->kept, 1);  // frame 0 alone: 1..11 lie in the windows
  EXPECT_FALSE(f->excluded[0]);
  // K 1, W 0: every frame but the first.
  const auto all = SelectHeldOutFrames(5, 1, 0);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->held_out, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(all->kept, 1);
}

TEST(HoldoutFrames, AWindowThatLeavesNoFrameToTextureFromIsAClearError) {
  // 10 frames, K 1, W 1: 1..8 held out, their windows cover 0..9.
  ExpectRefused(SelectHeldOutFrames(10, 1, 1), {"10 frames", "K 1", "W 1"}, "usage",
                "--every 1 --window 1 leave no frame to texture from");
  // K 3, W 1 on 6 frames: 3 (2..4) alone; 0, 1 and 5 are kept.
  const auto f = SelectHeldOutFrames(6, 3, 1);
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->kept, 3);
}

TEST(HoldoutFrames, NoFrameToHoldOutOrBadValuesAreUsageErrors) {
  ExpectRefused(SelectHeldOutFrames(10, 10, 0), {"K 10 of 10"}, "usage", "no frame of the 10");
  ExpectRefused(SelectHeldOutFrames(10, 4, 6), {"K 4 W 6 of 10"}, "usage", "no frame of the 10");
  ExpectRefused(SelectHeldOutFrames(0, 1, 0), {"no frames"}, "usage", "no frame of the 0");
  ExpectRefused(SelectHeldOutFrames(10, 0, 0), {"K 0"}, "usage", "--every must be");
  ExpectRefused(SelectHeldOutFrames(10, 2, -1), {"W -1"}, "usage", "--window must be");
}

Expected<HoldoutCommand> Parse(const std::vector<std::string>& args) {
  return cli_test::ParseEvalArgs("holdout", HoldoutFlags(), ParseHoldoutCommand, args);
}

void ExpectUsage(const std::vector<std::string>& args, const std::string& says) {
  ExpectRefused(Parse(args), args, "usage", says);
}

TEST(HoldoutCli, TakesTheFlagsAsGiven) {
  const auto c =
      Parse({"--source", "synthetic:turn-and-kick", "--every", "15", "--window", "2", "--skeleton",
             "track", "--poses", "slam", "--methods", "thesis,blend", "--frames", "90"});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->options.source, "synthetic:turn-and-kick");
  EXPECT_EQ(c->options.every, 15);
  EXPECT_EQ(c->options.window, 2);
  EXPECT_EQ(c->options.skeleton, "track");
  EXPECT_TRUE(c->options.slam_poses);
  EXPECT_EQ(c->options.methods, (std::vector<std::string>{"thesis", "blend"}));
  EXPECT_EQ(c->options.max_frames, 90);
  EXPECT_FALSE(c->json_path);
  const auto d = Parse({"--source", "oni:x.oni", "--every", "4", "--window", "0"});
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->options.skeleton, "source");
  EXPECT_FALSE(d->options.slam_poses);
  EXPECT_EQ(d->options.max_frames, -1);
  EXPECT_EQ(d->options.methods, (std::vector<std::string>{"thesis"}));
}

TEST(HoldoutCli, BadValuesAreUsageErrors) {
  const std::vector<std::string> base = {"--source", "synthetic:turn-and-kick"};
  auto with = [&base](std::vector<std::string> more) {
    more.insert(more.begin(), base.begin(), base.end());
    return more;
  };
  ExpectUsage({"--every", "5", "--window", "1"}, "holdout needs --source");
  ExpectUsage(with({"--window", "1"}), "holdout needs --every");
  ExpectUsage(with({"--every", "5"}), "holdout needs --window");
  ExpectUsage(with({"--every", "0", "--window", "1"}), "--every must be a whole number >= 1");
  ExpectUsage(with({"--every", "five", "--window", "1"}), "--every expects an integer");
  ExpectUsage(with({"--every", "5", "--window", "-1"}), "--window must be a whole number >= 0");
  ExpectUsage(with({"--every", "5", "--window", "1.5"}), "--window expects an integer");
  ExpectUsage(with({"--every", "5", "--window", "1", "--frames", "0"}), "--frames must be");
  ExpectUsage(with({"--every", "5", "--window", "1", "--poses", "truth"}), "--poses must be");
  ExpectUsage(with({"--every", "5", "--window", "1", "--skeleton", ""}), "--skeleton: empty");
  ExpectUsage(with({"--every", "5", "--window", "1", "--methods", "thesis,nope"}),
              "unknown method 'nope'");
  ExpectUsage(with({"--every", "5", "--window", "1", "--methods", "thesis,"}), "empty item");
  const auto json = Parse(with({"--every", "5", "--window", "1", "--json", "/nonexistent/x.json"}));
  ExpectRefused(json, {"--json /nonexistent/x.json"}, "io", "does not exist");
}

TEST(HoldoutEval, ASourceWithoutColourIsOneClearError) {
  // A depth-only folder (rgbd:DIR without rgb/): two 16-bit depth images and a camera.
  const test_support::TempDir dir("holdout-eval");
  fs::create_directories(dir.path() / "depth");
  for (const char* name : {"000000.png", "000001.png"})
    ASSERT_TRUE(cv::imwrite((dir.path() / "depth" / name).string(),
                            cv::Mat(24, 32, CV_16UC1, cv::Scalar(2000))));
  std::ofstream(dir.path() / "camera.json")
      << R"({"width": 32, "height": 24, "fx": 30, "fy": 30, "cx": 15.5, "cy": 11.5})";
  HoldoutOptions options;
  options.source = "rgbd:" + dir.path().string();
  options.every = 1;
  const auto run = RunHoldout(options);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "unsupported");
  const std::string& m = run.error().message;
  EXPECT_NE(m.find("holdout compares each held-out frame with its colour image"), std::string::npos)
      << m;
  for (const char* kind : {"synthetic:", "oni:", "tum:", "clip:", "DIR/rgb/"})
    EXPECT_NE(m.find(kind), std::string::npos) << kind << " missing in: " << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(HoldoutEval, AWindowThatLeavesNoFrameToTextureFromStopsTheRun) {
  // 8 frames of the scene, K 1, W 1: frames 1..6 held out, 0..7 in their windows. The error
  // comes before anything is recorded or rendered.
  HoldoutOptions options;
  options.source = "synthetic:turn-and-kick";
  options.max_frames = 8;
  options.every = 1;
  options.window = 1;
  const auto run = RunHoldout(options);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "usage");
  EXPECT_NE(run.error().message.find("--every 1 --window 1 leave no frame to texture from: each "
                                     "of the 8 frames"),
            std::string::npos)
      << run.error().message;
  EXPECT_NE(run.error().message.find("give --every above 2W + 1 = 3 or a smaller --window"),
            std::string::npos)
      << run.error().message;
}

TEST(HoldoutEval, AnUnknownMethodIsAUsageError) {
  HoldoutOptions options;
  options.source = "synthetic:turn-and-kick";
  options.methods = {"thesis", "nope"};
  ExpectRefused(RunHoldout(options), {"--methods thesis,nope"}, "usage", "unknown method 'nope'");
}

}  // namespace
}  // namespace reenact::eval

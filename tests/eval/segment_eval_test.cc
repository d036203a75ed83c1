// `reenact-eval segment`: its command line (bad input refused before the run) and a short run
// against the synthetic ground truth.
#include "tests/eval/segment_eval.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/eval/eval_cli_test_support.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

Expected<SegmentCommand> Parse(std::vector<std::string> args) {
  return cli_test::ParseEvalArgs("segment", SegmentFlags(), ParseSegmentCommand, std::move(args));
}

void ExpectUsage(const std::vector<std::string>& args, const std::string& says) {
  cli_test::ExpectRefused(Parse(args), args, "usage", says);
}

TEST(SegmentCli, Defaults) {
  const auto r = Parse({});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenarios, std::vector<std::string>{"turn-and-kick"});
  EXPECT_EQ(r->options.frame_step, 1);
  EXPECT_TRUE(r->options.depth_noise);
  EXPECT_FALSE(r->json_path);
}

TEST(SegmentCli, Flags) {
  const auto r =
      Parse({"--scenario", "turn-and-kick,calibration", "--step", "5", "--noise", "off"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenarios, (std::vector<std::string>{"turn-and-kick", "calibration"}));
  EXPECT_EQ(r->options.frame_step, 5);
  EXPECT_FALSE(r->options.depth_noise);
}

TEST(SegmentCli, BadInputIsRefused) {
  ExpectUsage({"--noise", "maybe"}, "--noise must be on or off");
  ExpectUsage({"--step", "0"}, "--step");
  ExpectUsage({"--step", "two"}, "step");
  ExpectUsage({"--scenario", ""}, "--scenario");
  ExpectUsage({"--scenario", "turn-and-kick,"}, "--scenario");
  const auto json = Parse({"--json", "/nonexistent-folder/out.json"});
  ASSERT_FALSE(json.ok());
  EXPECT_EQ(json.error().code, "io");
}

TEST(SegmentEval, UnknownScenarioIsNotFound) {
  SegmentEvalOptions o;
  o.scenarios = {"moonwalk"};
  const auto rows = RunSegmentEval(o);
  ASSERT_FALSE(rows.ok());
  EXPECT_EQ(rows.error().code, "not_found");
}

TEST(SegmentEval, ShortRunMeetsTheIssuesGoalAndWritesTheReport) {
  SegmentEvalOptions o;
  o.frame_step = 45;  // frames 0, 45, 90, 135 (the kick)
  const auto rows = RunSegmentEval(o);
  ASSERT_TRUE(rows.ok()) << rows.error().message;
  ASSERT_EQ(rows->size(), 1u);
  const SegmentEvalRow& row = rows->front();
  EXPECT_EQ(row.frames, 4);
  EXPECT_GE(row.iou_min, 0.9);
  EXPECT_LE(row.iou_min, row.iou_p10);
  EXPECT_LE(row.iou_p10, row.iou_mean);
  EXPECT_LE(row.iou_mean, 1.0);
  EXPECT_EQ(row.not_ok_frames, 0);
  EXPECT_EQ(row.floor_fits, 1);  // a static sensor: fitted once
  EXPECT_GT(row.ms_per_frame, 0);

  const fs::path path =
      fs::temp_directory_path() / ("reenact-segment-eval-" + std::to_string(::getpid()) + ".json");
  ASSERT_TRUE(SegmentReport(*rows).WriteJson(path.string()).ok());
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  fs::remove(path);
  for (const char* field : {"\"command\": \"segment\"", "\"scenario\": \"turn-and-kick\"",
                            "\"iou\":", "\"iou_min\":", "\"iou_p10\":", "\"ms_per_frame\":"})
    EXPECT_NE(text.str().find(field), std::string::npos) << field << " in " << text.str();
}

}  // namespace
}  // namespace reenact::eval

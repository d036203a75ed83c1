// `reenact-eval slam`: bad command lines refused before any work, each with a clear error;
// a short run on the real TUM frames (skipped when ../shared/data is absent).
#include "tests/eval/slam_eval.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/eval/eval_cli_test_support.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// ../shared/data from the repository root (this file is tests/eval/ in it).
fs::path TumRpyDir() {
  return fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "shared" /
         "data" / "tum-fr1-rpy-head";
}

Expected<SlamCommand> Parse(std::vector<std::string> args) {
  return cli_test::ParseEvalArgs("slam", SlamFlags(), ParseSlamCommand, std::move(args));
}

void ExpectError(const std::vector<std::string>& args, const std::string& code,
                 const std::string& says) {
  cli_test::ExpectRefused(Parse(args), args, code, says);
}

TEST(SlamEvalCli, DefaultsRunEveryMethodOnEveryFrame) {
  const auto r = Parse({"--tum", "some/dir"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.tum_dir, "some/dir");
  EXPECT_EQ(r->options.methods,
            (std::vector<std::string>{"reenact", "opencv-rgbd", "opencv-fasticp"}));
  EXPECT_EQ(r->options.max_frames, -1);
  EXPECT_DOUBLE_EQ(r->options.readout_ratio, kKinectReadoutRatio);
  EXPECT_FALSE(r->json_path.has_value());
}

TEST(SlamEvalCli, MissingTumIsRefused) { ExpectError({}, "usage", "--tum DIR"); }

TEST(SlamEvalCli, UnknownMethodIsRefused) {
  ExpectError({"--tum", "d", "--methods", "reenact,orb-slam"}, "usage", "orb-slam");
}

TEST(SlamEvalCli, EmptyMethodListIsRefused) {
  ExpectError({"--tum", "d", "--methods", "reenact,"}, "usage", "--methods");
}

TEST(SlamEvalCli, TooFewFramesAreRefused) {
  ExpectError({"--tum", "d", "--max-frames", "2"}, "usage", "--max-frames");
}

TEST(SlamEvalCli, NonIntegerFramesAreRefused) {
  ExpectError({"--tum", "d", "--max-frames", "ten"}, "usage", "max-frames");
}

TEST(SlamEvalCli, ReadoutRatioOutsideZeroOneIsRefused) {
  ExpectError({"--tum", "d", "--readout-ratio", "1.5"}, "usage", "--readout-ratio");
}

TEST(SlamEvalCli, UnknownCameraIsRefused) {
  ExpectError({"--tum", "d", "--camera", "fr9"}, "usage", "fr9");
}

TEST(SlamEvalCli, UnwritableJsonIsRefused) {
  ExpectError({"--tum", "d", "--json", "/no/such/folder/out.json"}, "io", "does not exist");
}

TEST(SlamEval, MissingSequenceIsAnError) {
  SlamEvalOptions o;
  o.tum_dir = "/no/such/tum/sequence_fr1";
  const auto r = RunSlamEval(o);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "not_found");
}

TEST(SlamEval, SequenceWithoutGroundTruthIsAnError) {
  if (!fs::exists(TumRpyDir())) GTEST_SKIP() << TumRpyDir() << " is absent";
  // A copy of the first three frames' list without groundtruth.txt (the images stay put).
  const fs::path dir = fs::temp_directory_path() /
                       ("reenact-slam-eval-fr1-" +
                        std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream in(TumRpyDir() / "associations.txt");
  std::ofstream out(dir / "associations.txt");
  std::string line;
  for (int i = 0; i < 3 && std::getline(in, line); ++i) {
    std::istringstream s(line);
    std::string t1, rgb, t2, depth;
    s >> t1 >> rgb >> t2 >> depth;
    out << t1 << " " << (TumRpyDir() / rgb).string() << " " << t2 << " "
        << (TumRpyDir() / depth).string() << "\n";
  }
  out.close();
  SlamEvalOptions o;
  o.tum_dir = dir.string();
  const auto r = RunSlamEval(o);
  fs::remove_all(dir);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("groundtruth"), std::string::npos) << r.error().message;
}

TEST(SlamEval, ShortRunOnRealFramesReportsEveryFigure) {
  if (!fs::exists(TumRpyDir())) GTEST_SKIP() << TumRpyDir() << " is absent";
  SlamEvalOptions o;
  o.tum_dir = TumRpyDir().string();
  o.max_frames = 12;
  o.methods = {"reenact", "opencv-rgbd"};
  const auto run = RunSlamEval(o);
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_EQ(run->camera, "fr1");
  EXPECT_EQ(run->frames, 12);
  EXPECT_EQ(run->frames_with_truth, 12);
  ASSERT_EQ(run->methods.size(), 2u);
  for (const SlamMethodResult& m : run->methods) {
    EXPECT_EQ(m.frames, 12) << m.method;
    EXPECT_EQ(m.tracked, 12) << m.method;
    EXPECT_TRUE(std::isfinite(m.ate_rmse_m)) << m.method;
    // 12 frames (0.4 s) of a hand-held sensor: errors of centimetres, not decimetres.
    EXPECT_LT(m.ate_rmse_m, 0.05) << m.method;
    EXPECT_TRUE(std::isfinite(m.rpe_m) && std::isfinite(m.rpe_deg)) << m.method;
    EXPECT_GT(m.ms_per_frame, 0) << m.method;
  }
  EXPECT_GT(run->methods[0].keyframes, 0);
  EXPECT_GT(run->methods[0].map_points, 0);
  EXPECT_GT(run->methods[0].map_bytes, 32 * run->methods[0].map_points);  // descriptors alone
  const proto::Report report = SlamReport(*run);
  ASSERT_EQ(report.rows.size(), 2u);
  const std::string json = report.ToJson();
  for (const char* field : {"ate_rmse_m", "ms_per_frame", "tracked_rate", "map_bytes", "fps"})
    EXPECT_NE(json.find(field), std::string::npos) << field;
}

}  // namespace
}  // namespace reenact::eval

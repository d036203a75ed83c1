// Bad input to `reenact-eval quality`: each refused with a clear error before the long run.
#include "tests/eval/quality_cli.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/eval/eval_cli_test_support.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

Expected<QualityCommand> Parse(std::vector<std::string> args) {
  return cli_test::ParseEvalArgs("quality", QualityFlags(), ParseQualityCommand, std::move(args));
}

void ExpectError(const std::vector<std::string>& args, const std::string& code,
                 const std::string& says) {
  cli_test::ExpectRefused(Parse(args), args, code, says);
}

class TempDir {
 public:
  TempDir()
      : path_(fs::temp_directory_path() / ("reenact-eval-cli-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    ::chmod(path_.c_str(), 0755);
    fs::remove_all(path_);
  }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(QualityCli, DefaultsAreTheStandardSet) {
  const auto r = Parse({});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenario, "turn-and-kick");
  EXPECT_EQ(r->options.methods, std::vector<std::string>{"thesis"});
  EXPECT_EQ(r->options.views_deg, (std::vector<double>{0, 30, 60, 90, 135, 180}));
  EXPECT_EQ(r->options.frame_step, 10);
  EXPECT_FALSE(r->json_path || r->markdown_path);
  EXPECT_TRUE(r->options.image_dir.empty());
}

TEST(QualityCli, ParsesEveryOption) {
  TempDir tmp;
  const auto r =
      Parse({"--scenario", "calibration", "--methods", "thesis", "--views", "-45,22.5,90", "--step",
             "3", "--json", tmp / "q.json", "--markdown", tmp / "q.md", "--images",
             tmp / "pics/deeper", "--image-pairs", "0@0,12@22.5"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.scenario, "calibration");
  EXPECT_EQ(r->options.views_deg, (std::vector<double>{-45, 22.5, 90}));
  EXPECT_EQ(r->options.frame_step, 3);
  EXPECT_EQ(*r->json_path, tmp / "q.json");
  EXPECT_EQ(*r->markdown_path, tmp / "q.md");
  EXPECT_EQ(r->options.image_dir, tmp / "pics/deeper");
  ASSERT_EQ(r->options.image_pairs.size(), 2u);
  EXPECT_EQ(r->options.image_pairs[1].frame, 12);
  EXPECT_EQ(r->options.image_pairs[1].view_deg, 22.5);
  EXPECT_FALSE(fs::exists(tmp / "q.json"));  // checking creates nothing
  EXPECT_FALSE(fs::exists(tmp / "pics"));
}

TEST(QualityCli, UnknownMethodListsTheKnownOnes) {
  ExpectError({"--methods", "thesis,magic"}, "usage",
              "unknown method 'magic'; known methods: thesis");
}

TEST(QualityCli, EmptyOrGarbageViewsAreRefused) {
  ExpectError({"--views", ""}, "usage", "--views: empty list");
  ExpectError({"--views", "0,,90"}, "usage", "--views: empty item");
  ExpectError({"--views", "0,90,"}, "usage", "--views: empty item");
  ExpectError({"--views", "ninety"}, "usage", "'ninety' is not a finite number");
  ExpectError({"--views", "30deg"}, "usage", "'30deg' is not a finite number");
  ExpectError({"--views", "nan"}, "usage", "'nan' is not a finite number");
  ExpectError({"--views", "1e999"}, "usage", "'1e999' is not a finite number");
}

TEST(QualityCli, StepBelowOneOrNotANumberIsRefused) {
  ExpectError({"--step", "0"}, "usage", "--step must be a whole number >= 1");
  ExpectError({"--step", "-2"}, "usage", "--step must be a whole number >= 1");
  const auto r = Parse({"--step", "x"});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("step"), std::string::npos) << r.error().message;
}

TEST(QualityCli, MalformedImagePairsAreRefused) {
  TempDir tmp;
  ExpectError({"--image-pairs", "90@0"}, "usage", "needs --images");
  ExpectError({"--images", tmp / "p", "--image-pairs", "90"}, "usage", "is not FRAME@DEG");
  ExpectError({"--images", tmp / "p", "--image-pairs", "-1@0"}, "usage", "frame '-1'");
  ExpectError({"--images", tmp / "p", "--image-pairs", "5@east"}, "usage", "'east'");
}

TEST(QualityCli, UnwritableOutputPathsAreRefused) {
  TempDir tmp;
  ExpectError({"--json", tmp / "missing/q.json"}, "io", "does not exist");
  ExpectError({"--markdown", tmp / "missing/q.md"}, "io", "does not exist");
  ExpectError({"--json", tmp.path().string()}, "io", "is a folder");
  std::ofstream(tmp / "file") << "x";
  ExpectError({"--images", tmp / "file/sub"}, "io", "is a file, not a folder");
  if (::geteuid() != 0) {  // root may write anywhere
    fs::create_directories(tmp / "ro");
    ::chmod((tmp / "ro").c_str(), 0555);
    ExpectError({"--markdown", tmp / "ro/q.md"}, "io", "cannot write into");
    ExpectError({"--images", tmp / "ro/pics"}, "io", "cannot write into");
    ::chmod((tmp / "ro").c_str(), 0755);
  }
}

TEST(QualityRun, UnknownScenarioListsTheKnownOnes) {
  QualityOptions options;
  options.scenario = "no-such-scene";
  const auto r = RunQuality(options);  // fails before capture or GL
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "not_found");
  EXPECT_NE(r.error().message.find("turn-and-kick"), std::string::npos) << r.error().message;
}

TEST(QualityRun, UnknownMethodIsRefusedBeforeTheRun) {
  QualityOptions options;
  options.methods = {"thesis", "magic"};
  const auto r = RunQuality(options);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "usage");
  EXPECT_NE(r.error().message.find("known methods: thesis"), std::string::npos);
}

}  // namespace
}  // namespace reenact::eval

namespace reenact::eval {
namespace {

TEST(QualityCli, ParsesSkeletonNoiseAndTheSteadyMethod) {
  const auto r = Parse({"--methods", "thesis,steady", "--skeleton-noise", "0.01"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->options.methods, (std::vector<std::string>{"thesis", "steady"}));
  EXPECT_DOUBLE_EQ(r->options.skeleton_noise_m, 0.01);
}

TEST(QualityCli, RefusesNegativeSkeletonNoise) {
  ExpectError({"--skeleton-noise", "-0.01"}, "usage", "--skeleton-noise must be metres");
}

TEST(QualityCli, RefusesSkeletonNoiseThatIsNotANumber) {
  ExpectError({"--skeleton-noise", "lots"}, "usage", "skeleton-noise");
}

TEST(QualityCli, ParsesTrackedSkeletons) {
  const auto r = Parse({"--skeletons", "track"});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->options.tracked_skeletons);
  const auto d = Parse({});
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_FALSE(d->options.tracked_skeletons);
}

TEST(QualityCli, RefusesAnUnknownSkeletonSource) {
  ExpectError({"--skeletons", "nite"}, "usage", "--skeletons must be truth or track");
}

TEST(QualityCli, RefusesTrackedSkeletonsWithNoise) {
  ExpectError({"--skeletons", "track", "--skeleton-noise", "0.01"}, "usage", "exclude each other");
}

TEST(QualityCli, ParsesLighting) {
  const auto flat = Parse({"--lighting", "flat"});
  ASSERT_TRUE(flat.ok()) << flat.error().message;
  EXPECT_TRUE(flat->options.flat_lighting);
  const auto scene = Parse({});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_FALSE(scene->options.flat_lighting);
}

TEST(QualityCli, RefusesAnUnknownLighting) {
  ExpectError({"--lighting", "studio"}, "usage", "--lighting must be scene or flat");
}

}  // namespace
}  // namespace reenact::eval

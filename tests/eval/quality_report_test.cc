#include "tests/eval/quality_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace reenact::eval {
namespace {

QualityRun TwoRows() {
  QualityRun run;
  run.clip_frames = 180;
  QualityRow a{"thesis", "turn-and-kick", 0,      18,     22.674, 0.8831,  0.8342, 5.71,
               0.0571,   0.0214,          0.0123, 0.0102, 0,      0.99996, 4.13};
  QualityRow b = a;
  b.view_deg = 22.5;
  b.psnr_db = std::numeric_limits<double>::infinity();
  run.rows = {a, b};
  return run;
}

TEST(QualityReport, JsonRowsCarryTheDesignFieldNames) {
  const std::string json = QualityReport(TwoRows()).ToJson();
  for (const char* field :
       {"\"method\"", "\"scenario\"", "\"view_deg\"", "\"n\"", "\"psnr_db\"", "\"ssim\"", "\"iou\"",
        "\"wrong_part_rate\"", "\"wrong_seen_part_rate\"", "\"wrong_texture_rate\"",
        "\"doubled_limb_rate\"", "\"ms_per_frame\""})
    EXPECT_NE(json.find(field), std::string::npos) << field;
}

TEST(QualityReport, SubjectLightLineComparesTheFitWithTheScenesLight) {
  QualityRun run;
  run.true_subject_light = Eigen::Vector3d(0, 0, 2);
  run.subject_light.found = true;
  run.subject_light.light = 1.5 * Eigen::Vector3d(std::sin(0.5), 0, std::cos(0.5));  // 28.6 deg
  run.subject_light.gain = 0.4567;
  run.subject_light.samples = 1234;
  run.subject_light.bins = 56;
  const std::string line = SubjectLightLine(run);
  EXPECT_NE(line.find("strength 1.50, 28.6 degrees from the scene's light (gain 0.457 over 1234 "
                      "samples in 56 surface bins); the scene's light has strength 2.00"),
            std::string::npos)
      << line;

  run.true_subject_light = Eigen::Vector3d::Zero();
  run.subject_light = {};
  run.subject_light.reason = "REASON";
  const std::string none = SubjectLightLine(run);
  EXPECT_NE(none.find("none found at load (REASON); the subject is lit flat"), std::string::npos)
      << none;
}

TEST(QualityReport, MarkdownHasTheTableTheRulesAndTheCommand) {
  QualityOptions options;
  options.views_deg = {0, 22.5};
  options.frame_step = 3;
  const std::string md = QualityMarkdown(options, TwoRows(), "docs/quality.md", "MACHINE");
  EXPECT_NE(
      md.find("| thesis | 0 | 18 | 22.67 | 0.883 | 0.834 | 5.7 | 0.057 | 0.021 | 0.012 | 0.010 | "
              "0.000 | 1.0000 | 4.1 |"),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("| thesis | 22.5 | 18 | inf |"), std::string::npos) << md;
  EXPECT_NE(md.find(kCropRule), std::string::npos);
  EXPECT_NE(md.find("wrong_part_rate: share of rendered subject pixels"), std::string::npos);
  EXPECT_NE(md.find("wrong_seen_part_rate: the same against the part the ground truth shows"),
            std::string::npos);
  EXPECT_NE(md.find("wrong_texture_rate: the part of that where the ground truth shows the drawn "
                    "cylinder's part"),
            std::string::npos);
  EXPECT_NE(md.find("doubled_limb_rate: the part of the seen-part rate whose source texels show "
                    "a part"),
            std::string::npos);
  EXPECT_NE(md.find("Measured MACHINE."), std::string::npos);
  EXPECT_NE(md.find("every 3rd frame"), std::string::npos);
  EXPECT_NE(md.find("reenact-eval quality --scenario turn-and-kick --methods thesis --views "
                    "0,22.5 --step 3"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("## Pictures"), std::string::npos);  // none taken
}

TEST(QualityReport, MarkdownSaysWhereTheSkeletonsCameFrom) {
  QualityOptions options;
  options.tracked_skeletons = true;
  const std::string md = QualityMarkdown(options, TwoRows(), "docs/quality.md", "MACHINE");
  EXPECT_NE(md.find("--step 10 --skeletons track"), std::string::npos) << md;
  EXPECT_NE(md.find("the recorded skeletons from our depth tracker"), std::string::npos) << md;
  EXPECT_EQ(md.find("lost"), std::string::npos) << md;  // every frame tracked
  QualityRun lossy = TwoRows();
  lossy.clip_frames = 219;
  lossy.scene_frames = 225;
  const std::string lost = QualityMarkdown(options, lossy, "docs/quality.md", "MACHINE");
  EXPECT_NE(lost.find("219 frames recorded"), std::string::npos) << lost;
  EXPECT_NE(lost.find("the tracker lost 6 of the scenario's 225 frames"), std::string::npos)
      << lost;
  options.tracked_skeletons = false;
  const std::string exact = QualityMarkdown(options, TwoRows(), "docs/quality.md", "MACHINE");
  EXPECT_EQ(exact.find("--skeletons"), std::string::npos);
  EXPECT_EQ(exact.find("depth tracker"), std::string::npos);
}

TEST(QualityReport, PictureLinksAreRelativeToTheDocument) {
  QualityRun run = TwoRows();
  run.images.push_back({"thesis", {90, 60}, "docs/quality/thesis_f090_v060.png", {}, 0.1});
  const std::string md = QualityMarkdown(QualityOptions{}, run, "docs/quality.md", "M");
  EXPECT_NE(md.find("](quality/thesis_f090_v060.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("frame 90, view 60 degrees"), std::string::npos) << md;
}

TEST(QualityReport, MachineLineNamesDateCoresAndRenderer) {
  const std::string line = MachineLine("llvmpipe");
  EXPECT_EQ(line.substr(4, 1), "-");  // YYYY-MM-DD first
  EXPECT_NE(line.find("logical cores"), std::string::npos);
  EXPECT_NE(line.find("OpenGL renderer llvmpipe"), std::string::npos);
}

TEST(QualityReport, UnwritableMarkdownFileIsAnIoError) {
  const std::string path = std::filesystem::temp_directory_path() /
                           ("reenact-no-such-dir-" + std::to_string(::getpid())) / "q.md";
  const Status s = WriteTextFile(path, "x");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, "io");
  EXPECT_NE(s.error().message.find(path), std::string::npos);
}

}  // namespace
}  // namespace reenact::eval

// `reenact-eval holdout` on the synthetic turn-and-kick (180 frames) against `reenact-eval
// quality` at view 0 (the sensor's own view) on the same frames, every method of the registry.
// Needs OpenGL (EGL surfaceless); suites start with "Gl".
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/eval/holdout_eval.h"
#include "tests/eval/quality_eval.h"
#include "tests/support/temp_dir.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> AllMethods() {
  std::vector<std::string> names;
  for (const QualityMethod& m : QualityMethods()) names.push_back(m.name);
  return names;
}

HoldoutOptions Options(int every, int window) {
  HoldoutOptions options;
  options.source = "synthetic:turn-and-kick";
  options.every = every;
  options.window = window;
  options.methods = AllMethods();
  return options;
}

QualityHarness& Quality() {
  static QualityHarness harness = [] {
    QualityOptions options;
    options.views_deg = {0};
    auto h = QualityHarness::Create(options);
    if (!h.ok()) throw std::runtime_error(h.error().message);
    return std::move(h).value();
  }();
  return harness;
}

struct Means {
  double psnr_db = 0, iou = 0;
  double squared_error = 0;  // per-pixel mean squared error, summed over the frames
  int n = 0;
};

// PSNR (dB) of a mean squared error, and back (8-bit peak).
double SquaredErrorOf(double psnr_db) { return 255.0 * 255.0 * std::pow(10.0, -psnr_db / 10); }
double PsnrOf(double squared_error) { return 10 * std::log10(255.0 * 255.0 / squared_error); }

TEST(GlHoldoutEval, AgreesWithQualityAtTheSensorsView) {
  // Every 15th frame held out, no neighbours: 15, 30, ..., 165, each textured from the 169
  // others. The scene gives every frame a skeleton, the sensor pose and a mask.
  const auto run = RunHoldout(Options(15, 0));
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_EQ(run->source_frames, 180);
  EXPECT_EQ(run->recorded_frames, 180);
  EXPECT_EQ(run->held_out, 11);
  EXPECT_EQ(run->excluded, 11);
  EXPECT_EQ(run->kept, 169);
  EXPECT_EQ(run->compared, 11);
  ASSERT_EQ(run->rows.size(), QualityMethods().size());

  std::map<std::string, Means> holdout, quality;
  for (const HoldoutFrame& f : run->frames) {
    EXPECT_EQ(f.source_frame % 15, 0) << f.source_frame;
    // The held-out image is not in the clip, so it never textures itself.
    EXPECT_NE(f.texture_frame, f.source_frame) << f.method << " frame " << f.source_frame;
    const auto e = Quality().Evaluate(**FindQualityMethod(f.method), 0, f.source_frame);
    ASSERT_TRUE(e.ok()) << e.error().message;
    // The silhouette is the model posed by the same exact skeleton with radii fitted to the
    // same body (from 169 frames instead of 180), trimmed where the texture frame's mask
    // shows no subject; a neighbouring frame's mask differs from the frame's own by a few
    // pixels at moving limbs (0.022 at most over these frames when measured, at the kick).
    EXPECT_NEAR(f.comparison.iou, e->comparison.iou, 0.05)
        << f.method << " frame " << f.source_frame;
    for (const auto& [means, c] : {std::pair{&holdout[f.method], &f.comparison},
                                   std::pair{&quality[f.method], &e->comparison}}) {
      means->psnr_db += c->psnr_db;
      means->squared_error += SquaredErrorOf(c->psnr_db);
      means->iou += c->iou;
      ++means->n;
    }
  }
  for (const HoldoutRow& row : run->rows) {
    SCOPED_TRACE(row.method);
    const Means& h = holdout[row.method];
    const Means& q = quality[row.method];
    ASSERT_EQ(h.n, 11);
    EXPECT_NEAR(row.psnr_db, h.psnr_db / h.n, 1e-9);
    EXPECT_NEAR(row.iou, h.iou / h.n, 1e-9);
    // PSNR: two differences, of opposite sign. Quality's view 0 looks from the sensor's
    // position at the subject's centre, so the stored view is resampled onto a re-aimed
    // pixel grid, while holdout renders on the sensor's own grid: where both texture from
    // the same still pose (frames 15, 120, 150) holdout's squared error measured 20-40 lower
    // (per pixel, 0-255 squared) for every method. In dB that is 0.4-0.6 for the thesis but
    // 2-5 for `surface`, whose own error is that much smaller, so the frames' squared errors
    // are compared, as the PSNR of their mean. And holdout textures from another frame, 1/30 s
    // away or a still pose: where the leg kicks, limbs move centimetres per frame and it
    // measured up to 2.9 dB lower (frame 90). Over the 11 frames the PSNRs of the mean squared
    // errors measured -0.6 to +0.8 dB apart for the eleven methods; the bound, 1.5 dB, is
    // about twice that, and far below the 3-10 dB that a wrong pose, camera or crop costs
    // (the empty-image floor of gl_quality_eval_test.cc).
    EXPECT_NEAR(PsnrOf(h.squared_error / h.n), PsnrOf(q.squared_error / q.n), 1.5);
    // IoU: the per-frame differences above average out to 0.005 at most when measured; four
    // times that.
    EXPECT_NEAR(h.iou / h.n, q.iou / q.n, 0.02);
  }
}

TEST(GlHoldoutEval, AWindowKeepsItsNeighboursOutOfTexturing) {
  // Every 30th frame with 3 neighbours on each side: 30, 60, ..., 150 (180 is past the end).
  const test_support::TempDir images("holdout-images");
  HoldoutOptions options = Options(30, 3);
  options.image_dir = images.path().string();
  const auto run = RunHoldout(options);
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_EQ(run->held_out, 5);
  EXPECT_EQ(run->excluded, 35);
  EXPECT_EQ(run->kept, 145);
  ASSERT_EQ(run->frames.size(), 5 * QualityMethods().size());
  for (const HoldoutFrame& f : run->frames) {
    SCOPED_TRACE(f.method + " frame " + std::to_string(f.source_frame));
    // Only the kept frames have images: the texture frame lies 4 or more frames away.
    ASSERT_GE(f.texture_frame, 0);
    EXPECT_GE(std::abs(f.texture_frame - f.source_frame), 4);
    // Some subject is drawn and matched, and the figures are finite.
    EXPECT_GT(f.comparison.iou, 0.5);
    EXPECT_TRUE(std::isfinite(f.comparison.psnr_db));
    // The picture: ground truth | reenactment | error, three panels of the box's width.
    ASSERT_TRUE(fs::exists(f.image_path));
    const cv::Mat picture = cv::imread(f.image_path);
    EXPECT_EQ((picture.cols - 2 * 4) % 3, 0);
  }
  for (const HoldoutRow& row : run->rows) EXPECT_GE(row.texture_gap, 4.0) << row.method;
}

}  // namespace
}  // namespace reenact::eval

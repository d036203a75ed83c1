// The quality harness on a short run, in CI (`make test`): turn-and-kick captured through the
// real recording pipeline, frames 0, 45, 90 and 135 reenacted by the thesis method from 0 and
// 90 degrees. The bounds follow from how the scene and the method are built (see each
// comment), not from an earlier run. Needs OpenGL (EGL surfaceless); suites start with "Gl".
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/eval/quality_eval.h"
#include "tests/eval/quality_report.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

constexpr int kStep = 45;  // frames 0, 45, 90, 135 of 180

QualityOptions ShortRun() {
  QualityOptions options;
  options.scenario = "turn-and-kick";
  options.views_deg = {0, 90};
  options.frame_step = kStep;
  return options;
}

QualityHarness& Harness() {
  static QualityHarness harness = [] {
    auto h = QualityHarness::Create(ShortRun());
    if (!h.ok()) throw std::runtime_error(h.error().message);
    return std::move(h).value();
  }();
  return harness;
}

const QualityMethod& Thesis() { return **FindQualityMethod("thesis"); }

// PSNR of an empty (black, no subject) rendering against the same ground truth under the
// same crop rule: the floor any reenactment must clear.
double EmptyImagePsnr(const capture::SyntheticView& truth) {
  const ImageRgb8 black(truth.color.width, truth.color.height, 3, 0);
  const ImageGray8 none(truth.color.width, truth.color.height, 1, 0);
  return CompareSubject(black, none, truth.color, truth.mask).psnr_db;
}

TEST(GlQualityEval, AtZeroDegreesTheThesisRerendersTheCapturedView) {
  QualityHarness& h = Harness();
  int same_frame = 0;
  for (int k = 0; k < h.clip().frame_count(); k += kStep) {
    const auto e = h.Evaluate(Thesis(), 0, k);
    ASSERT_TRUE(e.ok()) << e.error().message;
    const int w = h.camera().width, hgt = h.camera().height;

    // The synthetic skeleton is complete in every frame and every frame shows the subject,
    // so every cylinder is textured from a stored frame.
    EXPECT_EQ(e->provenance.UntexturedRate(), 0.0) << "k " << k;
    EXPECT_GT(e->provenance.subject_pixels, 5000) << "k " << k;
    // GL and its CPU oracle draw the same list (their agreement test's bound): the
    // provenance describes the measured picture.
    EXPECT_GE(e->reference_iou, 0.98) << "k " << k;

    // The silhouette depends only on the posed cylinders: the exact skeleton, radii fitted
    // to this subject's own masks. They cover the trunk and limbs and miss only where the
    // body is not a cylinder (hands, feet, shoulders, hair), so well over half the union
    // is shared; a silhouette off by a limb's width would fall far below.
    EXPECT_GT(e->comparison.iou, 0.6) << "k " << k;

    // At 0 degrees the viewer stands where the sensor stood, so the stored view is
    // re-rendered from the same pixels: colour errors only from JPEG, resampling and the
    // silhouette mismatch. An empty image errs on every subject pixel at full intensity.
    // Halving the mean squared error is +3 dB.
    EXPECT_GT(e->comparison.psnr_db, EmptyImagePsnr(e->truth) + 3.0) << "k " << k;

    // When Eq. 5 picks frame k itself, the mapping (Eq. 6-16 onto the same cylinders) takes
    // every surface point to itself, and viewer and sensor share their centre: each pixel
    // samples the stored frame along its own ray, where the sensor saw what the ground truth
    // shows at that pixel. So the wrong-part rate must equal the share of rendered pixels
    // whose cylinder's part differs from the true label at the pixel itself, computed here
    // from the ground truth alone (up to bilinear blending across label borders).
    if (e->frame.texture_frame != k) continue;
    ++same_frame;
    int subject = 0, disagree = 0;
    for (int y = 0; y < hgt; ++y)
      for (int x = 0; x < w; ++x) {
        const int part = e->reference.part.at(x, y);
        if (part < 0) continue;
        ++subject;
        disagree += e->truth.part_labels.at(x, y) != PartLabel(e->frame.cylinder_parts[part]);
      }
    const double expected = static_cast<double>(disagree) / subject;
    EXPECT_NEAR(e->provenance.WrongPartRate(), expected, 0.015) << "k " << k;
    // And it is low: a cylinder covers another part only where neighbours meet at a joint
    // or a limb crosses the trunk.
    EXPECT_LT(e->provenance.WrongPartRate(), 0.2) << "k " << k;
    // Against the part the truth shows at each pixel, that copy is right everywhere but
    // where bilinear samples straddle a label border or the cylinders overhang the body
    // (rendered, not true: the drawn part is expected and background was sampled).
    int overhang = 0;
    for (int y = 0; y < hgt; ++y)
      for (int x = 0; x < w; ++x)
        overhang += e->reference.part.at(x, y) >= 0 && e->truth.part_labels.at(x, y) == 0;
    EXPECT_LT(e->provenance.WrongSeenPartRate(), static_cast<double>(overhang) / subject + 0.015)
        << "k " << k;
    // Those wrong texels lie within a pixel of where the truth shows their part, or are
    // background: none is another part's texture 5 cm (about 10 px here) from that part.
    EXPECT_LT(e->provenance.DoubledLimbRate(), 0.001) << "k " << k;
  }
  // Frame k's own skeleton matches the viewer's exactly up to the re-aiming of the camera,
  // so Eq. 5 picks it for most frames.
  EXPECT_GE(same_frame, 3);
}

TEST(GlQualityEval, ShortRunWritesRowsPicturesAndMarkdown) {
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-gl-quality-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  QualityOptions options = ShortRun();
  options.image_dir = (dir / "pics").string();
  options.image_pairs = {{90, 90}};
  const auto run = RunQuality(options);
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_EQ(run->clip_frames, 180);
  ASSERT_EQ(run->rows.size(), 2u);
  for (const QualityRow& r : run->rows) {
    EXPECT_EQ(r.method, "thesis");
    EXPECT_EQ(r.n, 4);
    // Silhouettes depend on the pose only, not on the view's texture choice (see above).
    EXPECT_GT(r.iou, 0.6) << r.view_deg;
    EXPECT_GE(r.reference_iou, 0.98) << r.view_deg;
    EXPECT_GE(r.wrong_part_rate, 0.0);
    EXPECT_LE(r.wrong_part_rate, 1.0);
    EXPECT_TRUE(std::isfinite(r.psnr_db));
    EXPECT_GT(r.ms_per_frame, 0.0);
  }
  EXPECT_EQ(run->rows[0].view_deg, 0.0);
  EXPECT_EQ(run->rows[1].view_deg, 90.0);

  // The picture: three panels of the comparison box side by side (side_by_side.h).
  ASSERT_EQ(run->images.size(), 1u);
  const cv::Mat png = cv::imread(run->images[0].path, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(png.empty()) << run->images[0].path;
  EXPECT_EQ(png.channels(), 3);
  EXPECT_EQ((png.cols - 2 * 4) % 3, 0);
  EXPECT_LE(png.rows, 480);
  EXPECT_GT(png.rows, 100);  // a standing person seen from 3 m fills a good part of the height

  // The markdown: the table, the crop rule and a link to the picture relative to the file.
  const std::string md_path = (dir / "quality.md").string();
  const std::string md = QualityMarkdown(options, *run, md_path, MachineLine(run->gl_renderer));
  EXPECT_NE(md.find("| thesis | 90 | 4 |"), std::string::npos) << md;
  EXPECT_NE(md.find(kCropRule), std::string::npos);
  EXPECT_NE(md.find("](pics/thesis_f090_v090.png)"), std::string::npos) << md;
  ASSERT_TRUE(WriteTextFile(md_path, md).ok());
  std::ifstream in(md_path);
  std::stringstream back;
  back << in.rdbuf();
  EXPECT_EQ(back.str(), md);
  fs::remove_all(dir);
}

TEST(GlQualityEval, TrackedSkeletonsAreTheDepthTrackersWithinTheIssuesBound) {
  QualityOptions options = ShortRun();
  options.tracked_skeletons = true;
  auto h = QualityHarness::Create(options);
  ASSERT_TRUE(h.ok()) << h.error().message;
  ASSERT_EQ(h->clip().frame_count(), h->scene().frame_count());
  double sum = 0, largest = 0;
  for (int n = 0; n < h->clip().frame_count(); ++n) {
    const Skeleton& recorded = h->clip().frame(n).skeleton_in_world;
    const Skeleton truth = h->scene().skeleton_in_world(n);
    for (int j = 0; j < kJointCount; ++j) {
      const double e = (recorded.position[j] - truth.position[j]).norm();
      sum += e;
      largest = std::max(largest, e);
    }
  }
  // Not the scene's exact skeletons (the tracker fits noisy depth), and within issue 8's
  // goal for the tracker on turning (mean joint error at most 5 cm).
  EXPECT_GT(largest, 0.005);
  EXPECT_LT(sum / (kJointCount * h->clip().frame_count()), 0.05);
  // The harness reenacts from them like from any clip.
  const auto e = h->Evaluate(Thesis(), 90, kStep);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_GT(e->comparison.psnr_db, EmptyImagePsnr(e->truth));
}

TEST(GlQualityEval, FramesTheTrackerLosesAreLeftOutAndTheRestComparedAtTheirOwnTime) {
  // CesiumMan walking CMU 131_02 does not show the calibration pose, so our tracker gives no
  // skeleton on its first frames, until it starts without it (docs/measurements.md), and the
  // recorder stores no frame without a skeleton. (CesiumMan's walk-handheld, used here
  // before, loses no frame since the tracker leaves out the box beside its path.) Clip frame n
  // must then be compared with the scene frame it was recorded from, not with scene frame n:
  // the subject walks about 1.2 m/s, so a clip that is a frame or more behind the scene puts
  // every joint 4 cm or more off, well above a track that follows the truth.
  const fs::path data = fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() /
                        "shared" / "data";
  const fs::path glb = data / "models" / "CesiumMan.glb";
  const fs::path walk = data / "mocap" / "cmu-131_02-walk.bvh";
  if (!fs::exists(glb) || !fs::exists(walk)) GTEST_SKIP() << data << " not present";
  QualityOptions options;
  options.scenario = "bvh:" + walk.string();
  options.body = glb.string();
  options.tracked_skeletons = true;
  options.views_deg = {0};
  auto h = QualityHarness::Create(options);
  ASSERT_TRUE(h.ok()) << h.error().message;
  const int clip_frames = h->clip().frame_count();
  ASSERT_LT(clip_frames, h->scene().frame_count()) << "no frame lost: pick another scenario";
  auto joint_error = [&h](int n, int scene_frame) {
    const Skeleton truth = h->scene().skeleton_in_world(scene_frame);
    double sum = 0;
    for (int j = 0; j < kJointCount; ++j)
      sum += (h->clip().frame(n).skeleton_in_world.position[j] - truth.position[j]).norm();
    return sum / kJointCount;
  };
  double mapped = 0, shifted = 0;
  int after_loss = 0;
  for (int n = 0; n < clip_frames; ++n) {
    const int scene_frame = h->SceneFrame(n);
    ASSERT_GE(scene_frame, n);
    if (n > 0) {
      ASSERT_GT(scene_frame, h->SceneFrame(n - 1));
    }
    EXPECT_NEAR(h->clip().frame(n).timestamp_s * h->scene().frame_rate_hz(), scene_frame, 1e-6);
    if (scene_frame == n) continue;
    mapped += joint_error(n, scene_frame);
    shifted += joint_error(n, n);
    ++after_loss;
  }
  ASSERT_GT(after_loss, 0);
  // The tracker's error on that walk is 7-11 cm over seeds (8.7 on the first; issue 8); the
  // shifted comparison adds the walk's displacement to it, at least 4 cm a frame.
  EXPECT_LT(mapped / after_loss, 0.20);
  EXPECT_GT(shifted / after_loss, mapped / after_loss + 0.04);
  // The last clip frame is evaluated against the scene's own frame of that time.
  const auto e = h->Evaluate(Thesis(), 0, clip_frames - 1);
  ASSERT_TRUE(e.ok()) << e.error().message;
  EXPECT_GT(e->comparison.iou, 0.5);
}

TEST(GlQualityEval, ATrackerThatFindsNoOneIsATrackingErrorAndLeavesNothing) {
  // CMU 131_01's walk with the whole body turned onto the floor (root pitched 90 degrees, the
  // hips 17 cm up): a person lying down. The tracker follows people standing on the floor
  // (person_detector.h), so it gives no skeleton on any frame, and the recorder stores no
  // frame without one: the run must say so instead of comparing an empty clip.
  const fs::path data = fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() /
                        "shared" / "data";
  const fs::path walk = data / "mocap" / "cmu-131_01-walk.bvh";
  if (!fs::exists(walk)) GTEST_SKIP() << walk << " not present";
  const fs::path dir =
      fs::temp_directory_path() / ("reenact-gl-quality-lying-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path lying = dir / "lying.bvh";
  {
    std::ifstream in(walk);
    std::ofstream out(lying);
    std::string line;
    // Its lines may end in CR LF.
    while (std::getline(in, line) && line.rfind("MOTION", 0) != 0) out << line << "\n";
    std::getline(in, line);  // Frames: N
    std::string frame_time;
    std::getline(in, frame_time);
    constexpr int kFrames = 40;  // 120 Hz: 10 frames at the scene's 30
    out << "MOTION\nFrames: " << kFrames << "\n" << frame_time << "\n";
    for (int f = 0; f < kFrames && std::getline(in, line); ++f) {
      std::istringstream values(line);
      std::vector<std::string> v{std::istream_iterator<std::string>(values), {}};
      ASSERT_GT(v.size(), 6u);
      v[1] = "3";   // Yposition, CMU units of 5.644 cm
      v[5] = "90";  // Xrotation
      for (const std::string& x : v) out << x << " ";
      out << "\n";
    }
  }
  QualityOptions options;
  options.scenario = "bvh:" + lying.string();
  options.tracked_skeletons = true;
  options.views_deg = {0};
  const auto h = QualityHarness::Create(options);
  fs::remove_all(dir);
  ASSERT_FALSE(h.ok());
  EXPECT_EQ(h.error().code, "tracking");
  EXPECT_NE(h.error().message.find("no skeleton on any of the 10 frames"), std::string::npos)
      << h.error().message;
  EXPECT_NE(h.error().message.find("no person found"), std::string::npos) << h.error().message;
  EXPECT_FALSE(
      fs::exists(fs::temp_directory_path() / ("reenact-eval-" + std::to_string(::getpid()))));
}

TEST(GlQualityEval, ImagePairBeyondTheClipIsRefused) {
  QualityOptions options = ShortRun();
  options.views_deg = {0};
  options.image_dir =
      (fs::temp_directory_path() / ("reenact-gl-quality-bad-" + std::to_string(::getpid())))
          .string();
  options.image_pairs = {{180, 0}};  // frames are 0..179
  const auto run = RunQuality(options);
  ASSERT_FALSE(run.ok());
  EXPECT_EQ(run.error().code, "usage");
  EXPECT_NE(run.error().message.find("image frame 180 is beyond the clip's 180 frames"),
            std::string::npos)
      << run.error().message;
  EXPECT_FALSE(fs::exists(options.image_dir));  // refused before anything is written
}

}  // namespace
}  // namespace reenact::eval

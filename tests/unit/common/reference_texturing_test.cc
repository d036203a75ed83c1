// The CPU reference renderer's texture candidates and occlusion-aware modes
// (common/render/texturing.h) on constructed scenes whose answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error/check.h"
#include "common/render/reference_renderer.h"

namespace reenact {
namespace {

// Viewer camera with a principal point off the pixel grid; every crop is this whole camera,
// so with an identity stored_from_viewer a pixel samples exactly its own texel.
PinholeCamera Camera() { return PinholeCamera{160, 120, 200, 200, 80.3, 60.7, {}}; }

constexpr BodyPart kTorso = BodyPart::kLowerTorso;
constexpr BodyPart kArm = BodyPart::kLeftForearm;

// A crop of one colour, all subject, labelled `part` at depth `depth_m` everywhere.
ReferenceCrop Crop(uint8_t r, uint8_t g, uint8_t b, BodyPart part, float depth_m) {
  const PinholeCamera cam = Camera();
  ReferenceCrop crop;
  crop.color = ImageRgb8(cam.width, cam.height, 3);
  for (int i = 0; i < cam.width * cam.height; ++i) {
    crop.color.data[3 * i] = r;
    crop.color.data[3 * i + 1] = g;
    crop.color.data[3 * i + 2] = b;
  }
  crop.mask = ImageGray8(cam.width, cam.height, 1, 255);
  crop.camera = cam;
  crop.part_labels = ImageLabel8(cam.width, cam.height, 1, static_cast<uint8_t>(PartLabel(part)));
  crop.depth_m = Image<float>(cam.width, cam.height, 1, depth_m);
  return crop;
}

// The torso as a cylinder seen head-on: its near cap at depth 1 m is a disk of 30 px radius
// around (84.3, 58.7); every cap point maps to stored depth 1 m.
ReferencePart Torso(TexturingMode mode, const std::vector<const ReferenceCrop*>& crops,
                    const std::vector<double>& weights = {}) {
  ReferencePart part;
  part.cylinder = Cylinder{{0.02, -0.01, 1.0}, {0.02, -0.01, 1.5}, 0.15};
  part.part = kTorso;
  part.texturing = mode;
  for (size_t i = 0; i < crops.size(); ++i)
    part.candidates.push_back({crops[i], static_cast<int>(10 + i), Eigen::Matrix4d::Identity(),
                               weights.empty() ? 1.0 : weights[i]});
  return part;
}

const Eigen::Vector2d kCapCentre(84.3, 58.7);

// Calls f(x, y) for the pixels well inside the cap.
template <typename F>
int ForEachCapPixel(F f) {
  int n = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x)
      if ((Eigen::Vector2d(x, y) - kCapCentre).norm() < 28) {
        f(x, y);
        ++n;
      }
  return n;
}

ReferenceRender Render(const ReferencePart& part, const ReferenceRenderOptions& options = {}) {
  const std::vector<ReferencePart> parts = {part};
  return RenderReference(Camera(), parts, options);
}

TEST(ReferenceTexturing, TorsoOccludedByAnArmInCandidate0TakesItsColourFromCandidate1) {
  // Stored frame 0 (red): an arm 30 cm in front of the torso covers crop columns < 84.
  ReferenceCrop occluded = Crop(200, 0, 0, kTorso, 1.0f);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 84; ++x) {
      occluded.part_labels.at(x, y) = static_cast<uint8_t>(PartLabel(kArm));
      occluded.depth_m.at(x, y) = 0.7f;
    }
  const ReferenceCrop clear = Crop(0, 200, 0, kTorso, 1.0f);  // stored frame 1 (green)

  const ReferenceRender visible = Render(Torso(TexturingMode::kFirstVisible, {&occluded, &clear}));
  const ReferenceRender first = Render(Torso(TexturingMode::kFirst, {&occluded, &clear}));
  ForEachCapPixel([&](int x, int y) {
    const bool behind_arm = x < 84;
    EXPECT_EQ(visible.color.at(x, y, 0), behind_arm ? 0 : 200) << x << ", " << y;
    EXPECT_EQ(visible.color.at(x, y, 1), behind_arm ? 200 : 0) << x << ", " << y;
    EXPECT_EQ(visible.source_frame.at(x, y, 0), behind_arm ? 11 : 10);
    EXPECT_EQ(visible.source_frame.at(x, y, 1), -1);
    EXPECT_EQ(visible.source_weight.at(x, y, 0), 1.0f);
    EXPECT_FLOAT_EQ(visible.source_pixel.at(x, y, 0), static_cast<float>(x));
    EXPECT_FLOAT_EQ(visible.source_pixel.at(x, y, 1), static_cast<float>(y));
    // The thesis rule ignores visibility: candidate 0 everywhere.
    EXPECT_EQ(first.color.at(x, y, 0), 200);
    EXPECT_EQ(first.source_frame.at(x, y, 0), 10);
  });
}

TEST(ReferenceTexturing, BlendOfTwoVisibleCandidatesIsTheirWeightedMean) {
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f), green = Crop(0, 200, 0, kTorso, 1.0f);
  // A third candidate with a large weight that shows the arm there: not visible, no share.
  const ReferenceCrop arm = Crop(0, 0, 200, kArm, 1.0f);
  const ReferenceRender r =
      Render(Torso(TexturingMode::kBlendVisible, {&red, &arm, &green}, {1.0, 5.0, 3.0}));
  EXPECT_GT(ForEachCapPixel([&](int x, int y) {
              // (1 (200, 0, 0) + 3 (0, 200, 0)) / 4.
              EXPECT_EQ(r.color.at(x, y, 0), 50);
              EXPECT_EQ(r.color.at(x, y, 1), 150);
              EXPECT_EQ(r.color.at(x, y, 2), 0);
              EXPECT_EQ(r.source_frame.at(x, y, 0), 10);
              EXPECT_EQ(r.source_frame.at(x, y, 1), 12);
              EXPECT_EQ(r.source_frame.at(x, y, 2), -1);
              EXPECT_FLOAT_EQ(r.source_weight.at(x, y, 0), 0.25f);
              EXPECT_FLOAT_EQ(r.source_weight.at(x, y, 1), 0.75f);
              EXPECT_EQ(r.source_weight.at(x, y, 2), 0.0f);
            }),
            2000);
}

TEST(ReferenceTexturing, DepthDisagreementBeyondTheToleranceRejectsACandidate) {
  ReferenceRenderOptions options;
  options.depth_tolerance_m = 0.1;
  const ReferenceCrop green = Crop(0, 200, 0, kTorso, 1.0f);
  // Candidate 0 labels the torso everywhere, its stored depth is off by `offset`.
  for (const auto& [offset, rejected] : std::vector<std::pair<float, bool>>{
           {0.09f, false}, {-0.09f, false}, {0.11f, true}, {-0.11f, true}, {0.5f, true}}) {
    const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f + offset);
    for (TexturingMode mode : {TexturingMode::kFirstVisible, TexturingMode::kBlendVisible}) {
      const ReferenceRender r = Render(Torso(mode, {&red, &green}, {1.0, 0.0}), options);
      ForEachCapPixel([&](int x, int y) {
        ASSERT_EQ(r.color.at(x, y, 0), rejected ? 0 : 200) << offset;
        ASSERT_EQ(r.source_frame.at(x, y, 0), rejected ? 11 : 10) << offset;
      });
    }
  }
  // No depth reading (0): only the label test applies.
  const ReferenceCrop no_reading = Crop(200, 0, 0, kTorso, 0.0f);
  const ReferenceRender r = Render(Torso(TexturingMode::kFirstVisible, {&no_reading, &green}));
  ForEachCapPixel([&](int x, int y) { ASSERT_EQ(r.color.at(x, y, 0), 200); });
}

TEST(ReferenceTexturing, WithoutAVisibleCandidateTheFirstUsableOneColoursElseNothing) {
  // Both show the arm: none visible, so the first whose mask covers the point colours it.
  ReferenceCrop off_subject = Crop(200, 0, 0, kArm, 1.0f);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 84; ++x) off_subject.mask.at(x, y) = 0;
  const ReferenceCrop arm = Crop(0, 200, 0, kArm, 1.0f);
  for (TexturingMode mode : {TexturingMode::kFirstVisible, TexturingMode::kBlendVisible}) {
    const ReferenceRender r = Render(Torso(mode, {&off_subject, &arm}), {});
    ForEachCapPixel([&](int x, int y) {
      // Bilinear alpha at a texel centre is that texel's mask.
      ASSERT_EQ(r.color.at(x, y, 1), x < 84 ? 200 : 0) << x;
      ASSERT_EQ(r.source_frame.at(x, y, 0), x < 84 ? 11 : 10) << x;
    });
  }
  // Only the half-masked candidate: the uncovered half is discarded in every mode.
  for (TexturingMode mode :
       {TexturingMode::kFirst, TexturingMode::kFirstVisible, TexturingMode::kBlendVisible}) {
    const ReferenceRender r = Render(Torso(mode, {&off_subject}));
    ForEachCapPixel([&](int x, int y) { ASSERT_EQ(r.mask.at(x, y), x < 84 ? 0 : 255) << x; });
  }
  // kFirst never looks past candidate 0.
  const ReferenceRender first = Render(Torso(TexturingMode::kFirst, {&off_subject, &arm}));
  ForEachCapPixel([&](int x, int y) { ASSERT_EQ(first.mask.at(x, y), x < 84 ? 0 : 255) << x; });
}

TEST(ReferenceTexturing, ACropWithoutPartLabelsHasNoVisiblePoint) {
  ReferenceCrop unlabelled = Crop(200, 0, 0, kTorso, 1.0f);
  unlabelled.part_labels = ImageLabel8();
  const ReferenceCrop green = Crop(0, 200, 0, kTorso, 1.0f);
  const ReferenceRender r = Render(Torso(TexturingMode::kFirstVisible, {&unlabelled, &green}));
  ForEachCapPixel([&](int x, int y) { ASSERT_EQ(r.color.at(x, y, 1), 200); });
  // Alone it still colours by the usable rule.
  const ReferenceRender alone = Render(Torso(TexturingMode::kBlendVisible, {&unlabelled}));
  ForEachCapPixel([&](int x, int y) { ASSERT_EQ(alone.color.at(x, y, 0), 200); });
}

TEST(ReferenceTexturing, BlendWithZeroWeightsFallsBackToTheFirstVisible) {
  const ReferenceCrop arm = Crop(0, 0, 200, kArm, 1.0f);
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f), green = Crop(0, 200, 0, kTorso, 1.0f);
  const ReferenceRender r =
      Render(Torso(TexturingMode::kBlendVisible, {&arm, &red, &green}, {1.0, 0.0, 0.0}));
  ForEachCapPixel([&](int x, int y) {
    ASSERT_EQ(r.color.at(x, y, 0), 200);
    ASSERT_EQ(r.source_frame.at(x, y, 0), 11);
    ASSERT_EQ(r.source_weight.at(x, y, 0), 1.0f);
  });
}

// The torso with `ranked` candidates and then `fallbacks`, in `mode`.
ReferencePart TorsoWithFallbacks(TexturingMode mode,
                                 const std::vector<const ReferenceCrop*>& ranked,
                                 const std::vector<const ReferenceCrop*>& fallbacks) {
  std::vector<const ReferenceCrop*> crops = ranked;
  crops.insert(crops.end(), fallbacks.begin(), fallbacks.end());
  ReferencePart part = Torso(mode, crops);
  for (size_t i = ranked.size(); i < crops.size(); ++i) {
    part.candidates[i].fallback = true;
    part.candidates[i].weight = 0;
  }
  return part;
}

TEST(ReferenceTexturing, AFallbackReplacesARankedTexelThatShowsAnotherPart) {
  // The ranked candidate's texels show the arm (in front of the torso there); of the two
  // fallbacks, the first shows the arm too, the second the torso: the second colours.
  const ReferenceCrop arm_red = Crop(200, 0, 0, kArm, 1.0f);
  const ReferenceCrop arm_blue = Crop(0, 0, 200, kArm, 1.0f);
  const ReferenceCrop green = Crop(0, 200, 0, kTorso, 1.0f);
  for (TexturingMode mode : {TexturingMode::kFirstVisible, TexturingMode::kBlendVisible}) {
    const ReferenceRender r = Render(TorsoWithFallbacks(mode, {&arm_red}, {&arm_blue, &green}));
    EXPECT_GT(ForEachCapPixel([&](int x, int y) {
                ASSERT_EQ(r.color.at(x, y, 1), 200);
                ASSERT_EQ(r.source_frame.at(x, y, 0), 12);
                ASSERT_EQ(r.source_weight.at(x, y, 0), 1.0f);
                ASSERT_EQ(r.source_frame.at(x, y, 1), -1);
              }),
              2000);
    // Without a visible fallback, the first usable ranked candidate as before.
    const ReferenceRender none = Render(TorsoWithFallbacks(mode, {&arm_red}, {&arm_blue}));
    ForEachCapPixel([&](int x, int y) { ASSERT_EQ(none.color.at(x, y, 0), 200); });
  }
}

TEST(ReferenceTexturing, AFallbackNeverReplacesAVisibleOrThisPartsTexelNorWidensTheSilhouette) {
  ReferenceRenderOptions options;
  options.depth_tolerance_m = 0.1;
  const ReferenceCrop green = Crop(0, 200, 0, kTorso, 1.0f);
  // Visible ranked candidate: its colour.
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f);
  // This part's label, but the stored depth 0.5 m off: not visible, yet not an occluder.
  const ReferenceCrop red_far = Crop(200, 0, 0, kTorso, 1.5f);
  // Another part's label, but off the subject on the left half: unusable there.
  ReferenceCrop arm_half = Crop(200, 0, 0, kArm, 1.0f);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 84; ++x) arm_half.mask.at(x, y) = 0;
  for (TexturingMode mode : {TexturingMode::kFirstVisible, TexturingMode::kBlendVisible}) {
    for (const ReferenceCrop* ranked : {&red, &red_far}) {
      const ReferenceRender r = Render(TorsoWithFallbacks(mode, {ranked}, {&green}), options);
      ForEachCapPixel([&](int x, int y) { ASSERT_EQ(r.color.at(x, y, 0), 200); });
    }
    const ReferenceRender r = Render(TorsoWithFallbacks(mode, {&arm_half}, {&green}), options);
    ForEachCapPixel([&](int x, int y) {
      ASSERT_EQ(r.mask.at(x, y), x < 84 ? 0 : 255) << x;  // no ranked texel: discarded
      if (x >= 84) {
        ASSERT_EQ(r.color.at(x, y, 1), 200) << x;
      }
    });
  }
  // kFirst ignores every candidate past the first, fallbacks too.
  const ReferenceRender first =
      Render(TorsoWithFallbacks(TexturingMode::kFirst, {&arm_half}, {&green}), options);
  ForEachCapPixel([&](int x, int y) {
    ASSERT_EQ(first.mask.at(x, y), x < 84 ? 0 : 255) << x;
    if (x >= 84) {
      ASSERT_EQ(first.color.at(x, y, 0), 200) << x;
    }
  });
}

TEST(ReferenceTexturing, RejectsARankedCandidateAfterAFallback) {
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f);
  ReferencePart part = TorsoWithFallbacks(TexturingMode::kBlendVisible, {&red}, {&red});
  std::swap(part.candidates[0], part.candidates[1]);
  EXPECT_THROW(Render(part), CheckError);
}

TEST(ReferenceTexturing, RejectsMoreCandidatesThanTheMaximum) {
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f);
  EXPECT_THROW(Render(Torso(TexturingMode::kFirst,
                            std::vector<const ReferenceCrop*>(kMaxTextureCandidates + 1, &red))),
               CheckError);
}

TEST(ReferenceTexturing, RejectsANegativeOrNonFiniteWeight) {
  const ReferenceCrop red = Crop(200, 0, 0, kTorso, 1.0f);
  EXPECT_THROW(Render(Torso(TexturingMode::kBlendVisible, {&red}, {-1.0})), CheckError);
  EXPECT_THROW(Render(Torso(TexturingMode::kBlendVisible, {&red}, {std::nan("")})), CheckError);
}

TEST(ReferenceTexturing, RejectsLabelsOrDepthOfAnotherSize) {
  ReferenceCrop labels = Crop(200, 0, 0, kTorso, 1.0f);
  labels.part_labels = ImageLabel8(3, 3, 1, 0);
  EXPECT_THROW(Render(Torso(TexturingMode::kFirstVisible, {&labels})), CheckError);
  ReferenceCrop depth = Crop(200, 0, 0, kTorso, 1.0f);
  depth.depth_m = Image<float>(160, 120, 2, 0.0f);
  EXPECT_THROW(Render(Torso(TexturingMode::kFirstVisible, {&depth})), CheckError);
}

TEST(ReferenceTexturing, RejectsANegativeDepthTolerance) {
  ReferenceRenderOptions options;
  options.depth_tolerance_m = -0.01;
  EXPECT_THROW(options.Check(), CheckError);
}

}  // namespace
}  // namespace reenact

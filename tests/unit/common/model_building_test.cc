#include "common/model/model_building.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error/check.h"
#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

constexpr std::array<BodyPart, 6> kFreeLimbs = {BodyPart::kLeftUpperArm,  BodyPart::kLeftForearm,
                                                BodyPart::kRightUpperArm, BodyPart::kRightForearm,
                                                BodyPart::kLeftShin,      BodyPart::kRightShin};

RadiusRatios Truth() {
  RadiusRatios truth = DefaultRadiusRatios();
  truth[Index(BodyPart::kLeftUpperArm)] = 0.2;
  truth[Index(BodyPart::kRightForearm)] = 0.1;
  return truth;
}

// A clip whose frames are rendered on request from its skeletons and the true ratios;
// records the frames asked for.
struct SyntheticClip {
  std::vector<Skeleton> skeletons;
  RadiusRatios truth = Truth();
  PinholeCamera camera = PinholeCamera::KinectLike();
  std::vector<int> requested;
  std::vector<int> unavailable;  // frames whose images "cannot be decoded"
  std::vector<int> empty_mask;   // frames whose mask comes back empty
  std::vector<int> fat_mask;     // frames whose mask is dilated by 6 pixels

  ModelFrameImagesFn Fn() {
    return [this](int n) -> std::optional<ModelFrameImages> {
      requested.push_back(n);
      const auto has = [n](const std::vector<int>& v) {
        return std::find(v.begin(), v.end(), n) != v.end();
      };
      if (has(unavailable)) return std::nullopt;
      ModelFrameImages im{camera, {}, {}};
      testing::RayCastCylinders(PoseCylinders(skeletons[n], truth), camera, im.depth, im.mask);
      if (has(empty_mask)) im.mask = ImageGray8(camera.width, camera.height, 1, 0);
      if (has(fat_mask)) {
        const ImageGray8 m = im.mask;
        const ImageDepthMm d = im.depth;
        for (int y = 0; y < m.height; ++y)
          for (int x = 0; x < m.width; ++x)
            for (int dy = -6; dy <= 6 && !im.mask.at(x, y); ++dy)
              for (int dx = -6; dx <= 6; ++dx)
                if (m.Contains(x + dx, y + dy) && m.at(x + dx, y + dy)) {
                  im.mask.at(x, y) = 255;
                  im.depth.at(x, y) = d.at(x + dx, y + dy);
                  break;
                }
      }
      return im;
    };
  }
};

double LimbError(const RadiusRatios& fitted, const RadiusRatios& truth, BodyPart p) {
  return std::abs(fitted[Index(p)] - truth[Index(p)]) / truth[Index(p)];
}

TEST(ModelBuilding, FitsTheRepresentativeFrameOfAClip) {
  SyntheticClip clip;
  clip.skeletons = {StandingPerson(3, 0, false), StandingPerson(3, 0.9, true),
                    StandingPerson(3, 0.4, true), StandingPerson(2.6, 0, true),
                    StandingPerson(3, 0, true, /*crossed_legs=*/true)};
  // Arms held straight out, facing the camera, legs apart: frame 3 (Eq. 2-4).
  const ModelBuildResult r = BuildCylinderModel(clip.skeletons, clip.Fn());
  ASSERT_EQ(r.representative_frame, 3);
  EXPECT_EQ(r.fitted_frames, std::vector<int>{3});
  EXPECT_EQ(clip.requested, std::vector<int>{3});  // only the chosen frame is fetched
  for (BodyPart p : kFreeLimbs) {
    ASSERT_TRUE(r.fitted[Index(p)]) << PartName(p);
    EXPECT_EQ(r.outcome[Index(p)], PartFitOutcome::kFitted);
    EXPECT_EQ(r.fit_count[Index(p)], 1);
    EXPECT_LT(LimbError(r.radius_ratio, clip.truth, p), 0.1) << PartName(p);
  }
}

TEST(ModelBuilding, UnavailableImagesPassToTheNextRankedFrame) {
  SyntheticClip clip;
  clip.skeletons = {StandingPerson(3, 0.4, true), StandingPerson(3, 0, true),
                    StandingPerson(3, 0.9, true)};
  clip.unavailable = {1};
  const ModelBuildResult r = BuildCylinderModel(clip.skeletons, clip.Fn());
  EXPECT_EQ(r.skipped_frames, std::vector<int>{1});
  EXPECT_EQ(r.representative_frame, 0);  // yaw 0.4 scores above yaw 0.9
  EXPECT_EQ(clip.requested, (std::vector<int>{1, 0}));
  EXPECT_GT(r.fitted_count(), 0);
}

TEST(ModelBuilding, RobustKBestBeatsASingleCorruptedFrame) {
  SyntheticClip clip;
  for (double yaw : {0.2, 0.0, 0.1, 0.3, 0.4})
    clip.skeletons.push_back(StandingPerson(3, yaw, true));
  clip.fat_mask = {1};  // the best frame by F(n) has a badly dilated person mask

  const ModelBuildResult single = BuildCylinderModel(clip.skeletons, clip.Fn());
  ASSERT_EQ(single.representative_frame, 1);
  ModelBuildOptions robust_options;
  robust_options.robust_k = 3;
  const ModelBuildResult robust = BuildCylinderModel(clip.skeletons, clip.Fn(), robust_options);
  EXPECT_EQ(robust.fitted_frames, (std::vector<int>{1, 2, 0}));
  ASSERT_EQ(robust.frame_scores.size(), 3u);
  EXPECT_GE(robust.frame_scores[0], robust.frame_scores[1]);
  EXPECT_GE(robust.frame_scores[1], robust.frame_scores[2]);

  double single_sum = 0, robust_sum = 0;
  for (BodyPart p : kFreeLimbs) {
    ASSERT_TRUE(single.fitted[Index(p)] && robust.fitted[Index(p)]) << PartName(p);
    EXPECT_EQ(robust.fit_count[Index(p)], 3);
    const double e1 = LimbError(single.radius_ratio, clip.truth, p);
    const double ek = LimbError(robust.radius_ratio, clip.truth, p);
    EXPECT_LE(ek, e1 + 1e-12) << PartName(p);
    EXPECT_LT(ek, 0.1) << PartName(p);
    single_sum += e1;
    robust_sum += ek;
  }
  // The dilation adds 12 pixels to bands 15-25 pixels wide: the single fit is far off.
  EXPECT_GT(single_sum / kFreeLimbs.size(), 0.3);
  EXPECT_LT(robust_sum, single_sum);
}

TEST(ModelBuilding, EveryJointMissingFitsNothingAndFetchesNothing) {
  SyntheticClip clip;
  clip.skeletons.assign(4, Skeleton{});
  ModelBuildOptions options;
  options.robust_k = 3;
  const ModelBuildResult r = BuildCylinderModel(clip.skeletons, clip.Fn(), options);
  EXPECT_FALSE(r.representative_frame);
  EXPECT_TRUE(r.fitted_frames.empty());
  EXPECT_TRUE(clip.requested.empty());
  EXPECT_EQ(r.radius_ratio, DefaultRadiusRatios());
  EXPECT_EQ(r.fitted_count(), 0);
  for (PartFitOutcome o : r.outcome) EXPECT_EQ(o, PartFitOutcome::kNoFrame);
  EXPECT_EQ(PartFitOutcomeName(PartFitOutcome::kNoFrame), "no_frame");

  const ModelBuildResult none = BuildCylinderModel({}, clip.Fn());
  EXPECT_FALSE(none.representative_frame);
}

TEST(ModelBuilding, MissingHeadAndSubMillimetreBonesKeepTheirDefaults) {
  SyntheticClip clip;
  Skeleton s = StandingPerson(3, 0, true);
  s.confidence[Index(Joint::kHead)] = 0;                                          // head lost
  s.Set(Joint::kLeftElbow, s[Joint::kLeftHand] + Eigen::Vector3d(0.0005, 0, 0));  // 0.5 mm forearm
  s.Set(Joint::kRightKnee, s[Joint::kRightFoot]);  // zero-length shin
  clip.skeletons = {s};
  const ModelBuildResult r = BuildCylinderModel(clip.skeletons, clip.Fn());
  ASSERT_EQ(r.representative_frame, 0);
  EXPECT_EQ(r.outcome[Index(BodyPart::kHead)], PartFitOutcome::kMissingJoint);
  EXPECT_EQ(r.outcome[Index(BodyPart::kLeftForearm)], PartFitOutcome::kShortBone);
  EXPECT_EQ(r.outcome[Index(BodyPart::kRightShin)], PartFitOutcome::kShortBone);
  for (BodyPart p : {BodyPart::kHead, BodyPart::kLeftForearm, BodyPart::kRightShin}) {
    EXPECT_FALSE(r.fitted[Index(p)]);
    EXPECT_EQ(r.radius_ratio[Index(p)], DefaultRadiusRatios()[Index(p)]);
  }
  for (double ratio : r.radius_ratio) EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_TRUE(r.fitted[Index(BodyPart::kRightForearm)]);
}

TEST(ModelBuilding, EmptyMaskKeepsDefaultsUnlessOtherFramesFitTheParts) {
  SyntheticClip clip;
  clip.skeletons = {StandingPerson(3, 0.3, true), StandingPerson(3, 0, true),
                    StandingPerson(3, 0.15, true)};
  clip.empty_mask = {1};
  const ModelBuildResult single = BuildCylinderModel(clip.skeletons, clip.Fn());
  ASSERT_EQ(single.representative_frame, 1);
  EXPECT_EQ(single.fitted_count(), 0);
  EXPECT_EQ(single.radius_ratio, DefaultRadiusRatios());
  for (PartFitOutcome o : single.outcome) EXPECT_EQ(o, PartFitOutcome::kNoPixels);

  ModelBuildOptions options;
  options.robust_k = 3;
  const ModelBuildResult robust = BuildCylinderModel(clip.skeletons, clip.Fn(), options);
  for (BodyPart p : kFreeLimbs) {
    EXPECT_EQ(robust.fit_count[Index(p)], 2) << PartName(p);
    EXPECT_LT(LimbError(robust.radius_ratio, clip.truth, p), 0.1) << PartName(p);
  }
  options.min_part_fits = 3;  // demand a fit in every frame: the empty one breaks it
  const ModelBuildResult strict = BuildCylinderModel(clip.skeletons, clip.Fn(), options);
  for (BodyPart p : kFreeLimbs) EXPECT_EQ(strict.outcome[Index(p)], PartFitOutcome::kTooFewFits);
}

TEST(ModelBuilding, ImagesThatDisagreeWithTheCameraAreSkipped) {
  const std::vector<Skeleton> skeletons = {StandingPerson(3, 0, true)};
  const ModelBuildResult r = BuildCylinderModel(skeletons, [](int) {
    return std::optional<ModelFrameImages>(ModelFrameImages{
        PinholeCamera::KinectLike(), ImageDepthMm(320, 240, 1, 0), ImageGray8(640, 480, 1, 0)});
  });
  EXPECT_EQ(r.skipped_frames, std::vector<int>{0});
  EXPECT_FALSE(r.representative_frame);
}

TEST(ModelBuilding, BadOptionsAreABug) {
  const std::vector<Skeleton> skeletons = {StandingPerson(3, 0, true)};
  const ModelFrameImagesFn none = [](int) { return std::optional<ModelFrameImages>(); };
  ModelBuildOptions options;
  options.robust_k = 0;
  EXPECT_THROW(BuildCylinderModel(skeletons, none, options), CheckError);
  options.robust_k = 3;
  options.min_part_fits = 4;
  EXPECT_THROW(BuildCylinderModel(skeletons, none, options), CheckError);
  EXPECT_THROW(BuildCylinderModel(skeletons, ModelFrameImagesFn{}), CheckError);
}

}  // namespace
}  // namespace reenact

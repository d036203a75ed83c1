#include "viewer-client/play/texturing_presets.h"

#include <gtest/gtest.h>

namespace reenact::viewer {
namespace {

TEST(TexturingPresets, EachAddsOneStepAndAllPassCheck) {
  const TexturingOptions thesis = TexturingPreset("thesis").value();
  EXPECT_EQ(thesis.selection, TextureSelection::kWholeBody);
  EXPECT_EQ(thesis.mode, TexturingMode::kFirst);
  const TexturingOptions per_part = TexturingPreset("per-part").value();
  EXPECT_EQ(per_part.selection, TextureSelection::kPerPart);
  EXPECT_EQ(per_part.mode, TexturingMode::kFirst);
  const TexturingOptions occlusion = TexturingPreset("occlusion").value();
  EXPECT_EQ(occlusion.mode, TexturingMode::kFirstVisible);
  EXPECT_GT(occlusion.candidates, 1);
  const TexturingOptions blend = TexturingPreset("blend").value();
  EXPECT_EQ(blend.mode, TexturingMode::kBlendVisible);
  EXPECT_GT(blend.hysteresis, 0.0);
  EXPECT_EQ(blend.shape, BodyShape::kCylinders);
  const TexturingOptions shape = TexturingPreset("shape").value();
  EXPECT_EQ(shape.shape, BodyShape::kExtended);
  EXPECT_EQ(shape.mode, TexturingMode::kBlendVisible);
  const TexturingOptions profile = TexturingPreset("profile").value();
  EXPECT_EQ(profile.shape, BodyShape::kProfiled);
  EXPECT_EQ(profile.mode, TexturingMode::kBlendVisible);
  EXPECT_FALSE(profile.relight);
  const TexturingOptions relit = TexturingPreset("relit").value();
  EXPECT_EQ(relit.shape, BodyShape::kProfiled);
  EXPECT_EQ(relit.mode, TexturingMode::kBlendVisible);
  EXPECT_TRUE(relit.relight);
  EXPECT_EQ(relit.fallback_candidates, 0);
  const TexturingOptions fallback = TexturingPreset("fallback").value();
  EXPECT_TRUE(fallback.relight);
  EXPECT_EQ(fallback.candidates, relit.candidates);
  EXPECT_EQ(fallback.candidates + fallback.fallback_candidates, kMaxTextureCandidates);
  for (const TexturingOptions& o :
       {thesis, per_part, occlusion, blend, shape, profile, relit, fallback})
    EXPECT_NO_THROW(o.Check());
}

TEST(TexturingPresets, UnknownNameIsAUsageErrorListingTheKnownOnes) {
  const auto r = TexturingPreset("Blend");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, "usage");
  EXPECT_NE(
      r.error().message.find("thesis, per-part, occlusion, blend, shape, profile, relit, fallback"),
      std::string::npos);
}

}  // namespace
}  // namespace reenact::viewer

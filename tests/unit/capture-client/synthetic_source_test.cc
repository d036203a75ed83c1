// The synthetic: capture source's choice of body:
// synthetic:SCENARIO[?body=FILE.glb[&body_height=M]].

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "capture-client/source/frame_source.h"

namespace reenact::capture {
namespace {

const std::string kCesiumMan = std::string(REENACT_SHARED_DATA_DIR) + "/models/CesiumMan.glb";

TEST(SyntheticSource, SpecChoosesTheBody) {
  if (!std::filesystem::exists(kCesiumMan)) GTEST_SKIP() << kCesiumMan << " is absent";
  Expected<std::unique_ptr<FrameSource>> s =
      OpenFrameSource("synthetic:turn-and-kick?body=" + kCesiumMan + "&body_height=1.7");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_NE((*s)->info().description.find("CesiumMan.glb"), std::string::npos);
  Expected<std::optional<SensorFrame>> f = (*s)->Next();
  ASSERT_TRUE(f.ok() && f->has_value());
  const Skeleton& sk = *(*f)->skeleton_in_world;
  // Scaled to 1.7 m: the head centre sits well below 1.7 m but above CesiumMan's own 1.51 m
  // body's head centre (1.34 m), and the feet near the floor.
  EXPECT_GT(sk[Joint::kHead].z(), 1.36);
  EXPECT_LT(sk[Joint::kHead].z(), 1.7);
  // Default and explicit procedural body are the same scene.
  Expected<std::unique_ptr<FrameSource>> a = OpenFrameSource("synthetic:calibration");
  Expected<std::unique_ptr<FrameSource>> b =
      OpenFrameSource("synthetic:calibration?body=procedural");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ((*(*a)->Next())->color.data, (*(*b)->Next())->color.data);
}

TEST(SyntheticSource, SpecPlaysTheCloseUp) {
  // upper-body-turn: 195 frames from a sensor 0.9 m in front of the subject; the subject's
  // nearest pixel has a reading (beyond the 0.4 m minimum range), none farther than 1.2 m.
  Expected<std::unique_ptr<FrameSource>> s = OpenFrameSource("synthetic:upper-body-turn");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ((*s)->info().frame_count, 195);
  Expected<std::optional<SensorFrame>> f = (*s)->Next();
  ASSERT_TRUE(f.ok() && f->has_value());
  const SensorFrame& frame = **f;
  ASSERT_TRUE(frame.world_from_sensor && frame.skeleton_in_world && frame.person_mask);
  int subject = 0;
  uint16_t nearest = 65535, farthest = 0;
  for (size_t i = 0; i < frame.depth.data.size(); ++i) {
    if (!frame.person_mask->data[i]) continue;
    ++subject;
    nearest = std::min(nearest, frame.depth.data[i]);
    farthest = std::max(farthest, frame.depth.data[i]);
  }
  EXPECT_GT(subject, 640 * 480 / 10);
  EXPECT_GE(nearest, 400);
  EXPECT_LE(farthest, 1200);
}

TEST(SyntheticSource, BadOptionsAreUsageErrors) {
  for (const std::string spec : {"synthetic:", "synthetic:turn-and-kick?bod=x.glb",
                                 "synthetic:turn-and-kick?body_height=1.6",
                                 "synthetic:turn-and-kick?body=x.glb&body_height=-1",
                                 "synthetic:turn-and-kick?body=x.glb&body_height=tall"}) {
    const Expected<std::unique_ptr<FrameSource>> s = OpenFrameSource(spec);
    ASSERT_FALSE(s.ok()) << spec;
    EXPECT_EQ(s.error().code, "usage") << spec << ": " << s.error().message;
  }
  const Expected<std::unique_ptr<FrameSource>> bvh = OpenFrameSource("synthetic:model-walk");
  ASSERT_FALSE(bvh.ok());
  EXPECT_NE(bvh.error().message.find("needs a skinned body"), std::string::npos);
}

}  // namespace
}  // namespace reenact::capture

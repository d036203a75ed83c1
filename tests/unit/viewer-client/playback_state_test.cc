// The interactive players' clock and toggles (viewer-client/play/playback_state.h), against
// the arithmetic its header states.
#include "viewer-client/play/playback_state.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::viewer {
namespace {

PlaybackState Ten() { return PlaybackState(10, OrbitCameraOptions{}, true, false); }

TEST(PlaybackState, AdvancesByWallTimeTimesSpeedAndWraps) {
  PlaybackState s = Ten();
  s.Advance(0.25, 12);  // 3 frames (binary-exact figures)
  EXPECT_EQ(s.frame(), 3);
  s.OnCommand(ViewerCommand::kFaster);  // speed 2
  EXPECT_DOUBLE_EQ(s.speed(), 2);
  s.Advance(0.5, 12);  // 12 more: 15 mod 10
  EXPECT_EQ(s.frame(), 5);
  for (int i = 0; i < 10; ++i) s.OnCommand(ViewerCommand::kFaster);
  EXPECT_DOUBLE_EQ(s.speed(), 8);
  for (int i = 0; i < 10; ++i) s.OnCommand(ViewerCommand::kSlower);
  EXPECT_DOUBLE_EQ(s.speed(), 0.125);
}

TEST(PlaybackState, PauseHoldsAndStepsPauseAndWrap) {
  PlaybackState s = Ten();
  s.OnCommand(ViewerCommand::kTogglePlay);
  EXPECT_FALSE(s.playing());
  s.Advance(1.0, 30);
  EXPECT_EQ(s.frame(), 0);
  s.OnCommand(ViewerCommand::kTogglePlay);
  s.OnCommand(ViewerCommand::kStepBackward);  // from 0 to 9, paused
  EXPECT_FALSE(s.playing());
  EXPECT_EQ(s.frame(), 9);
  s.OnCommand(ViewerCommand::kStepForward);
  EXPECT_EQ(s.frame(), 0);
}

TEST(PlaybackState, TogglesAndQuit) {
  PlaybackState s = Ten();
  s.OnCommand(ViewerCommand::kToggleSkeleton);
  EXPECT_TRUE(s.skeleton());
  s.OnCommand(ViewerCommand::kToggleTexture);
  EXPECT_FALSE(s.textured());
  s.OnCommand(ViewerCommand::kToggleTexture);
  s.OnCommand(ViewerCommand::kToggleBareCylinders);
  EXPECT_FALSE(s.textured());
  EXPECT_FALSE(s.quit());
  s.OnCommand(ViewerCommand::kQuit);
  EXPECT_TRUE(s.quit());
}

TEST(PlaybackState, OrbitAndZoomStayInTheirRanges) {
  PlaybackState s = Ten();
  s.OnOrbit(100, 0);
  EXPECT_DOUBLE_EQ(s.orbit().angle_deg, OrbitCameraOptions{}.angle_deg - 30);
  s.OnOrbit(0, 1e6);
  EXPECT_DOUBLE_EQ(s.orbit().height_offset_m, 2.5);
  s.OnZoom(1000);
  EXPECT_DOUBLE_EQ(s.orbit().distance_scale, 0.3);
  s.OnZoom(-1000);
  EXPECT_DOUBLE_EQ(s.orbit().distance_scale, 4.0);
}

TEST(PlaybackState, RefusesAnEmptyClip) {
  EXPECT_THROW(PlaybackState(0, OrbitCameraOptions{}, true, false), CheckError);
}

}  // namespace
}  // namespace reenact::viewer

#include "viewer-client/play/playback_state.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"

namespace reenact::viewer {

PlaybackState::PlaybackState(int frame_count, const OrbitCameraOptions& orbit, bool textured,
                             bool draw_skeleton)
    : frame_count_(frame_count), orbit_(orbit), textured_(textured), skeleton_(draw_skeleton) {
  REENACT_CHECK(frame_count >= 1, "a clip to play has at least one frame");
}

void PlaybackState::OnCommand(ViewerCommand c) {
  switch (c) {
    case ViewerCommand::kTogglePlay:
      playing_ = !playing_;
      break;
    case ViewerCommand::kStepBackward:
      Step(-1);
      break;
    case ViewerCommand::kStepForward:
      Step(+1);
      break;
    case ViewerCommand::kFaster:
      speed_ = std::min(8.0, speed_ * 2);
      break;
    case ViewerCommand::kSlower:
      speed_ = std::max(0.125, speed_ / 2);
      break;
    case ViewerCommand::kToggleSkeleton:
      skeleton_ = !skeleton_;
      break;
    case ViewerCommand::kToggleBareCylinders:
      textured_ = false;
      break;
    case ViewerCommand::kToggleTexture:
      textured_ = !textured_;
      break;
    case ViewerCommand::kQuit:
      quit_ = true;
      break;
  }
}

void PlaybackState::OnOrbit(double dx, double dy) {
  orbit_.angle_deg -= 0.3 * dx;
  orbit_.height_offset_m = std::clamp(orbit_.height_offset_m + 0.005 * dy, -1.5, 2.5);
}

void PlaybackState::OnZoom(double steps) {
  orbit_.distance_scale = std::clamp(orbit_.distance_scale * std::pow(0.9, steps), 0.3, 4.0);
}

void PlaybackState::Advance(double seconds, double frame_rate_hz) {
  if (!playing_) return;
  position_ += seconds * frame_rate_hz * speed_;
  position_ = std::fmod(position_, frame_count_);
}

int PlaybackState::frame() const { return static_cast<int>(position_) % frame_count_; }

void PlaybackState::Step(int delta) {
  playing_ = false;
  position_ = std::fmod(std::floor(position_) + delta + frame_count_, frame_count_);
}

}  // namespace reenact::viewer

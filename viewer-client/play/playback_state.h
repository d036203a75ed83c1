#pragma once
// The interactive players' playback state (window_player.h, ar_window_player.h): the clip
// position advanced by wall time times the speed, paused or playing, scrubbed a frame at a
// time, the presentation toggles and the orbit camera, driven by the window's commands
// (render/window.h).
//
// position (clip frames, in [0, frame_count)) += seconds * frame_rate_hz * speed while
// playing; speed in [1/8, 8], halved and doubled by the - and + keys; a step pauses and moves
// to the previous or next whole frame, wrapping around.

#include "viewer-client/play/orbit_camera.h"
#include "viewer-client/render/window.h"

namespace reenact::viewer {

class PlaybackState : public WindowListener {
 public:
  // frame_count >= 1 (CheckError otherwise).
  PlaybackState(int frame_count, const OrbitCameraOptions& orbit, bool textured,
                bool draw_skeleton);

  void OnCommand(ViewerCommand c) override;
  // Drag: turns the orbit camera (0.3 degrees per pixel) and raises it (5 mm per pixel).
  void OnOrbit(double dx, double dy) override;
  // Wheel: distance times 0.9 per step towards the subject, within [0.3, 4] times the sensor's.
  void OnZoom(double steps) override;

  void Advance(double seconds, double frame_rate_hz);
  int frame() const;
  const OrbitCameraOptions& orbit() const { return orbit_; }
  bool playing() const { return playing_; }
  double speed() const { return speed_; }
  bool textured() const { return textured_; }
  bool skeleton() const { return skeleton_; }
  bool quit() const { return quit_; }

 private:
  void Step(int delta);
  int frame_count_;
  OrbitCameraOptions orbit_;
  bool textured_, skeleton_;
  bool playing_ = true, quit_ = false;
  double speed_ = 1, position_ = 0;
};

}  // namespace reenact::viewer

#include "viewer-client/play/window_player.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "viewer-client/play/texture_cache.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/window.h"

namespace reenact::viewer {
namespace {

class PlaybackState : public WindowListener {
 public:
  PlaybackState(int frame_count, const HeadlessPlayOptions& options)
      : frame_count_(frame_count),
        orbit_(options.orbit),
        textured_(options.textured),
        skeleton_(options.draw_skeleton) {}

  void OnCommand(ViewerCommand c) override {
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
  void OnOrbit(double dx, double dy) override {
    orbit_.angle_deg -= 0.3 * dx;
    orbit_.height_offset_m = std::clamp(orbit_.height_offset_m + 0.005 * dy, -1.5, 2.5);
  }
  void OnZoom(double steps) override {
    orbit_.distance_scale = std::clamp(orbit_.distance_scale * std::pow(0.9, steps), 0.3, 4.0);
  }

  void Advance(double seconds, double frame_rate_hz) {
    if (!playing_) return;
    position_ += seconds * frame_rate_hz * speed_;
    position_ = std::fmod(position_, frame_count_);
  }
  int frame() const { return static_cast<int>(position_) % frame_count_; }
  const OrbitCameraOptions& orbit() const { return orbit_; }
  bool textured() const { return textured_; }
  bool skeleton() const { return skeleton_; }
  bool quit() const { return quit_; }

 private:
  void Step(int delta) {
    playing_ = false;
    position_ = std::fmod(std::floor(position_) + delta + frame_count_, frame_count_);
  }
  int frame_count_;
  OrbitCameraOptions orbit_;
  bool textured_, skeleton_;
  bool playing_ = true, quit_ = false;
  double speed_ = 1, position_ = 0;
};

}  // namespace

Status PlayInWindow(const Reenactment& reenactment, const HeadlessPlayOptions& options) {
  WindowOptions window_options;
  window_options.render_width = options.width;
  window_options.render_height = options.height;
  window_options.title = "reenact - " + reenactment.manifest().title;
  auto window = Window::Create(window_options);
  if (!window.ok())
    return MakeError(window.error().code,
                     window.error().message + " (use --headless --out DIR without a display)");
  Renderer& renderer = window->renderer();
  const PinholeCamera camera =
      ScaledViewerCamera(reenactment.manifest().color_camera, options.width, options.height);
  TextureCache texture_for_frame(renderer, reenactment);

  PlaybackState state(reenactment.frame_count(), options);
  auto last = std::chrono::steady_clock::now();
  while (!window->ShouldClose() && !state.quit()) {
    window->PollEvents(state);
    const auto now = std::chrono::steady_clock::now();
    state.Advance(std::chrono::duration<double>(now - last).count(),
                  reenactment.manifest().frame_rate_hz);
    last = now;
    const auto view = OrbitViewFor(reenactment, state.orbit());
    if (!view) return MakeError("degenerate", "cannot place the orbit camera");
    ReenactedFrame rf = reenactment.Build(state.frame(), camera, view->viewer_from_world,
                                          std::ref(texture_for_frame));
    rf.draw.floor = view->floor;
    rf.draw.textured = state.textured();
    if (!state.skeleton()) rf.draw.bones.clear();
    renderer.Draw(rf.draw);
    window->Present();
  }
  return {};
}

}  // namespace reenact::viewer

#include "viewer-client/play/window_player.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include "viewer-client/play/playback_state.h"
#include "viewer-client/play/texture_cache.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/window.h"

namespace reenact::viewer {

Status PlayInWindow(const Reenactment& reenactment, const HeadlessPlayOptions& options) {
  if (reenactment.frame_count() < 1)
    return MakeError("invalid_argument", "the clip has no frames to reenact");
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

  PlaybackState state(reenactment.frame_count(), options.orbit, options.textured,
                      options.draw_skeleton);
  auto last = std::chrono::steady_clock::now();
  PartSelectionHistory history;
  while (!window->ShouldClose() && !state.quit()) {
    window->PollEvents(state);
    const auto now = std::chrono::steady_clock::now();
    state.Advance(std::chrono::duration<double>(now - last).count(),
                  reenactment.manifest().frame_rate_hz);
    last = now;
    const auto view = OrbitViewFor(reenactment, state.orbit());
    if (!view) return MakeError("degenerate", "cannot place the orbit camera");
    ReenactedFrame rf = reenactment.Build(state.frame(), camera, view->viewer_from_world,
                                          std::ref(texture_for_frame), &history);
    rf.draw.floor = view->floor;
    rf.draw.textured = state.textured();
    if (!state.skeleton()) rf.draw.bones.clear();
    renderer.Draw(rf.draw);
    window->Present();
  }
  return {};
}

}  // namespace reenact::viewer

#include "viewer-client/play/ar_window_player.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <thread>

#include "common/error/check.h"
#include "viewer-client/play/ar_pipeline.h"
#include "viewer-client/play/playback_state.h"
#include "viewer-client/render/window.h"

namespace reenact::viewer {

void ArWindowOptions::Check() const {
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(window_width > 0 && window_height > 0, "window size must be positive");
  frame.Check();
}

Expected<ArPlaySummary> PlayArInWindow(const Reenactment& reenactment, proto::ClipMap map,
                                       CameraSource& camera, const ArWindowOptions& options) {
  options.Check();
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const PinholeCamera& intrinsics = camera.camera();
  WindowOptions window_options;
  window_options.width = options.window_width;
  window_options.height = options.window_height;
  window_options.render_width = intrinsics.width;
  window_options.render_height = intrinsics.height;
  window_options.title = options.title;
  auto window = Window::Create(window_options);
  if (!window.ok()) return window.error();  // "no_display" says to use --headless
  Renderer& renderer = window->renderer();
  auto compositor =
      ArCompositor::Create(reenactment, std::move(map), intrinsics, renderer, options.frame);
  if (!compositor.ok()) return compositor.error();

  PlaybackState state(reenactment.frame_count(), OrbitCameraOptions{}, options.frame.textured,
                      options.frame.draw_skeleton);
  ArSummaryBuilder builder;
  std::optional<double> first_timestamp_s;
  Clock::time_point first_shown;
  auto last = Clock::now();
  ArPipeline pipeline(*compositor, CameraFrames(camera, options.max_frames));
  while (!window->ShouldClose() && !state.quit()) {
    window->PollEvents(state);
    const auto now = Clock::now();
    state.Advance(std::chrono::duration<double>(now - last).count(),
                  reenactment.manifest().frame_rate_hz);
    last = now;
    compositor->SetPresentation(state.textured(), state.skeleton());
    auto next = pipeline.Next(state.frame());
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const std::optional<ArFrame>& out = *next;
    // Shown no earlier than its timestamp says, counted from the first frame's showing.
    if (!first_timestamp_s) {
      first_timestamp_s = out->timestamp_s;
      first_shown = Clock::now();
    } else {
      std::this_thread::sleep_until(
          first_shown + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                            std::max(0.0, out->timestamp_s - *first_timestamp_s))));
    }

    // The composite (camera image, reenactment, banner) as the window's picture.
    FrameDraw show;
    show.camera = compositor->render_camera();
    show.background = &out->out.color;
    renderer.Draw(show);
    window->Present();

    builder.Add(*out);
  }
  ArPlaySummary summary = builder.summary();
  if (summary.frames == 0 && !state.quit() && !window->ShouldClose())
    return MakeError("empty", "camera " + camera.description() +
                                  " delivered no frames: check the path, the sequence's rgb.txt "
                                  "or that the camera is not in use by another program");
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace reenact::viewer

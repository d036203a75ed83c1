#pragma once
// An on-screen window for `reenact-viewer play` (GLFW 3.3, OpenGL 3.3 core) that owns a
// Renderer drawing in the window's context: the same code as headless rendering, with the
// offscreen frame blitted (letterboxed) to the window. Keys and mouse reach the player as
// commands and deltas through WindowListener. Without a display (no X11/Wayland server),
// Create returns an Error instead of crashing.
//
// Keys: space play/pause, left/right scrub one frame (repeats while held), +/- (also keypad)
// speed, s skeleton overlay, c bare cylinders, t texture on/off, Escape or q quit.
// Mouse: drag with the left button to orbit, scroll to zoom.

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "common/error/expected.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

enum class ViewerCommand {
  kTogglePlay,
  kStepBackward,
  kStepForward,
  kFaster,
  kSlower,
  kToggleSkeleton,
  kToggleBareCylinders,
  kToggleTexture,
  kQuit,
};

// The command a GLFW key code (GLFW_KEY_*) stands for, if any. Pure; testable without a
// display.
std::optional<ViewerCommand> CommandForKey(int glfw_key);

// Receives input from Window::PollEvents on the calling thread.
class WindowListener {
 public:
  virtual ~WindowListener() = default;
  virtual void OnCommand(ViewerCommand command) = 0;
  // Cursor motion in window pixels while the left button is held (x right, y down).
  virtual void OnOrbit(double dx_pixels, double dy_pixels) = 0;
  // Scroll steps: positive when the wheel turns away from the user (zoom in).
  virtual void OnZoom(double steps) = 0;
};

struct WindowOptions {
  int width = 1280;                 // initial window size in screen units, > 0
  int height = 720;                 // > 0
  std::string title = "reenact";    // window title
  bool vsync = true;                // swap interval 1 (true) or 0
  int render_width = 640;           // initial offscreen render size, pixels, > 0 (the
  int render_height = 480;          // renderer follows each FrameDraw's camera anyway)
  // Throws CheckError on a non-positive size.
  void Check() const;
};

// Move-only. Use from the thread that created it (GLFW wants the main thread).
class Window {
 public:
  // Errors: "no_display" when GLFW cannot initialise (no display server) or cannot open a
  // window with a 3.3 core context; "gl_unavailable" / "gl_shader" from the renderer.
  static Expected<Window> Create(const WindowOptions& options);

  Window(Window&&) noexcept;
  Window& operator=(Window&&) noexcept;
  ~Window();

  // The renderer drawing in this window's context (made current by every Window call).
  Renderer& renderer();

  bool ShouldClose() const;
  void RequestClose();
  // Processes pending window events, delivering them to `listener`.
  void PollEvents(WindowListener& listener);
  // Blits the renderer's last Draw to the window and swaps buffers.
  void Present();
  // Framebuffer size in pixels (may differ from the window size on high-DPI screens).
  std::pair<int, int> framebuffer_size() const;

 private:
  struct State;
  Window(std::unique_ptr<State> state, Renderer renderer);
  std::unique_ptr<State> state_;     // declared first: destroyed after the renderer
  std::optional<Renderer> renderer_;
};

}  // namespace reenact::viewer
